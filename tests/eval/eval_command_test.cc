// `movseg eval` end to end: tiny mask folders in a temp dir, the printed table and the files.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "eval/eval_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

using test::rectMask;
using test::writeImage;

const cv::Size kSize(10, 10);
const cv::Rect kSquare(0, 0, 4, 4);

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// GT: 00000 (empty), 00001 and 00002 (the 4x4 square at the origin). PRED: 00000 everything
// (not counted: first frame), 00001 the square moved to (2, 2), 00002 the square.
// Frame 1: J = 4 / 28 = 1/7, error 24 %, tp 4 fp 12 fn 12. F with a 1-px tolerance
// (ceil(0.008 * 14.1)): the truth's boundary is column 3 and row 3 of the square (7 px); the
// prediction's is its column 5 and row 5 (7 px) plus the background row 1 (columns 1-5) and
// column 1 (rows 2-5) in front of it (9 px). Within 1 px (4-neighbours) of the other: 6 of the
// 16 predicted pixels ((1,2) (1,3) (1,4) (2,1) (3,1) (4,1)) and 6 of the 7 true ones (all but
// (3,3)): F = 2 * 6 / (16 + 7) = 12/23 = 0.521739. Frame 2: J 1, F 1, error 0, tp 16.
// Means: J = (1/7 + 1) / 2 = 4/7 = 0.571, error 12.00 %, J recall 0.5;
// summed P = R = 20 / 32 = 0.625.
void writePlainPair(const test::TempDir& dir) {
  writeImage(dir / "gt", "00000.png", rectMask(kSize, {}));
  writeImage(dir / "gt", "00001.png", rectMask(kSize, kSquare));
  writeImage(dir / "gt", "00002.png", rectMask(kSize, kSquare));
  writeImage(dir / "pred", "00000.png", rectMask(kSize, {0, 0, 10, 10}));
  writeImage(dir / "pred", "1.png", rectMask(kSize, {2, 2, 4, 4}));
  writeImage(dir / "pred", "00002.png", rectMask(kSize, kSquare));
}

// A sequence of two frames in `sequence` (frames/ empty, masks/ the square) and predictions
// that are its truth in `predictions`.
void writeSequenceAndItsTruth(const std::string& sequence, const std::string& predictions) {
  for (int i = 0; i < 2; ++i) {
    const std::string file = "0000" + std::to_string(i) + ".png";
    writeImage(sequence + "/frames", file, rectMask(kSize, {}));
    writeImage(sequence + "/masks", file, rectMask(kSize, kSquare));
    writeImage(predictions, file, rectMask(kSize, kSquare));
  }
}

TEST(EvalCli, PrintsTableAndWritesCsvAndJson) {
  test::TempDir dir;
  writePlainPair(dir);
  const test::CommandResult run =
      test::runCli("eval '" + (dir / "pred") + "' '" + (dir / "gt") + "' --csv '" +
                   (dir / "s.csv") + "' --json '" + (dir / "s.json") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("1 plain sequence"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("0.571"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("12.00"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("0.625"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("first frame of each sequence is not counted"), std::string::npos);

  EXPECT_EQ(readFile(dir / "s.csv"),
            "sequence,frame,J,F,error_rate,precision,recall,f1\n"
            "gt,1,0.142857,0.521739,24,0.25,0.25,0.25\n"
            "gt,2,1,1,0,1,1,1\n");

  const nlohmann::json report = nlohmann::json::parse(readFile(dir / "s.json"));
  const nlohmann::json& sequence = report.at("sequences").at(0);
  EXPECT_EQ(sequence.at("name"), "gt");
  EXPECT_EQ(sequence.at("frames"), 2);
  EXPECT_NEAR(sequence.at("J").get<double>(), 4.0 / 7, 1e-12);
  EXPECT_NEAR(sequence.at("J_recall").get<double>(), 0.5, 1e-12);
  EXPECT_NEAR(sequence.at("precision").get<double>(), 0.625, 1e-12);
  EXPECT_EQ(sequence.at("per_frame").size(), 2u);
  EXPECT_EQ(sequence.at("per_frame").at(0).at("fp"), 12);
  EXPECT_NEAR(report.at("mean").at("J").get<double>(), 4.0 / 7, 1e-12);
}

// --format names the ground truth's layout instead of guessing it: the plain pair read as
// plain gives the figures above, read as CDnet (no groundtruth/ folder) one line, and a layout
// that does not exist is a usage error.
TEST(EvalCli, FormatIsTakenAsGivenOrRefused) {
  test::TempDir dir;
  writePlainPair(dir);
  const std::string pair = "eval '" + (dir / "pred") + "' '" + (dir / "gt") + "'";
  const test::CommandResult plain = test::runCli(pair + " --format plain");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_NE(plain.output.find("1 plain sequence"), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("0.571"), std::string::npos) << plain.output;
  test::expectOneLineError(test::runCli(pair + " --format cdnet"), "temporalROI.txt",
                           test::kExitRunFailed);
  test::expectOneLineError(test::runCli(pair + " --format bogus"), "--format", test::kExitUsage);
}

TEST(EvalCli, DatasetLayoutScoresEverySequence) {
  test::TempDir dir;
  for (const std::string name : {"one", "two"}) {
    writeSequenceAndItsTruth(dir / ("gt/" + name), dir / ("pred/" + name));
  }
  const test::CommandResult run = test::runCli("eval '" + (dir / "pred") + "' '" + (dir / "gt") +
                                               "' --json '" + (dir / "s.json") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("2 davis sequences"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("\none "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("\ntwo "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("\nmean "), std::string::npos) << run.output;
  // The predictions are the truth: each sequence scores 1, over its one counted frame.
  const nlohmann::json report = nlohmann::json::parse(readFile(dir / "s.json"));
  const nlohmann::json& sequences = report.at("sequences");
  ASSERT_EQ(sequences.size(), 2u);
  for (size_t i = 0; i < sequences.size(); ++i) {
    const nlohmann::json& sequence = sequences.at(i);
    EXPECT_EQ(sequence.at("name"), i == 0 ? "one" : "two");
    EXPECT_EQ(sequence.at("frames"), 1) << i;
    EXPECT_EQ(sequence.at("J").get<double>(), 1.0) << i;
    EXPECT_EQ(sequence.at("F").get<double>(), 1.0) << i;
  }
  EXPECT_EQ(report.at("mean").at("J").get<double>(), 1.0);
}

TEST(EvalCli, NoPredictionsAtAllFails) {
  test::TempDir dir;
  writePlainPair(dir);
  std::filesystem::create_directories(dir / "nothing");
  const test::CommandResult run = test::runCli("eval '" + (dir / "nothing") + "' '" + (dir / "gt") +
                                               "' --csv '" + (dir / "s.csv") + "'");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("movseg: error: no predicted mask for sequence 'gt'"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "s.csv"));
}

TEST(EvalCli, BadGroundTruthIsAOneLineError) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "empty");
  const test::CommandResult run =
      test::runCli("eval '" + dir.path() + "' '" + (dir / "empty") + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.output.rfind("movseg: error: ground truth '", 0), 0u) << run.output;
  EXPECT_EQ(run.output.find('\n'), run.output.size() - 1) << run.output;
}

// `eval GT PRED`: the ground truth (frames + masks) given as PRED, the predictions as GT.
TEST(EvalCli, SwappedArgumentsAreAnError) {
  test::TempDir dir;
  writeSequenceAndItsTruth(dir / "seq", dir / "out");
  const test::CommandResult right =
      test::runCli("eval '" + (dir / "out") + "' '" + (dir / "seq") + "'");
  EXPECT_EQ(right.exit_code, 0) << right.output;
  EXPECT_NE(right.output.find("\nseq "), std::string::npos) << right.output;
  const test::CommandResult swapped =
      test::runCli("eval '" + (dir / "seq") + "' '" + (dir / "out") + "'");
  EXPECT_EQ(swapped.exit_code, 1) << swapped.output;
  EXPECT_NE(swapped.output.find("are they swapped? The order is movseg eval PRED GT"),
            std::string::npos)
      << swapped.output;
  EXPECT_EQ(swapped.output.find('\n'), swapped.output.size() - 1) << swapped.output;
}

TEST(EvalCli, ResizedPredictionIsAnError) {
  test::TempDir dir;
  writePlainPair(dir);
  writeImage(dir / "pred", "00002.png", rectMask({20, 10}, {}));
  const test::CommandResult run =
      test::runCli("eval '" + (dir / "pred") + "' '" + (dir / "gt") + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("00002.png' is 20x10"), std::string::npos) << run.output;
}

// A dataset made of links to sequences kept elsewhere (a subset of a larger set): a report
// must not land in a linked sequence's masks, frames or predictions, which the dataset folder's
// own path does not contain (exit 0 before, the mask replaced by the CSV).
TEST(EvalCli, NoReportInsideALinkedSequence) {
  test::TempDir dir;
  writeSequenceAndItsTruth(dir / "store/seq", dir / "store/pred");
  std::filesystem::create_directories(dir / "gt");
  std::filesystem::create_directories(dir / "pred");
  std::filesystem::create_directory_symlink(dir / "store/seq", dir / "gt/seq");
  std::filesystem::create_directory_symlink(dir / "store/pred", dir / "pred/seq");
  const std::string mask = dir / "store/seq/masks/00001.png";
  const std::string before = readFile(mask);
  for (const std::string target : {"gt/seq/masks/00001.png", "store/seq/masks/00001.png",
                                   "store/seq/frames/00001.png", "store/pred/00001.png"}) {
    const test::CommandResult run = test::runCli("eval '" + (dir / "pred") + "' '" + (dir / "gt") +
                                                 "' --csv '" + (dir / target) + "'");
    EXPECT_EQ(run.exit_code, test::kExitUsage) << target << ": " << run.output;
    EXPECT_NE(run.output.find("would write into the input"), std::string::npos) << run.output;
  }
  // Linked file by file (`cp -rs`): the folders are real, each mask a link into the store.
  for (const char* folder : {"frames", "masks"}) {
    std::filesystem::create_directories(dir / ("files/seq/" + std::string(folder)));
    for (int i = 0; i < 2; ++i) {
      const std::string file = std::string(folder) + "/0000" + std::to_string(i) + ".png";
      std::filesystem::create_symlink(dir / ("store/seq/" + file), dir / ("files/seq/" + file));
    }
  }
  const test::CommandResult by_file = test::runCli(
      "eval '" + (dir / "pred") + "' '" + (dir / "files") + "' --json '" + mask + "'");
  EXPECT_EQ(by_file.exit_code, test::kExitUsage) << by_file.output;
  EXPECT_EQ(readFile(mask), before);
  EXPECT_FALSE(std::filesystem::exists(mask + ".part"));  // not even tried
  EXPECT_EQ(test::runCli("eval '" + (dir / "pred") + "' '" + (dir / "gt") + "' --csv '" +
                         (dir / "s.csv") + "'")
                .exit_code,
            0);
}

// Masks 1000 times taller than wide: the report's thumbnails fit JPEG's limits (the report
// failed, "Maximum supported image dimension is 65500 pixels"); a frame that cannot be decoded
// (a PNG header claiming 200000x200000) is drawn as a grey canvas, not an error.
TEST(EvalCli, TheReportTakesTallMasksAndUndecodableFrames) {
  test::TempDir dir;
  const cv::Size tall(2, 1000);
  for (int i = 0; i < 3; ++i) {
    const std::string file = "0000" + std::to_string(i) + ".png";
    writeImage(dir / "gt/seq/frames", file, rectMask(tall, {}));
    writeImage(dir / "gt/seq/masks", file, rectMask(tall, {0, 0, 2, 400}));
    writeImage(dir / "pred/seq", file, rectMask(tall, {0, 100, 2, 400}));
  }
  // The PNG's IHDR width and height (bytes 16-23), then its CRC is wrong too: undecodable.
  std::fstream frame(dir / "gt/seq/frames/00002.png", std::ios::in | std::ios::out | std::ios::binary);
  frame.seekp(16);
  for (const char byte : {0, 3, 13, 64, 0, 3, 13, 64}) frame.put(byte);
  frame.close();
  const test::CommandResult run = test::runCli("eval '" + (dir / "pred") + "' '" + (dir / "gt") +
                                               "' --html '" + (dir / "r.html") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.find("OpenCV"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("libpng"), std::string::npos) << run.output;
  EXPECT_NE(readFile(dir / "r.html").find("data:image/jpeg;base64,"), std::string::npos);
}

// The table on a full disk: a failed write, exit 1 (exit 0 before). (Its message goes to the
// full disk too: runCli sends stderr where stdout goes.)
TEST(EvalCli, AFailedWriteOfTheTableFails) {
  test::TempDir dir;
  writePlainPair(dir);
  const std::string command = "eval '" + (dir / "pred") + "' '" + (dir / "gt") + "'";
  EXPECT_EQ(test::runCli(command).exit_code, 0);
  EXPECT_EQ(test::runCli(command + " > /dev/full").exit_code, 1);
}

// A sequence named with a newline keeps its table row on one line.
TEST(EvalCli, ANameWithANewlineIsOneRow) {
  test::TempDir dir;
  for (int i = 0; i < 2; ++i) {
    const std::string file = "0000" + std::to_string(i) + ".png";
    writeImage(dir / "gt/a\nb/masks", file, rectMask(kSize, kSquare));
    writeImage(dir / "pred/a\nb", file, rectMask(kSize, kSquare));
  }
  const test::CommandResult run =
      test::runCli("eval '" + (dir / "pred") + "' '" + (dir / "gt") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("\na b "), std::string::npos) << run.output;
}

}  // namespace
}  // namespace movseg
