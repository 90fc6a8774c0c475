// Issue 15's output faults: a full disk (a file-size limit), outputs that would overwrite the
// input, empty names, a folder holding another run, overlay names and codecs, exit codes.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/atomic_write.h"
#include "io/overlay.h"
#include "io/video_decoder.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {
namespace fs = std::filesystem;

class OutputFaults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    clip_ = new test::TempDir;
    const auto run = test::runCli("synth -o " + (*clip_ / "clip") + " --frames 12 --size 160x120");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { delete clip_; }
  static std::string frames() { return *clip_ / "clip/frames"; }
  static test::TempDir* clip_;
  test::TempDir dir_;
};
test::TempDir* OutputFaults::clip_ = nullptr;

// Every line of a JSON Lines file parses; their count.
int wholeJsonLines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) {
    EXPECT_NO_THROW(nlohmann::json::parse(line)) << "line " << lines << ": " << line;
    ++lines;
  }
  std::ifstream tail(path, std::ios::ate | std::ios::binary);
  EXPECT_TRUE(fs::file_size(path) == 0 || (tail.seekg(-1, std::ios::end), tail.get() == '\n'));
  return lines;
}

bool anyPartFile(const std::string& folder) {
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.path().string().find(".part") != std::string::npos) return true;
  }
  return false;
}

// On two threads the files are written behind, on a thread of their own: the same outcome.
TEST_F(OutputFaults, FullDiskForStatsStopsWithWholeLinesUnderTheFinalName) {
  for (const std::string threads : {"1", "2"}) {
    const std::string stats = dir_ / threads + "/stats.jsonl", out = dir_ / threads + "/out";
    fs::create_directories(dir_ / threads);
    const test::CommandResult r =
        test::runCliWithFileLimit(3000, "segment " + frames() + " -o " + out + " --stats " + stats +
                                            " -q --threads " + threads);
    test::expectOneLineError(r, "stats.jsonl", test::kExitRunFailed);
    ASSERT_TRUE(fs::exists(stats));
    const int lines = wholeJsonLines(stats);
    EXPECT_GT(lines, 0);
    EXPECT_LT(lines, 12);
    EXPECT_FALSE(anyPartFile(dir_.path()));
    const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(out + "/movseg-run.json"));
    EXPECT_FALSE(manifest.at("finished").get<bool>());
  }
}

// Debug pictures are the largest images a run writes: the first one passes the limit.
TEST_F(OutputFaults, FullDiskForPicturesStops) {
  for (const std::string threads : {"1", "2"}) {
    const std::string out = dir_ / threads;
    const test::CommandResult r =
        test::runCliWithFileLimit(3000, "segment " + frames() + " -o " + out +
                                            " --method paper --debug -q --threads " + threads);
    test::expectOneLineError(r, ".png", test::kExitRunFailed);
    EXPECT_TRUE(fs::exists(out + "/00000.png"));
    EXPECT_FALSE(fs::exists(out + "/00002.png"));
    EXPECT_FALSE(anyPartFile(dir_.path()));
  }
}

TEST_F(OutputFaults, FullDiskForAnOverlayVideoLeavesNoUnplayableFile) {
  const test::CommandResult r = test::runCliWithFileLimit(
      8000, "segment " + frames() + " -o " + dir_ / "out" + " --overlay " + dir_ / "o.mp4" + " -q");
  test::expectOneLineError(r, "o.mp4", test::kExitRunFailed);
  EXPECT_FALSE(fs::exists(dir_ / "o.mp4"));
  EXPECT_FALSE(anyPartFile(dir_.path()));
  EXPECT_TRUE(fs::exists(dir_ / "out/00011.png"));  // the masks are complete
}

TEST_F(OutputFaults, AnOverlayVideoPlaysWithEveryFrameInH264AtTheInputsRate) {
  const std::string video = dir_ / "x.MP4";  // the extension in any case
  ASSERT_TRUE(test::ffmpeg("-framerate 12 -i " + frames() +
                           "/%05d.png -c:v libx264 -pix_fmt yuv420p " + dir_ / "in.mp4"));
  const test::CommandResult r = test::runCli("segment " + dir_ / "in.mp4" + " -o " + dir_ / "out" +
                                             " --overlay " + video + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const VideoDecoder overlay(video, {});
  EXPECT_EQ(overlay.expectedFrames(), 12);
  EXPECT_DOUBLE_EQ(overlay.fps(), 12.0);
  EXPECT_EQ(
      test::runShell("ffprobe -v error -show_streams " + video + " | grep -q codec_name=h264"), 0);
}

TEST_F(OutputFaults, UnknownOverlayExtensionIsRefused) {
  test::expectOneLineError(
      test::runCli("segment " + frames() + " -o " + dir_ / "out" + " --overlay " + dir_ / "x.gif"),
      "x.gif", test::kExitUsage);
  EXPECT_FALSE(fs::exists(dir_ / "x.gif"));
}

// `paper` labels its features (`dense` has none to show): without them the overlay is the frame
// with its mask drawn and nothing else; with them, dots on some hundred pixels more. The rows of
// the frames-per-second line at the top differ from run to run, so only the rows below it count.
TEST_F(OutputFaults, FeatureDotsCanBeHidden) {
  for (const std::string run : {"dots", "plain"}) {
    const std::string hide = run == "plain" ? " --no-feature-dots" : "";
    ASSERT_EQ(test::runCli("segment " + frames() + " -o " + dir_ / run +
                           " --method paper --overlay -q" + hide)
                  .exit_code,
              0);
  }
  const cv::Mat dots = cv::imread(dir_ / "dots/overlay/00003.png");
  const cv::Mat plain = cv::imread(dir_ / "plain/overlay/00003.png");
  Result masked;
  masked.mask = cv::imread(dir_ / "plain/00003.png", cv::IMREAD_GRAYSCALE);
  ASSERT_GT(cv::countNonZero(masked.mask), 0);
  const cv::Mat expected = drawOverlay(cv::imread(frames() + "/00003.png"), masked, "", false);
  ASSERT_EQ(dots.size(), expected.size());
  ASSERT_EQ(plain.size(), expected.size());
  const cv::Range below_the_hud(40, dots.rows);
  EXPECT_EQ(cv::norm(plain.rowRange(below_the_hud), expected.rowRange(below_the_hud), cv::NORM_INF),
            0);
  std::vector<cv::Mat> channels;
  cv::split(dots.rowRange(below_the_hud) != plain.rowRange(below_the_hud), channels);
  EXPECT_GT(cv::countNonZero(channels[0] | channels[1] | channels[2]), 100);  // pixels with dots
}

TEST_F(OutputFaults, OutputsInsideTheInputAreRefused) {
  ASSERT_TRUE(test::ffmpeg("-i " + frames() + "/%05d.png -c:v libx264 -pix_fmt yuv420p " +
                           dir_ / "in.mp4"));
  const std::string video = dir_ / "in.mp4";
  const auto size = fs::file_size(video);
  const std::pair<std::string, std::string> cases[] = {
      {"segment " + frames() + " -o " + frames(), "-o"},
      {"segment " + frames() + " -o " + frames() + "/masks", "-o"},
      {"segment " + frames() + "/ -o " + frames() + "/./masks/", "-o"},
      {"segment " + (*clip_ / "clip") + " -o " + frames(),
       "-o"},  // a sequence folder reads frames/
      {"segment " + video + " -o " + dir_ / "out" + " --overlay " + video, "--overlay"},
      {"segment " + video + " -o " + dir_ / "out" + " --stats " + video, "--stats"},
      {"segment " + frames() + "/%05d.png -o " + frames(), "-o"},
      {"segment " + frames() + " -o ''", "empty"},
      {"segment " + frames() + " -o " + dir_ / "out" + " --stats ''", "empty"},
      {"bench " + (*clip_ / "clip") + " --methods diff --json " + frames() + "/t.json", "--json"},
      {"bench " + (*clip_ / "clip") + " --methods diff --html " + frames() + "/t.html", "--html"},
      // The image of --ignore is an input too.
      {"segment " + frames() + " -o " + dir_ / "out" + " --ignore " + dir_ / "ignore.png" +
           " --stats " + dir_ / "ignore.png",
       "--stats"},
  };
  fs::copy_file(frames() + "/00001.png", dir_ / "ignore.png");
  for (const auto& [arguments, named] : cases) {
    SCOPED_TRACE(arguments);
    test::expectOneLineError(test::runCli(arguments), named, test::kExitUsage);
  }
  EXPECT_EQ(fs::file_size(video), size);
  EXPECT_FALSE(cv::imread(dir_ / "ignore.png").empty());
  EXPECT_EQ(test::filesIn(frames()).size(), 12u);
  EXPECT_FALSE(fs::exists(dir_ / "out/00000.png"));
}

// Outputs that would replace one another, or the run's own files (its masks, its manifest), are
// refused before the work, as outputs inside the input are; a stats file beside the masks is not.
TEST_F(OutputFaults, OutputsThatWouldReplaceEachOtherOrTheRunsFilesAreRefused) {
  const std::string out = dir_ / "out", masks = *clip_ / "clip/masks", data = *clip_ / "clip";
  fs::copy(frames(), dir_ / "other");
  const std::string two_inputs = "segment " + frames() + " " + dir_ / "other" + " -o " + out;
  const std::pair<std::string, std::string> cases[] = {
      {"segment " + frames() + " -o " + out + " --overlay " + out, "would overwrite the masks"},
      {"segment " + frames() + " -o " + out + " --overlay " + out + "/",
       "would overwrite the masks"},
      {"segment " + frames() + " -o " + out + " --stats " + out + "/movseg-run.json", "--stats"},
      {"segment " + frames() + " -o " + out + " --stats " + out + "/00003.png", "--stats"},
      {"segment " + frames() + " -o " + out + " --overlay " + dir_ / "a.mp4" + " --stats " +
           dir_ / "a.mp4",
       "--stats and --overlay both name"},
      {two_inputs + " --overlay .", "a file name written in each input's folder"},
      {two_inputs + " --overlay ..", "a file name written in each input's folder"},
      {"eval " + masks + " " + masks + " --json " + dir_ / "r" + " --csv " + dir_ / "r",
       "both name"},
      {"eval " + masks + " " + masks + " --json " + dir_ / "r" + " --html " + dir_ / "./r",
       "both name"},
      {"bench " + data + " --methods diff --json " + dir_ / "r" + " --html " + dir_ / "r",
       "both name"},
      {"bench " + data + " --methods diff,diff --threads 2", "'diff' is named twice"},
  };
  for (const auto& [arguments, named] : cases) {
    SCOPED_TRACE(arguments);
    test::expectOneLineError(test::runCli(arguments), named, test::kExitUsage);
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir_ / "r"));

  const test::CommandResult beside =
      test::runCli("segment " + frames() + " -o " + out + " --stats " + out + "/stats.jsonl -q");
  ASSERT_EQ(beside.exit_code, 0) << beside.output;
  EXPECT_EQ(wholeJsonLines(out + "/stats.jsonl"), 12);
  EXPECT_EQ(test::filesIn(out).size(), 14u);  // 12 masks, the manifest, the stats
}

// An output named with all the 255 bytes a file name may have is written: its temporary name
// (NAME.part) is cut to fit, not refused as too long.
TEST_F(OutputFaults, OutputsWithTheLongestLegalNamesAreWritten) {
  const std::string stats = dir_ / (std::string(250, 's') + ".json");
  const std::string overlay = dir_ / (std::string(251, 'v') + ".mp4");
  const test::CommandResult r = test::runCli("segment " + frames() + " -o " + dir_ / "out" +
                                             " -q --stats " + stats + " --overlay " + overlay);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(wholeJsonLines(stats), 12);
  EXPECT_GT(fs::file_size(overlay), 0u);
  EXPECT_FALSE(anyPartFile(dir_.path()));
}

// TMPDIR for the commands run while it lives, as it was after.
class TemporaryFolderSetTo {
 public:
  explicit TemporaryFolderSetTo(const std::string& folder) {
    const char* was = std::getenv("TMPDIR");
    if (was != nullptr) previous_ = was;
    ::setenv("TMPDIR", folder.c_str(), 1);
  }
  ~TemporaryFolderSetTo() {
    if (previous_) {
      ::setenv("TMPDIR", previous_->c_str(), 1);
    } else {
      ::unsetenv("TMPDIR");
    }
  }

 private:
  std::optional<std::string> previous_;
};

// The folder for temporary files is asked for only by the commands that write there: a TMPDIR
// that does not exist fails those in one line, and the others run.
TEST_F(OutputFaults, AMissingTemporaryFolderFailsOnlyTheCommandsThatWriteThere) {
  test::CommandResult version, synth, demo, bench;
  {
    const TemporaryFolderSetTo missing(dir_ / "missing");
    version = test::runCli("--version");
    synth = test::runCli("synth -o " + dir_ / "s" + " --frames 2");
    demo = test::runCli("demo --frames 2");
    bench = test::runCli("bench " + (*clip_ / "clip") + " --methods diff");
  }
  EXPECT_EQ(version.exit_code, 0) << version.output;
  EXPECT_EQ(synth.exit_code, 0) << synth.output;
  test::expectOneLineError(demo, "no folder for temporary files: TMPDIR '" + dir_ / "missing",
                           test::kExitRunFailed);
  test::expectOneLineError(bench, "no folder for temporary files", test::kExitRunFailed);
}

// demo's default folder, which each run replaces, is a name anyone may take in a shared /tmp:
// a link there is refused, and what it points to is left as it was.
TEST_F(OutputFaults, ADemoFolderThatIsALinkIsRefused) {
  fs::create_directories(dir_ / "tmp");
  fs::create_directories(dir_ / "victim/frames");
  { std::ofstream(dir_ / "victim/camera.jsonl") << "keep\n"; }
  fs::create_directory_symlink(dir_ / "victim", dir_ / "tmp/movseg-demo");
  test::CommandResult demo;
  {
    const TemporaryFolderSetTo tmp(dir_ / "tmp");
    demo = test::runCli("demo --frames 2");
  }
  test::expectOneLineError(demo, "is a link, a file or another user's folder",
                           test::kExitRunFailed);
  EXPECT_EQ(test::filesIn(dir_ / "victim"), (std::vector<std::string>{"camera.jsonl", "frames"}));
  EXPECT_TRUE(fs::is_empty(dir_ / "victim/frames"));
}

// Without -o, demo writes to movseg-demo in the folder for temporary files and replaces it on
// every run (README; `make run` runs it so): a second, shorter run leaves no frame of the first.
TEST_F(OutputFaults, TheDemosDefaultFolderIsReplacedOnEveryRun) {
  fs::create_directories(dir_ / "tmp");
  const TemporaryFolderSetTo tmp(dir_ / "tmp");
  const test::CommandResult first = test::runCli("demo --frames 3");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find(dir_ / "tmp/movseg-demo"), std::string::npos) << first.output;
  ASSERT_TRUE(fs::exists(dir_ / "tmp/movseg-demo/frames/00002.png"));
  const test::CommandResult second = test::runCli("demo --frames 2");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_EQ(test::filesIn(dir_ / "tmp/movseg-demo/frames"),
            (std::vector<std::string>{"00000.png", "00001.png"}));
  EXPECT_EQ(test::filesIn(dir_ / "tmp/movseg-demo/segmented").size(), 3u);  // and the manifest
}

// Empty names are refused by every command, not taken as "none" or as the filesystem's root.
TEST_F(OutputFaults, EmptyOutputNamesAreRefused) {
  const std::string masks = *clip_ / "clip/masks";
  const std::string cases[] = {
      "synth -o '' --frames 2",
      "demo -o '' --frames 2",
      "eval " + masks + " " + masks + " --json ''",
      "eval " + masks + " " + masks + " --csv ''",
      "bench " + (*clip_ / "clip") + " --json ''",
      "bench " + (*clip_ / "clip") + " --ignore ''",
      "segment " + frames() + " -o " + dir_ / "out" + " --ignore ''",
  };
  for (const std::string& arguments : cases) {
    SCOPED_TRACE(arguments);
    test::expectOneLineError(test::runCli(arguments), "empty", test::kExitUsage);
  }
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// eval's reports stay out of PRED and GT, as segment's outputs stay out of its input.
TEST_F(OutputFaults, EvalRefusesToWriteIntoItsInputs) {
  const std::string masks = *clip_ / "clip/masks", mask = masks + "/00000.png";
  const auto size = fs::file_size(mask);
  for (const std::string option : {"--json", "--csv", "--html"}) {
    SCOPED_TRACE(option);
    test::expectOneLineError(
        test::runCli("eval " + masks + " " + (*clip_ / "clip") + " " + option + " " + mask),
        "would write into the input", test::kExitUsage);
    test::expectOneLineError(
        test::runCli("eval " + frames() + " " + masks + " " + option + " " + frames() + "/report"),
        "would write into the input", test::kExitUsage);
  }
  EXPECT_EQ(fs::file_size(mask), size);
}

// An output path that cannot be written is found before the work, not after it.
TEST_F(OutputFaults, UnwritableReportPathsFailBeforeTheWork) {
  fs::create_directories(dir_ / "a-folder");
  { std::ofstream(dir_ / "a-file") << "x"; }
  const std::string masks = *clip_ / "clip/masks";
  const test::CommandResult stats =
      test::runCli("segment " + frames() + " -o " + dir_ / "out" + " --stats " + dir_ / "a-folder");
  test::expectOneLineError(stats, "a-folder", test::kExitRunFailed);
  // Refused before any work: no mask, and not even the output folder the run would have made.
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  // An overlay video in a folder that does not exist: refused before the first mask too (its
  // writer opens at the first frame), the output folder and its new parent removed again.
  const test::CommandResult video = test::runCli("segment " + frames() + " -o " + dir_ / "new/out" +
                                                 " --overlay " + dir_ / "missing/overlay.mkv");
  test::expectOneLineError(video, "missing/overlay.mkv", test::kExitRunFailed);
  EXPECT_FALSE(fs::exists(dir_ / "new"));
  // The same with the stats file inside the new folder and a trailing separator: nothing left.
  const test::CommandResult inside =
      test::runCli("segment " + frames() + " -o " + dir_ / "new/out/" + " --stats " +
                   dir_ / "new/out/stats.jsonl --overlay " + dir_ / "missing/overlay.mkv");
  test::expectOneLineError(inside, "missing/overlay.mkv", test::kExitRunFailed);
  EXPECT_FALSE(fs::exists(dir_ / "new"));
  // With --overwrite, an earlier run's outputs stay when this run cannot write its own.
  ASSERT_EQ(test::runCli("segment " + frames() + " -q -o " + dir_ / "earlier").exit_code, 0);
  const auto earlier = test::filesIn(dir_ / "earlier");
  ASSERT_FALSE(earlier.empty());
  test::expectOneLineError(test::runCli("segment " + frames() + " -o " + dir_ / "earlier" +
                                        " --overwrite --overlay " + dir_ / "missing/overlay.mkv"),
                           "missing/overlay.mkv", test::kExitRunFailed);
  EXPECT_EQ(test::filesIn(dir_ / "earlier"), earlier);
  for (const std::string& report : {dir_ / "a-folder", dir_ / "a-file/x.json"}) {
    SCOPED_TRACE(report);
    // eval prints its table, bench its table and progress, only once they have done the work.
    test::expectOneLineError(test::runCli("eval " + masks + " " + masks + " --json " + report),
                             report, test::kExitRunFailed);
    test::expectOneLineError(test::runCli("eval " + masks + " " + masks + " --html " + report),
                             report, test::kExitRunFailed);
    test::expectOneLineError(
        test::runCli("bench " + (*clip_ / "clip") + " --methods diff --json " + report), report,
        test::kExitRunFailed);
    test::expectOneLineError(
        test::runCli("bench " + (*clip_ / "clip") + " --methods diff --html " + report), report,
        test::kExitRunFailed);
  }
  EXPECT_TRUE(fs::is_directory(dir_ / "a-folder"));
  EXPECT_TRUE(fs::is_empty(dir_ / "a-folder"));
}

// Reads a FIFO on a thread of its own until its writer closes it: what a `cat fifo` would get.
class FifoReader {
 public:
  explicit FifoReader(const std::string& path)
      // Opened without waiting for a writer; the CLI, which will not wait for a reader, finds one.
      : fd_(::open(path.c_str(), O_RDONLY | O_NONBLOCK)), thread_([this] { readAll(); }) {}
  ~FifoReader() {
    if (thread_.joinable()) thread_.join();
    if (fd_ >= 0) ::close(fd_);
  }
  // Everything written, once the writer has closed the FIFO.
  std::string text() {
    thread_.join();
    return text_;
  }

 private:
  // Until the writer hangs up (poll reports no hang-up before a writer came), at most 30 s.
  void readAll() {
    pollfd watch{fd_, POLLIN, 0};
    while (::poll(&watch, 1, 30000) > 0) {
      char buffer[4096];
      const ssize_t n = ::read(fd_, buffer, sizeof buffer);
      if (n > 0) text_.append(buffer, static_cast<size_t>(n));
      if (n <= 0 && (watch.revents & POLLHUP) != 0) return;
    }
  }

  int fd_;
  std::string text_;
  std::thread thread_;
};

// A FIFO, a device and a symlink stay what they are: the FIFO and the device get the bytes, the
// symlink's target is replaced.
TEST_F(OutputFaults, AFifoOrASymlinkAsOutputIsWrittenThroughNotReplaced) {
  const std::string fifo = dir_ / "stats.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  {
    FifoReader reader(fifo);
    const test::CommandResult r =
        test::runCli("segment " + frames() + " -o " + dir_ / "out" + " -q --stats " + fifo);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::istringstream lines(reader.text());
    std::string line;
    int count = 0;
    while (std::getline(lines, line)) EXPECT_EQ(nlohmann::json::parse(line).at("frame"), count++);
    EXPECT_EQ(count, 12);
  }
  // Without a reader: one line at once, not a wait for one.
  test::expectOneLineError(
      test::runCli("segment " + frames() + " -o " + dir_ / "out2" + " -q --stats " + fifo),
      "no process reads the FIFO", test::kExitRunFailed);
  EXPECT_FALSE(fs::exists(dir_ / "out2/00000.png"));
  struct stat info {};
  ASSERT_EQ(lstat(fifo.c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode));

  fs::create_directories(dir_ / "reports");
  fs::create_symlink("reports/scores.json", dir_ / "link.json");  // relative, as ln -s makes it
  const test::CommandResult r =
      test::runCli("eval " + (*clip_ / "clip/masks") + " " + (*clip_ / "clip/masks") + " --json " +
                   dir_ / "link.json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.json"));
  // The masks scored against themselves.
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir_ / "reports/scores.json")).at("mean").at("J"),
            1.0);
  EXPECT_FALSE(anyPartFile(dir_.path()));
}

// A device as every kind of output (a text file grown line by line, a JSON file, a mask): written
// in place, the node itself left as it was. The device is a node of the test's own with
// /dev/null's numbers, so that a regression replaces nothing anyone else uses.
TEST_F(OutputFaults, ADeviceAsOutputIsWrittenInPlaceNotReplaced) {
  const std::string device = dir_ / "null.png";  // a mask is encoded by its extension
  if (mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    GTEST_SKIP() << "cannot make a device node here: " << std::strerror(errno);
  }
  const auto expectTheSameDevice = [&] {
    struct stat info {};
    ASSERT_EQ(lstat(device.c_str(), &info), 0);
    EXPECT_TRUE(S_ISCHR(info.st_mode));
    EXPECT_EQ(info.st_rdev, makedev(1, 3));
  };
  const test::CommandResult stats =
      test::runCli("segment " + frames() + " -o " + dir_ / "out" + " -q --stats " + device);
  EXPECT_EQ(stats.exit_code, 0) << stats.output;
  EXPECT_TRUE(fs::exists(dir_ / "out/00011.png"));
  expectTheSameDevice();
  const test::CommandResult json = test::runCli("eval " + (*clip_ / "clip/masks") + " " +
                                                (*clip_ / "clip/masks") + " --json " + device);
  EXPECT_EQ(json.exit_code, 0) << json.output;
  expectTheSameDevice();
  const cv::Mat mask = cv::imread(dir_ / "out/00011.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(mask.empty());
  EXPECT_NO_THROW(writeImageAtomic(device, mask));
  expectTheSameDevice();
  EXPECT_FALSE(anyPartFile(dir_.path()));
}

// /dev/stdout names the process's own descriptor: written through it, whether it is a pipe or a
// file the shell opened, beside what the command itself prints there (it failed on a pipe; a
// file was replaced by a new one, and the command's own lines went to the old).
TEST_F(OutputFaults, StandardOutputAsAnOutputIsWrittenThroughItsDescriptor) {
  const auto countStats = [](const std::string& text) {
    std::istringstream lines(text);
    std::string line;
    int stats = 0, summaries = 0;
    while (std::getline(lines, line)) {
      if (line.rfind("segment: 12 frames", 0) == 0) {
        ++summaries;
      } else {
        EXPECT_EQ(nlohmann::json::parse(line).at("frame"), stats++);
      }
    }
    return std::make_pair(stats, summaries);
  };
  const test::CommandResult piped =
      test::runCli("segment " + frames() + " -o " + dir_ / "out" + " --stats /dev/stdout");
  ASSERT_EQ(piped.exit_code, 0) << piped.output;
  const auto [piped_stats, piped_summaries] = countStats(piped.output);
  EXPECT_EQ(piped_stats, 12) << piped.output;
  EXPECT_GE(piped_summaries, 1) << piped.output;

  const test::CommandResult redirected = test::runCli(
      "segment " + frames() + " -o " + dir_ / "out2" + " --stats /dev/stdout > " + dir_ / "log");
  ASSERT_EQ(redirected.exit_code, 0) << redirected.output;
  std::ostringstream log;
  log << std::ifstream(dir_ / "log").rdbuf();
  const auto [logged_stats, logged_summaries] = countStats(log.str());
  EXPECT_EQ(logged_stats, 12) << log.str();
  EXPECT_GE(logged_summaries, 1) << log.str();

  // eval's table, printed first, comes first in a file too: the streams are flushed before.
  const test::CommandResult report =
      test::runCli("eval " + (*clip_ / "clip/masks") + " " + (*clip_ / "clip/masks") +
                   " --json /dev/stdout > " + dir_ / "report");
  ASSERT_EQ(report.exit_code, 0) << report.output;
  std::ostringstream text;
  text << std::ifstream(dir_ / "report").rdbuf();
  const std::size_t json = text.str().find("{\n");
  EXPECT_NE(text.str().find("\"mean\": {"), std::string::npos) << text.str();
  EXPECT_LT(text.str().find("eval: "), json) << text.str();
  EXPECT_FALSE(anyPartFile(dir_.path()));
}

// A Linux file name need not be UTF-8 (Latin-1 "caf\xe9"); JSON text must be: the reports and
// the manifest name such a sequence with U+FFFD for the byte, where they failed with the JSON
// library's message.
TEST_F(OutputFaults, NamesThatAreNotUtf8AreReportedWithAReplacementCharacter) {
  const std::string data = dir_ / "data", latin1 = "caf\xe9";
  fs::create_directories(data);
  fs::create_directory_symlink(*clip_ / "clip", data + "/" + latin1);
  const test::CommandResult segment =
      test::runCli("segment '" + data + "/" + latin1 + "/frames' -o " + dir_ / "out" + " -q");
  ASSERT_EQ(segment.exit_code, 0) << segment.output;
  const test::CommandResult bench =
      test::runCli("bench " + data + " --methods diff --json " + dir_ / "bench.json");
  ASSERT_EQ(bench.exit_code, 0) << bench.output;
  const test::CommandResult eval =
      test::runCli("eval '" + data + "/" + latin1 + "/masks' '" + data + "/" + latin1 +
                   "' --json " + dir_ / "eval.json");
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  const auto read = [](const std::string& path) {
    return nlohmann::json::parse(std::ifstream(path));
  };
  EXPECT_EQ(read(dir_ / "bench.json").at("rows").at(0).at("sequence"), "caf\xef\xbf\xbd");
  EXPECT_NE(read(dir_ / "out/movseg-run.json").dump().find("caf\xef\xbf\xbd"), std::string::npos);
  EXPECT_EQ(read(dir_ / "eval.json").at("sequences").at(0).at("name"), "caf\xef\xbf\xbd");
}

// The folders of -o that a run replaces (overlay/, debug/) hold no input (with --overwrite the
// user's frames there were deleted), and with --debug no other output lies in debug/ (the
// pictures replaced an overlay there; a stats file there failed the run at its end).
TEST_F(OutputFaults, TheRunsOwnFoldersHoldNoInputAndNoOtherOutput) {
  const std::string out = dir_ / "out";
  ASSERT_EQ(test::runCli("segment " + frames() + " -o " + out + " --overlay -q").exit_code, 0);
  test::expectOneLineError(test::runCli("segment " + out + "/overlay -o " + out + " --overwrite"),
                           "which the run's own pictures replace", test::kExitUsage);
  EXPECT_EQ(test::filesIn(out + "/overlay").size(), 12u);
  for (const std::string& option : {std::string(" --overlay "), std::string(" --stats ")}) {
    test::expectOneLineError(test::runCli("segment " + frames() + " -o " + dir_ / "dbg" +
                                          " --debug" + option + dir_ / "dbg/debug/mask"),
                             "where --debug writes its pictures", test::kExitUsage);
  }
  EXPECT_FALSE(fs::exists(dir_ / "dbg/debug"));
}

// synth and demo write into a folder that holds files only when told to, and then leave no
// frame of a longer earlier sequence behind.
TEST_F(OutputFaults, SynthAndDemoReplaceAFolderThatHoldsFilesOnlyWithOverwrite) {
  const std::string synth = "synth -o " + dir_ / "seq" + " --size 64x48 --frames ";
  ASSERT_EQ(test::runCli(synth + "5").exit_code, 0);
  test::expectOneLineError(test::runCli(synth + "3"), "--overwrite", test::kExitUsage);
  EXPECT_TRUE(fs::exists(dir_ / "seq/frames/00004.png"));
  ASSERT_EQ(test::runCli(synth + "3 --overwrite").exit_code, 0);
  EXPECT_EQ(test::filesIn(dir_ / "seq/frames").size(), 3u);
  EXPECT_EQ(test::filesIn(dir_ / "seq/masks").size(), 3u);
  std::ifstream camera(dir_ / "seq/camera.jsonl");
  std::string line;
  int lines = 0;
  while (std::getline(camera, line)) ++lines;
  EXPECT_EQ(lines, 2);  // one per frame after the first

  const std::string demo = "demo -o " + dir_ / "demo" + " --frames ";
  ASSERT_EQ(test::runCli(demo + "4").exit_code, 0);
  test::expectOneLineError(test::runCli(demo + "3"), "--overwrite", test::kExitUsage);
  const test::CommandResult again = test::runCli(demo + "3 --overwrite");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  for (const char* folder : {"frames", "masks", "segmented", "overlay"}) {
    EXPECT_TRUE(fs::exists(dir_ / "demo/" + folder + "/00002.png")) << folder;
    EXPECT_FALSE(fs::exists(dir_ / "demo/" + folder + "/00003.png")) << folder;
  }
  // A folder of anything else is refused too.
  fs::create_directories(dir_ / "mine");
  { std::ofstream(dir_ / "mine/notes.txt") << "x"; }
  test::expectOneLineError(test::runCli("synth -o " + dir_ / "mine"), "not empty",
                           test::kExitUsage);
  EXPECT_FALSE(fs::exists(dir_ / "mine/frames"));
}

TEST_F(OutputFaults, ARunIntoAUsedFolderIsRefusedUnlessOverwritten) {
  const std::string run = "segment " + frames() + " -o " + dir_ / "out" + " -q";
  ASSERT_EQ(test::runCli(run).exit_code, 0);
  const nlohmann::json manifest =
      nlohmann::json::parse(std::ifstream(dir_ / "out/movseg-run.json"));
  EXPECT_EQ(manifest.at("input").get<std::string>(), frames());
  EXPECT_EQ(manifest.at("frames_done").get<int>(), 12);
  EXPECT_TRUE(manifest.at("finished").get<bool>());
  EXPECT_EQ(manifest.at("settings").at("lk_window").get<std::string>(), "11");

  test::expectOneLineError(test::runCli(run + " --max-frames 3"), "--overwrite", test::kExitUsage);
  ASSERT_EQ(test::runCli(run + " --max-frames 3 --overwrite").exit_code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "out/00002.png"));
  EXPECT_FALSE(fs::exists(dir_ / "out/00003.png"));  // the earlier run's masks are gone

  // Masks of an unknown run (no manifest, e.g. a run killed before 0.2) are not mixed either.
  fs::remove(dir_ / "out/movseg-run.json");
  test::expectOneLineError(test::runCli(run), "numbered masks", test::kExitUsage);
}

TEST_F(OutputFaults, ARunThatCouldNotStartDoesNotClaimItsFolder) {
  const std::string run = "segment " + frames() + " -o " + dir_ / "out" + " -q";
  test::expectOneLineError(test::runCli(run + " --stats " + dir_ / "no/such/folder/s.jsonl"),
                           "s.jsonl", test::kExitRunFailed);
  EXPECT_EQ(test::runCli(run).exit_code, 0);
}

TEST_F(OutputFaults, ExitCodesSayUsageOrRunFailure) {
  // Bad options and a missing input have their cases in Options.BadCliOptionsExitWithOneLine
  // and SegmentCli.MissingInput; here what those leave out.
  const std::string run = "segment " + frames() + " -o " + dir_ / "out";
  EXPECT_EQ(test::runCli(run + " --max-frames 0").exit_code, test::kExitUsage);
  EXPECT_EQ(test::runCli("segment").exit_code, test::kExitUsage);
  EXPECT_EQ(test::runCli("segment --help").exit_code, 0);
}

TEST_F(OutputFaults, AClosedStdoutIsNotADeathBySigpipe) {
  const std::string rc = dir_ / "rc";
  test::runShell("(" + std::string(MOVSEG_CLI_PATH) + " segment " + frames() + " -o " +
                 dir_ / "out" + "; echo $? > " + rc + ") | true");
  std::ifstream in(rc);
  int code = -1;
  in >> code;
  EXPECT_EQ(code, 0);
}

TEST_F(OutputFaults, AFileNameWithANewlineKeepsTheErrorOnOneLine) {
  test::expectOneLineError(test::runCli("segment '" + dir_ / "a\nb.mp4" + "' -o " + dir_ / "out"),
                           "no such file", test::kExitRunFailed);
}

}  // namespace
}  // namespace movseg
