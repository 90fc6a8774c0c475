#include "segment_run.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <deque>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "commands.h"
#include "concurrent.h"
#include "core/frame.h"
#include "core/text.h"
#include "core/worker.h"
#include "io/atomic_write.h"
#include "io/frame_source.h"
#include "io/json_text.h"
#include "io/overlay.h"
#include "io/video_decoder.h"
#include "live_window.h"
#include "movseg/fields.h"
#include "movseg/segmenter.h"
#include "movseg/stream_segmenter.h"
#include "params_options.h"
#include "progress.h"

namespace movseg::cli {
namespace fs = std::filesystem;
namespace {

// The record of the run whose outputs a folder holds: which input, with which settings, how far.
constexpr char kManifestName[] = "movseg-run.json";

std::atomic<bool> g_stop{false};
extern "C" void onSignal(int) { g_stop = true; }

// StopOnSignal's installation, shared by every scope.
std::mutex g_signal_mutex;
int g_signal_scopes = 0;
void (*g_previous_int)(int) = nullptr;
void (*g_previous_term)(int) = nullptr;

bool isVideoPath(const std::string& path) {
  const std::string ext = lowercase(fs::path(path).extension().string());
  return ext == ".mp4" || ext == ".avi" || ext == ".mkv" || ext == ".mov";
}

// ---- paths ------------------------------------------------------------------------------------

// A name the run writes in its folder: a mask, the manifest, or either's temporary name
// (temporaryPath(): "movseg-run.json.part", "00001.part.png").
bool isTheRunsFileName(std::string name) {
  const size_t mark = name.find(kTemporaryMark);
  if (mark != std::string::npos) name.erase(mark, sizeof kTemporaryMark - 1);
  return name == kManifestName || isFrameFileName(name);
}

// Refuses --stats or --overlay where the run writes its own files: the output folder (overlay
// pictures there would replace the masks), its manifest or one of its masks, and, with --debug,
// its `debug/` folder (the pictures would replace them, or the file stand in their way).
void refuseOverwritingTheRun(const SegmentOptions& options) {
  const std::string debug = (fs::path(options.output_dir) / "debug").string();
  for (const auto& [option, path] : {std::pair<const char*, std::string>{"--stats", options.stats_file},
                                     {"--overlay", options.overlay}}) {
    if (path.empty()) continue;
    if (options.debug && isSameOrInside(path, debug)) {
      throw UsageError(std::string(option) + " '" + path + "' lies in '" + debug +
                       "', where --debug writes its pictures");
    }
    const fs::path folder = fs::path(path).parent_path();
    const std::string name = fs::path(path).filename().string();
    const bool in_output_folder =
        isSamePlace(folder.empty() ? "." : folder.string(), options.output_dir);
    if (isSamePlace(path, options.output_dir) ||
        (in_output_folder && isTheRunsFileName(name))) {
      throw UsageError(oneLine(std::string(option) + " '" + path +
                               "' would overwrite the masks or the manifest in -o '" +
                               options.output_dir + "'"));
    }
  }
}

// Refuses an input (`input`, on disk `input_path`) inside the folders of -o that a run replaces
// (`overlay/`, `debug/`: with --overwrite the user's frames there were deleted).
void refuseInputInTheRunsFolders(const SegmentOptions& options, const std::string& input,
                                 const std::string& input_path) {
  if (input_path.empty()) return;
  for (const char* owned : {"overlay", "debug"}) {
    const std::string folder = (fs::path(options.output_dir) / owned).string();
    if (isSameOrInside(input_path, folder)) {
      throw UsageError("INPUT '" + input + "' lies in '" + folder +
                       "', which the run's own pictures replace");
    }
  }
}

// Refuses a sequence folder (frames/ in it) as the output folder: the masks at its top would
// be read as its frames next time (a folder of images is read before its frames/).
void refuseSequenceFolderAsOutput(const SegmentOptions& options) {
  std::error_code error;
  if (fs::is_directory(fs::path(options.output_dir) / "frames", error) &&
      fs::is_directory(options.output_dir, error)) {
    throw UsageError("-o '" + options.output_dir +
                     "' holds a sequence's frames/: its masks would be read as the frames");
  }
}

// Refuses outputs that would overwrite an input (the run's own and `other_inputs`, those of the
// same command), the run's own files or one another, and empty or unknown output names.
void checkOutputPaths(const SegmentOptions& options,
                      const std::vector<std::string>& other_inputs = {}) {
  if (options.output_dir.empty()) throw UsageError("the output folder (-o) is empty");
  std::vector<std::string> inputs = other_inputs;
  inputs.push_back(options.input);
  const std::pair<const char*, std::string> outputs[] = {
      {"-o", options.output_dir}, {"--stats", options.stats_file}, {"--overlay", options.overlay}};
  for (const std::string& input : inputs) {
    const std::string input_path = inputPath(input);
    for (const auto& [option, path] : outputs) refuseWritingIntoInput(option, path, input, input_path);
    refuseInputInTheRunsFolders(options, input, input_path);
  }
  for (const auto& [option, path] : outputs) {
    refuseWritingIntoInput(option, path, options.ignore, options.ignore);
  }
  refuseSharedOutputs({{"--stats", options.stats_file}, {"--overlay", options.overlay}});
  refuseOverwritingTheRun(options);
  refuseSequenceFolderAsOutput(options);
  const fs::path overlay(options.overlay);
  std::error_code error;
  if (!options.overlay.empty() && overlay.has_extension() && !isVideoPath(options.overlay) &&
      !fs::is_directory(overlay, error)) {
    throw UsageError("--overlay '" + options.overlay +
                     "': not a video name (.mp4, .mkv, .mov, .avi) nor a folder");
  }
}

// The region of Segmenter::setIgnoredRegion drawn as an image: white (above 127) where nothing
// moves, as the masks movseg writes; a JPEG's ringing around it stays black.
cv::Mat readIgnoredRegion(const std::string& path) {
  cv::Mat region = decodeImage(path, cv::IMREAD_GRAYSCALE);  // a frame's check, and its words
  if (region.empty()) throw std::runtime_error("--ignore: cannot decode image '" + path + "'");
  cv::threshold(region, region, 127, 255, cv::THRESH_BINARY);
  return region;
}

// ---- the run manifest -------------------------------------------------------------------------

// The manifest's record of a run: its input and every setting that changes a mask.
nlohmann::json runIdentity(const SegmentOptions& options) {
  nlohmann::json settings = cli::paramSettings(options.params);
  if (!options.resize.empty()) {
    settings["size"] = std::to_string(options.resize.width) + "x" + std::to_string(options.resize.height);
  }
  if (!options.ignore.empty()) settings["ignore"] = options.ignore;
  return {{"input", options.input}, {"settings", settings}};
}

// The nearest of `path` and its parents that exists.
fs::path existingAncestor(const std::string& path) {
  fs::path at = folderPath(path);
  std::error_code error;
  while (at.has_relative_path() && !fs::exists(at, error)) at = at.parent_path();
  return at;
}

// Removes `path` and its parents below `ancestor` (existingAncestor() before they were made), as
// long as they are empty.
void removeEmptyFoldersUpTo(const std::string& path, const fs::path& ancestor) {
  std::error_code error;
  for (fs::path at = folderPath(path); at != ancestor && at.has_relative_path();
       at = at.parent_path()) {
    if (!fs::remove(at, error)) return;  // not empty, or not there
  }
}

// The files a run writes beside its masks, tried before the run replaces anything: an earlier
// run's outputs are removed (--overwrite) only once this run can write its own. The overlay
// video itself is opened at the first frame, when its size is known.
void checkRunFiles(const SegmentOptions& options) {
  if (!options.stats_file.empty()) checkOutputFile(options.stats_file);
  if (isVideoPath(options.overlay)) checkOutputFile(options.overlay);
}

// An output folder holds the outputs of one run, described by its manifest. A folder holding
// another run's (a manifest, or numbered masks without one) is refused unless `overwrite`, which
// removes that run's masks, debug pictures and overlay frames first: runs never mix silently.
void claimOutputFolder(const SegmentOptions& options) {
  const fs::path dir(options.output_dir);
  const fs::path manifest = dir / kManifestName;
  std::vector<std::string> previous = frameFilesIn(dir.string());
  for (const std::string& overlay : frameFilesIn((dir / "overlay").string())) {
    previous.push_back(overlay);
  }
  if (previous.empty() && !fs::exists(manifest)) return;
  if (!options.overwrite) {
    throw UsageError("'" + options.output_dir + "' holds the outputs of an earlier run (" +
                     (fs::exists(manifest) ? kManifestName : "numbered masks") +
                     "); --overwrite replaces them");
  }
  for (const std::string& file : previous) fs::remove(file);
  fs::remove_all(dir / "debug");
  fs::remove(manifest);
}

class Manifest {
 public:
  explicit Manifest(const SegmentOptions& options)
      : path_((fs::path(options.output_dir) / kManifestName).string()), record_(runIdentity(options)) {
    update(0, SourceReport(), false);
  }
  // While the run goes, at most once a second: each rewrite makes a file and removes one, and
  // after every frame they cost a whole run (480 frames at 320x240) 0.2 to 0.4 s of its 3. A
  // run killed outright may so record up to a second's frames fewer than it wrote; every other
  // end of a run records them all (RunOutputs::complete).
  void progress(int frames_done, const SourceReport& source) {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_progress_) return;
    next_progress_ = now + std::chrono::seconds(1);
    update(frames_done, source, false);
  }
  void update(int frames_done, const SourceReport& source, bool finished) {
    record_["frames_done"] = frames_done;
    record_["frames_expected"] = source.expected_frames;
    record_["decode_errors"] = source.decode_errors;
    record_["finished"] = finished;
    writeTextAtomic(path_, jsonText(record_, 2) + "\n");
  }

 private:
  std::string path_;
  nlohmann::json record_;
  std::chrono::steady_clock::time_point next_progress_ =
      std::chrono::steady_clock::now() + std::chrono::seconds(1);
};

// ---- stats and overlays -----------------------------------------------------------------------

// A field's value as JSON; a camera model as its three rows.
struct ToJson {
  nlohmann::json operator()(const cv::Matx33d& m) const {
    return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
  }
  template <typename T>
  nlohmann::json operator()(const T& value) const {
    return value;
  }
};

// One line of --stats: the frame index, every field of diagnostics.def by its name, and the
// decode errors the source reported while this frame was read.
nlohmann::json statsLine(int index, const Diagnostics& d, int decode_errors) {
  nlohmann::json line{{"frame", index}};
  for (const FieldInfo& field : diagnosticFields()) {
    line[field.name] = std::visit(ToJson{}, diagnosticValue(d, field.name));
  }
  line["decode_errors"] = decode_errors;
  return line;
}

// The codec of an overlay video: H.264 where FFmpeg has an encoder for it, else MPEG-4 part 2
// (.avi: Motion JPEG, which every player of that container reads).
int overlayFourcc(const std::string& path) {
  if (lowercase(fs::path(path).extension().string()) == ".avi") {
    return cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
  }
  return cv::VideoWriter::fourcc('a', 'v', 'c', '1');
}

// Overlay frames as PNGs in a folder, or as one video written to a temporary name and renamed
// when it is complete and plays.
class OverlayWriter {
 public:
  OverlayWriter(std::string target, double fps) : target_(std::move(target)) {
    fps_ = std::isfinite(fps) && fps > 0 && fps <= 1000 ? fps : 25.0;
    if (target_.empty()) return;
    if (isVideoPath(target_)) {
      temporary_ = temporaryPath(target_, /*keep_extension=*/true);
    } else {
      makeOutputFolder(target_);
    }
  }
  void write(int index, const cv::Mat& picture) {
    if (target_.empty()) return;
    if (temporary_.empty()) {
      writeImageAtomic((fs::path(target_) / frameFileName(index)).string(), picture);
      return;
    }
    if (!video_.isOpened()) open(picture.size());
    video_.write(resizedTo(picture, size_));
    ++frames_;
  }
  // Closes the video and checks that it plays, with every frame: OpenCV's writer does not
  // report a failed write (a full disk leaves a file without its index).
  void close() {
    if (!video_.isOpened()) return;
    video_.release();
    try {
      const VideoDecoder check(temporary_, DecoderLimits());
      if (check.expectedFrames() != frames_) {
        throw std::runtime_error("it holds " + std::to_string(std::max(0, check.expectedFrames())) +
                                 " of " + std::to_string(frames_) + " frames");
      }
    } catch (const std::runtime_error& e) {
      std::remove(temporary_.c_str());
      throw std::runtime_error("cannot write overlay video '" + target_ + "': " + e.what() +
                               " (is the disk full?)");
    }
    std::error_code error;
    fs::rename(temporary_, target_, error);
    if (error) {
      std::remove(temporary_.c_str());
      throw std::runtime_error("cannot write overlay video '" + target_ + "': " + error.message());
    }
  }

 private:
  // Frames under 16 pixels a side are enlarged by a whole factor: FFmpeg's scaler, on the way
  // to Motion JPEG, wrote past its buffers for them (a 4x4 clip's .avi aborted the run).
  static cv::Size videoFrameSize(cv::Size size) {
    constexpr int kSmallestSide = 16;
    const int factor = (kSmallestSide + std::min(size.width, size.height) - 1) /
                       std::min(size.width, size.height);
    return factor > 1 ? cv::Size(size.width * factor, size.height * factor) : size;
  }

  void open(cv::Size size) {
    size_ = videoFrameSize(size);
    const int fourcc = overlayFourcc(target_);
    if (video_.open(temporary_, cv::CAP_FFMPEG, fourcc, fps_, size_)) return;
    if (fourcc == cv::VideoWriter::fourcc('a', 'v', 'c', '1') &&
        video_.open(temporary_, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps_, size_)) {
      return;
    }
    throw std::runtime_error("cannot write overlay video '" + target_ + "'");
  }

  std::string target_, temporary_;
  double fps_;
  cv::VideoWriter video_;
  cv::Size size_;
  int frames_ = 0;
};

std::string hudLine(int index, const Diagnostics& d) {
  const double ms = d.total_ms;
  char hud[64];
  std::snprintf(hud, sizeof hud, "frame %d  %.0f fps", index, ms > 0 ? 1000.0 / ms : 0.0);
  return hud;
}

void writeDebugPictures(const std::string& folder, int index, const Result& result) {
  for (const auto& [name, picture] : result.debug) {
    if (picture.empty()) continue;
    const fs::path dir = fs::path(folder) / name;
    makeOutputFolder(dir.string());
    writeImageAtomic((dir / frameFileName(index)).string(), picture);
  }
}

// Everything a run writes. finish() completes the files; when the run fails midway the
// destructor completes what it can instead, so that what was written stays under final names.
// The manifest is written last, once every output could be opened: a run that could not start
// leaves no record that would refuse the next one.
class RunOutputs {
 public:
  RunOutputs(const SegmentOptions& options, double fps)
      : options_(options),
        stats_(options.stats_file.empty() ? nullptr : std::make_unique<LineFile>(options.stats_file)),
        overlay_(options.overlay, fps),
        manifest_(options) {}
  ~RunOutputs() {
    if (finished_) return;
    try {
      complete(false);
    } catch (const std::exception&) {  // the error that ended the run is the one to report
    }
  }

  // `picture` is the overlay, empty when none is wanted.
  void write(int index, const Result& result, const cv::Mat& picture, const SourceReport& source,
             int decode_errors) {
    const fs::path dir(options_.output_dir);
    writeImageAtomic((dir / frameFileName(index)).string(), result.mask);
    // Pictures come with the result when asked for, by --debug or --debug-images alike.
    if (!result.debug.empty()) writeDebugPictures((dir / "debug").string(), index, result);
    if (stats_) stats_->append(jsonText(statsLine(index, result.diagnostics, decode_errors)));
    overlay_.write(index, picture);
    frames_ = index + 1;
    source_ = source;
    manifest_.progress(frames_, source_);
  }

  // `whole`: the run did all it was asked (not stopped by a signal).
  void finish(const SourceReport& source, bool whole) {
    source_ = source;
    finished_ = true;
    complete(whole);
  }

 private:
  void complete(bool finished) {
    if (stats_) stats_->close();
    stats_.reset();
    overlay_.close();
    manifest_.update(frames_, source_, finished);
  }

  const SegmentOptions& options_;
  std::unique_ptr<LineFile> stats_;
  OverlayWriter overlay_;
  Manifest manifest_;
  SourceReport source_;
  int frames_ = 0;
  bool finished_ = false;
};

// A frame as read, ready for the segmenter, and what its source said when it was read.
struct InputFrame {
  bool got = false;    // false at the end of the input
  cv::Mat frame;       // as decoded
  cv::Mat input;       // what the segmenter takes: `frame` resized (bench --size), or `frame`
  SourceReport report;
  std::string name;    // the source's describe()
};

// The source's frames, resized for the segmenter. With `ahead`, each is read and resized on a
// thread of its own while the caller works on the frame before: decoding (and bench's resize)
// were a third of the calling thread's time on two threads. A read's exception is thrown by the
// read() that would have returned its frame.
class FrameReader {
 public:
  // The source is not touched by the caller while the reader lives (it reads ahead).
  FrameReader(FrameSource* source, cv::Size resize, bool ahead)
      : source_(source), resize_(resize), ahead_(ahead ? std::make_unique<Worker>() : nullptr) {
    if (ahead_) readAhead();
  }

  // The next frame; valid until the next call. After the end, the end again.
  const InputFrame& read() {
    if (!ahead_) {
      readInto(&current_);
      return current_;
    }
    if (!reading_) return current_;  // the end, or a read that failed
    reading_ = false;
    try {
      ahead_->wait();
    } catch (...) {
      current_.got = false;  // nothing more to read
      throw;
    }
    // Swapped, not copied: the next read refills the frame the caller is now done with.
    std::swap(current_, next_);
    if (current_.got) readAhead();
    return current_;
  }

  // The frame read() returned last, for messages.
  const std::string& describe() const { return current_.name; }

 private:
  void readInto(InputFrame* frame) {
    frame->got = source_->read(&frame->frame);
    frame->report = source_->report();
    frame->name = source_->describe();
    if (frame->got) frame->input = resizedTo(frame->frame, resize_);
  }
  void readAhead() {
    reading_ = true;
    ahead_->start([this] { readInto(&next_); });
  }

  FrameSource* source_;
  cv::Size resize_;
  InputFrame current_, next_;      // next_ is the worker's between start() and wait()
  bool reading_ = false;           // a read is in flight
  std::unique_ptr<Worker> ahead_;  // last: destroyed first, it ends the read in flight
};

// A frame given to the segmenter, waiting for its result: one push later on two threads.
struct PushedFrame {
  int index = 0;
  cv::Size size;          // the frame's own: the mask is scaled back to it
  cv::Mat frame;          // kept only when an overlay is drawn
  SourceReport source;    // as it was when the frame was read
  int new_errors = 0;     // decode errors reported while it was read
};

// Each pushed frame's result, in order, to the run's outputs (the mask at the frame's size, the
// overlay, the live window) and its summary. With `behind`, the files are written on a thread of
// their own while the next frame is cut: encoding the PNGs and the file system's work were a
// third of the calling thread's time on two threads. A failed write is then thrown by the next
// write() or by finish().
class ResultWriter {
 public:
  ResultWriter(const SegmentOptions& options, RunOutputs* outputs, SegmentSummary* summary,
               Progress* progress, LiveWindow* window, bool behind)
      : options_(options), outputs_(outputs), summary_(summary), progress_(progress),
        window_(window), behind_(behind ? std::make_unique<Worker>() : nullptr) {}

  bool drawsOverlay() const { return !options_.overlay.empty() || options_.show; }

  void expect(PushedFrame pushed) { waiting_.push_back(std::move(pushed)); }

  // The result of the oldest frame expected, if the segmenter gave one; false when the viewer
  // closed the live window.
  bool write(std::optional<Result> given) {
    if (!given) return true;
    Files files{std::move(waiting_.front()), std::move(*given), cv::Mat()};
    waiting_.pop_front();
    const PushedFrame& pushed = files.pushed;
    Result& result = files.result;
    if (result.mask.size() != pushed.size) {
      cv::resize(result.mask, result.mask, pushed.size, 0, 0, cv::INTER_NEAREST);
    }
    summary_->frame_ms.add(result.diagnostics.total_ms);
    summary_->resets += result.diagnostics.reset;
    summary_->motion_fallbacks += result.diagnostics.motion_fallback;
    summary_->scene_cuts += result.diagnostics.scene_cut;
    if (drawsOverlay()) {
      files.picture = drawOverlay(pushed.frame, result, hudLine(pushed.index, result.diagnostics),
                                  options_.feature_dots);
    }
    const cv::Mat picture = files.picture;
    writeFiles(std::move(files));
    ++summary_->frames;
    progress_->update(summary_->frames);
    return window_->show(picture);
  }

  // Waits for the files being written, if any; throws when their write failed.
  void finish() {
    if (behind_) behind_->wait();
  }

 private:
  struct Files {
    PushedFrame pushed;
    Result result;
    cv::Mat picture;  // the overlay, empty when none is wanted
  };

  void writeFiles(Files files) {
    if (!behind_) return writeNow(files);
    behind_->wait();  // the previous frame's first, and its failure
    files_ = std::move(files);
    behind_->start([this] { writeNow(files_); });
  }

  void writeNow(const Files& files) {
    const PushedFrame& pushed = files.pushed;
    outputs_->write(pushed.index, files.result, files.picture, pushed.source, pushed.new_errors);
  }

  const SegmentOptions& options_;
  RunOutputs* outputs_;
  SegmentSummary* summary_;
  Progress* progress_;
  LiveWindow* window_;
  std::deque<PushedFrame> waiting_;  // pushed, oldest first, their results not yet written
  Files files_;                      // the worker's between start() and wait()
  std::unique_ptr<Worker> behind_;   // last: destroyed first, it ends the write in flight
};

}  // namespace

void refuseWritingIntoInput(const std::string& option, const std::string& path,
                            const std::string& input, const std::string& input_path) {
  if (!path.empty() && !input_path.empty() && isSameOrInside(path, input_path)) {
    throw UsageError(option + " '" + path + "' would write into the input '" + input + "'");
  }
}

namespace {

// UsageError when the existing file `path` is one of the files below `folder` under another
// name: a dataset linked file by file (`cp -rs`) holds links to masks and frames kept elsewhere.
void refuseReplacingAnInputFile(const std::string& option, const std::string& path,
                                const std::string& folder) {
  std::error_code error;
  if (!fs::exists(path, error) || !fs::is_directory(folder, error)) return;
  for (fs::recursive_directory_iterator entry(folder, fs::directory_options::skip_permission_denied,
                                              error), end;
       !error && entry != end; entry.increment(error)) {
    std::error_code same_error;
    if (fs::equivalent(entry->path(), path, same_error)) {
      throw UsageError(option + " '" + path + "' would write into the input '" +
                       entry->path().string() + "'");
    }
  }
}

}  // namespace

void checkReportPaths(std::initializer_list<std::pair<const char*, std::string>> reports,
                      const std::vector<std::string>& inputs) {
  for (const auto& [option, path] : reports) {
    for (const std::string& input : inputs) {
      refuseWritingIntoInput(option, path, input, input);
      if (!path.empty()) refuseReplacingAnInputFile(option, path, input);
    }
  }
  refuseSharedOutputs(reports);
  for (const auto& [option, path] : reports) {
    if (!path.empty()) checkOutputFile(path);
  }
}

StopOnSignal::StopOnSignal() {
  const std::lock_guard<std::mutex> lock(g_signal_mutex);
  if (g_signal_scopes++ > 0) return;
  g_stop = false;
  g_previous_int = std::signal(SIGINT, onSignal);
  g_previous_term = std::signal(SIGTERM, onSignal);
}

StopOnSignal::~StopOnSignal() {
  const std::lock_guard<std::mutex> lock(g_signal_mutex);
  if (--g_signal_scopes > 0) return;
  std::signal(SIGINT, g_previous_int);
  std::signal(SIGTERM, g_previous_term);
}

bool StopOnSignal::stopped() { return g_stop; }

namespace {

// The timestamps tell where the source ended (an estimated count from a duration that has them).
bool endsByTime(const SourceReport& source) {
  return !source.exact_count && source.duration_seconds > 0 && source.reached_seconds >= 0;
}

}  // namespace

bool SegmentSummary::truncated() const {
  if (interrupted || reached_max_frames) return false;
  // The duration counts the last frame's own time on screen, a frame interval.
  if (endsByTime(source)) {
    const double last_frame = source.fps > 0 ? 1 / source.fps : 0;
    return source.reached_seconds + last_frame + 1 < source.duration_seconds;
  }
  if (source.expected_frames < 0) return false;
  const int tolerance = source.exact_count ? 0 : static_cast<int>(std::ceil(source.fps));
  return frames + tolerance < source.expected_frames;
}

SegmentSummary runSegmentation(const SegmentOptions& options) {
  checkOutputPaths(options);
  LiveWindow window(options.show);
  Params params = options.params;
  params.debug_images = params.debug_images || options.debug;
  // One code path for both thread counts: on one thread each frame's result is flushed at once,
  // as Segmenter::process would give it.
  StreamSegmenter segmenter(params, options.threads);
  if (!options.ignore.empty()) segmenter.setIgnoredRegion(readIgnoredRegion(options.ignore));
  StopOnSignal stop_on_signal;
  std::unique_ptr<FrameSource> source;
  try {
    source = FrameSource::open(options.input, DecoderLimits{options.timeout, &g_stop});
  } catch (const std::exception&) {
    // A signal while the stream was being opened ended the open: an interrupted run, not a
    // failed one (nothing written yet).
    if (!StopOnSignal::stopped()) throw;
    SegmentSummary summary;
    summary.interrupted = true;
    return summary;
  }
  const SourceReport opened = source->report();
  const fs::path existing = existingAncestor(options.output_dir);
  std::optional<RunOutputs> opened_outputs;
  try {
    makeOutputFolder(options.output_dir);
    checkRunFiles(options);
    claimOutputFolder(options);
    opened_outputs.emplace(options, opened.fps);
  } catch (const std::exception&) {
    // An output that cannot be written is refused before any work: nothing is left behind,
    // not even the folders this run made for it.
    removeEmptyFoldersUpTo(options.output_dir, existing);
    throw;
  }
  RunOutputs& outputs = *opened_outputs;

  SegmentSummary summary;
  int total = opened.expected_frames;
  if (options.max_frames >= 0 && (total < 0 || total > options.max_frames)) total = options.max_frames;
  Progress progress("segment", total, options.quiet);
  // On two threads the frames are also read ahead and their files written behind.
  ResultWriter writer(options, &outputs, &summary, &progress, &window, options.threads > 1);
  FrameReader reader(source.get(), options.resize, options.threads > 1);
  int decode_errors = 0;
  // The next frame, and the decode errors reported while it was read; throws for a frame that
  // cannot be read, or a decode error with stop_on_decode_error.
  const auto readFrame = [&](int* new_errors) -> const InputFrame& {
    const InputFrame& read = reader.read();
    summary.source = read.report;
    *new_errors = summary.source.decode_errors - decode_errors;
    decode_errors = summary.source.decode_errors;
    if (*new_errors > 0 && options.stop_on_decode_error) {
      throw std::runtime_error(read.name + ": decode error: " + summary.source.last_error);
    }
    return read;
  };
  const auto checked = [&](auto step) {
    try {
      return step();
    } catch (const std::exception& e) {
      throw std::runtime_error(reader.describe() + ": " + e.what());
    }
  };
  const auto start = std::chrono::steady_clock::now();
  std::exception_ptr input_failure;  // thrown once the frames before it are written
  int pushed = 0;
  for (;;) {
    if (options.max_frames >= 0 && pushed >= options.max_frames) {
      summary.reached_max_frames = true;
      break;
    }
    if (g_stop) break;
    int new_errors = 0;
    const InputFrame* read = nullptr;
    try {
      read = &readFrame(&new_errors);
    } catch (const std::exception&) {
      input_failure = std::current_exception();
      break;
    }
    if (!read->got) break;
    // The frame is kept for its overlay: the reader refills its buffer before the result comes.
    const cv::Mat kept = writer.drawsOverlay() ? read->frame.clone() : cv::Mat();
    writer.expect({pushed++, read->frame.size(), kept, summary.source, new_errors});
    std::optional<Result> result = checked([&] { return segmenter.push(read->input); });
    if (options.threads == 1) result = checked([&] { return segmenter.flush(); });
    if (!writer.write(std::move(result))) break;
  }
  writer.write(checked([&] { return segmenter.flush(); }));  // the last frame's, on two threads
  writer.finish();
  if (input_failure) std::rethrow_exception(input_failure);
  summary.interrupted = g_stop;
  progress.finish();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outputs.finish(summary.source, !summary.interrupted);
  if (summary.frames == 0 && !summary.interrupted && !summary.reached_max_frames) {
    throw std::runtime_error("no frames in '" + options.input + "'" +
                             (summary.source.timed_out ? " (no answer within the timeout)" : ""));
  }
  return summary;
}

std::vector<RunOutcome> runSegmentations(
    const std::vector<SegmentOptions>& runs, int threads,
    const std::function<void(size_t index, const RunOutcome& outcome)>& ended) {
  StopOnSignal stop_on_signal;  // one for the batch: a signal between two runs is not lost
  std::vector<RunOutcome> outcomes(runs.size());
  std::mutex ended_mutex;
  runConcurrently(runs.size(), threads, [&](size_t i) {
    RunOutcome& outcome = outcomes[i];
    if (g_stop) {
      outcome.summary.interrupted = true;
    } else {
      try {
        outcome.summary = runSegmentation(runs[i]);
      } catch (const std::exception& e) {
        outcome.error = e.what();
      }
    }
    const std::lock_guard<std::mutex> lock(ended_mutex);
    ended(i, outcome);
  });
  return outcomes;
}

std::string inputName(const std::string& input) {
  fs::path path = fs::path(input).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();  // "walk/" is "walk"
  std::error_code error;
  if (!fs::is_directory(path, error)) return path.stem().string();
  const std::string name = path.filename().string();
  const bool layout = name == "frames" || name == "input" || name == "images";
  return layout ? path.parent_path().filename().string() : name;
}

std::vector<SegmentOptions> perInputRuns(const SegmentOptions& shared,
                                         const std::vector<std::string>& inputs) {
  if (shared.show) throw UsageError("--show takes one input");
  if (shared.output_dir.empty()) throw UsageError("the output folder (-o) is empty");
  for (const auto& [option, name] : {std::pair<const char*, std::string>{"--stats", shared.stats_file},
                                     {"--overlay", shared.overlay}}) {
    if (fs::path(name).has_parent_path() || name == "." || name == "..") {
      throw UsageError(std::string(option) + " '" + name +
                       "': with several inputs, a file name written in each input's folder");
    }
  }
  std::map<std::string, std::string> named;  // name -> input
  std::vector<SegmentOptions> runs;
  for (const std::string& input : inputs) {
    const std::string name = inputName(input);
    if (name.empty() || name == "." || name == "..") {
      throw UsageError("'" + input + "': no name for its output folder");
    }
    if (!named.emplace(name, input).second) {
      throw UsageError("'" + named[name] + "' and '" + input + "' would both write " +
                       (fs::path(shared.output_dir) / name).string() + ": rename one");
    }
    refuseWritingIntoInput("-o", shared.output_dir, input, inputPath(input));
    SegmentOptions run = shared;
    run.input = input;
    run.output_dir = (fs::path(shared.output_dir) / name).string();
    const auto inFolder = [&](const std::string& file) {
      return file.empty() ? file : (fs::path(run.output_dir) / file).string();
    };
    run.stats_file = inFolder(shared.stats_file);
    run.overlay = inFolder(shared.overlay);
    runs.push_back(std::move(run));
  }
  // Before any run: one run's outputs may not land in another's input, and a bad name is a
  // usage error of the command, not a failure of each run.
  for (const SegmentOptions& run : runs) checkOutputPaths(run, inputs);
  return runs;
}

std::string describeInputProblems(const SegmentSummary& summary) {
  const SourceReport& source = summary.source;
  std::string text;
  const auto add = [&text](const std::string& part) { text += (text.empty() ? "" : "; ") + part; };
  if (source.decode_errors > 0) {
    add(std::to_string(source.decode_errors) + " decode errors (last: " + source.last_error + ")");
  }
  if (summary.truncated()) {
    char reached[96];
    if (endsByTime(source)) {
      std::snprintf(reached, sizeof reached, "frames up to %.1f s of %.1f s",
                    source.reached_seconds, source.duration_seconds);
    } else {
      std::snprintf(reached, sizeof reached, "%d of %s%d frames", summary.frames,
                    source.exact_count ? "" : "about ", source.expected_frames);
    }
    add(std::string(reached) + ": the video is truncated");
  }
  if (source.timed_out) add("no frame within the timeout: the stream stalled");
  return text;
}

std::string describeSummary(const SegmentSummary& summary) {
  const double ms = summary.frame_ms.median();
  char line[160];
  std::snprintf(line, sizeof line, "%d frames in %.2f s (%.1f fps overall, median %.2f ms/frame)",
                summary.frames, summary.seconds,
                summary.seconds > 0 ? summary.frames / summary.seconds : 0.0, ms);
  std::string text = line;
  if (summary.resets > 0) text += ", " + std::to_string(summary.resets) + " size resets";
  if (summary.motion_fallbacks > 0) {
    text += ", " + std::to_string(summary.motion_fallbacks) + " alignment fallbacks";
  }
  if (summary.scene_cuts > 0) text += ", " + std::to_string(summary.scene_cuts) + " scene cuts";
  const std::string problems = describeInputProblems(summary);
  if (!problems.empty()) text += "; " + problems;
  return text;
}

}  // namespace movseg::cli
