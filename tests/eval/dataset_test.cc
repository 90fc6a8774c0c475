// Ground-truth layouts and conventions, on tiny mask folders written to a temp dir.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "eval/dataset.h"
#include "eval/eval_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

using test::rectMask;
using test::writeImage;
using test::writeText;

const cv::Size kSize(10, 10);
const cv::Rect kSquare(0, 0, 4, 4);

std::string maskName(int index) {
  char name[16];
  std::snprintf(name, sizeof name, "%05d.png", index);
  return name;
}

// <folder>/frames/0000i.png and <folder>/masks/0000i.png (kSquare) for each index.
void writeDavisSequence(const std::string& folder, std::initializer_list<int> frames,
                        std::initializer_list<int> masks) {
  for (int index : frames) writeImage(folder + "/frames", maskName(index), rectMask(kSize, {}));
  for (int index : masks) writeImage(folder + "/masks", maskName(index), rectMask(kSize, kSquare));
}

// Expects `call` to throw std::runtime_error whose message contains `needle`.
template <typename Call>
void expectError(Call call, const std::string& needle) {
  try {
    call();
    FAIL() << "no error; expected one mentioning " << needle;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(EvalDataset, FrameNumbersAreTrailingDigits) {
  EXPECT_EQ(frameNumber("a/00012.png"), 12);
  EXPECT_EQ(frameNumber("12.png"), 12);
  EXPECT_EQ(frameNumber("gt000012.png"), 12);
  EXPECT_EQ(frameNumber("birdfall2_00012.png"), 12);
  EXPECT_THROW(frameNumber("mask.png"), std::runtime_error);
  expectError([] { frameNumber("1700000000123.png"); }, "has more than 9 digits");
}

TEST(EvalDataset, TwoFilesOfOneFrameAreAnError) {
  test::TempDir dir;
  writeImage(dir.path(), "00012.png", rectMask(kSize, {}));
  writeImage(dir.path(), "12.png", rectMask(kSize, {}));
  expectError([&] { numberedImages(dir.path()); }, "both frame 12");
}

TEST(EvalDataset, DetectsEachLayout) {
  test::TempDir dir;
  writeImage(dir / "plain", "00000.png", rectMask(kSize, kSquare));
  writeDavisSequence(dir / "davis", {0}, {0});
  writeImage(dir / "segtrack", "bird_00000.png", rectMask(kSize, {}));
  writeImage(dir / "segtrack/GroundTruth", "bird_00000.png", rectMask(kSize, kSquare));
  writeImage(dir / "segtrack2/ground-truth", "00000.png", rectMask(kSize, kSquare));
  writeImage(dir / "cdnet/groundtruth", "gt000001.png", rectMask(kSize, kSquare));
  writeText(dir / "cdnet", "temporalROI.txt", "1 1\n");
  EXPECT_EQ(loadGroundTruth(dir / "plain", GtFormat::kAuto).at(0).format, GtFormat::kPlain);
  EXPECT_EQ(loadGroundTruth(dir / "davis", GtFormat::kAuto).at(0).format, GtFormat::kDavis);
  EXPECT_EQ(loadGroundTruth(dir / "segtrack", GtFormat::kAuto).at(0).format, GtFormat::kSegtrack);
  EXPECT_EQ(loadGroundTruth(dir / "segtrack2", GtFormat::kAuto).at(0).format, GtFormat::kSegtrack);
  EXPECT_EQ(loadGroundTruth(dir / "cdnet", GtFormat::kAuto).at(0).format, GtFormat::kCdnet);
  // A folder of those is a dataset, one sequence each, named by folder.
  const std::vector<GtSequence> all = loadGroundTruth(dir.path(), GtFormat::kAuto);
  ASSERT_EQ(all.size(), 5u);
  EXPECT_EQ(all[0].name, "cdnet");
  EXPECT_TRUE(all[0].in_dataset);
  // An explicit format that does not fit is an error, not a guess.
  EXPECT_THROW(loadGroundTruth(dir / "plain", GtFormat::kCdnet), std::runtime_error);
}

// `eval PRED blackswan/masks` names the sequence blackswan, not masks.
TEST(EvalDataset, AMaskFolderGivenAloneIsNamedAfterItsSequence) {
  test::TempDir dir;
  writeDavisSequence(dir / "blackswan", {0}, {0});
  writeImage(dir / "cows/ground-truth", "00000.png", rectMask(kSize, kSquare));
  writeImage(dir / "masks_of_mine", "00000.png", rectMask(kSize, kSquare));
  EXPECT_EQ(loadGroundTruth(dir / "blackswan/masks", GtFormat::kAuto).at(0).name, "blackswan");
  EXPECT_EQ(loadGroundTruth(dir / "blackswan/masks/", GtFormat::kAuto).at(0).name, "blackswan");
  EXPECT_EQ(loadGroundTruth(dir / "cows/ground-truth", GtFormat::kPlain).at(0).name, "cows");
  EXPECT_EQ(loadGroundTruth(dir / "masks_of_mine", GtFormat::kAuto).at(0).name, "masks_of_mine");
}

TEST(EvalDataset, EmptyOrNonMaskFolderIsAnError) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "empty");
  expectError([&] { loadGroundTruth(dir / "empty", GtFormat::kAuto); }, "not a mask folder");
  writeText(dir / "notes", "readme.txt", "no masks here");
  expectError([&] { loadGroundTruth(dir / "notes", GtFormat::kAuto); }, "not a mask folder");
  std::filesystem::create_directories(dir / "davis/masks");
  expectError([&] { loadGroundTruth(dir / "davis", GtFormat::kAuto); }, "no mask images");
  expectError([&] { loadGroundTruth(dir / "absent", GtFormat::kAuto); }, "not a folder");
}

TEST(EvalDataset, CdnetLevels) {
  // Columns 0-1: 0 static, 2-3: 50 shadow, 4-5: 85 outside ROI, 6-7: 170 unknown, 8-9: 255.
  test::TempDir dir;
  cv::Mat labels(kSize, CV_8U);
  const uchar levels[] = {0, 50, 85, 170, 255};
  for (int i = 0; i < 5; ++i) labels.colRange(2 * i, 2 * i + 2).setTo(levels[i]);
  writeImage(dir / "seq/groundtruth", "gt000001.png", labels);
  writeText(dir / "seq", "temporalROI.txt", "1 1\n");
  const GtSequence sequence = loadGroundTruth(dir / "seq", GtFormat::kAuto).at(0);
  cv::Mat ignore;
  const cv::Mat truth = readGtMask(sequence, sequence.frames.at(0), &ignore);
  EXPECT_EQ(cv::countNonZero(truth), 20);
  EXPECT_EQ(cv::countNonZero(truth.colRange(8, 10)), 20);
  ASSERT_FALSE(ignore.empty());
  EXPECT_EQ(cv::countNonZero(ignore), 40);
  EXPECT_EQ(cv::countNonZero(ignore.colRange(4, 8)), 40);
  // A prediction of everything: the 20 motion pixels right, the 40 static and shadow pixels
  // false positives, the ignored 40 not counted.
  const FrameScore score = scoreFrame(rectMask(kSize, {0, 0, 10, 10}), truth, ignore);
  EXPECT_EQ(score.tp, 20);
  EXPECT_EQ(score.fp, 40);
  EXPECT_EQ(score.fn, 0);
  EXPECT_EQ(score.tn, 0);
  // Any other grey level is not CDnet ground truth.
  labels.at<uchar>(0, 0) = 128;
  writeImage(dir / "seq/groundtruth", "gt000001.png", labels);
  expectError([&] { readGtMask(sequence, sequence.frames.at(0), &ignore); }, "grey level 128");
  // Nor is a 16-bit file, which read as 8-bit took 255 (motion) for 0 (static).
  cv::Mat deep;
  labels.at<uchar>(0, 0) = 0;
  labels.convertTo(deep, CV_16U);
  writeImage(dir / "seq/groundtruth", "gt000001.png", deep);
  expectError([&] { readGtMask(sequence, sequence.frames.at(0), &ignore); }, "is not 8-bit");
}

TEST(EvalDataset, CdnetCountsTemporalRoiOnlyAndMatchesSegmentNumbering) {
  // Frames in000001-in000006, ROI 3-5. `movseg segment input/` writes 00000.png for in000001,
  // so 00002.png is frame 3: only 00002-00004 are right, and only they are counted.
  test::TempDir dir;
  for (int i = 1; i <= 6; ++i) {
    const std::string number = std::to_string(i);
    writeImage(dir / "seq/input", "in00000" + number + ".png", rectMask(kSize, {}));
    writeImage(dir / "seq/groundtruth", "gt00000" + number + ".png", rectMask(kSize, kSquare));
    const bool in_roi = i >= 3 && i <= 5;
    writeImage(dir / "pred", maskName(i - 1), rectMask(kSize, in_roi ? kSquare : cv::Rect()));
  }
  writeText(dir / "seq", "temporalROI.txt", "3 5\n");
  const GtSequence sequence = loadGroundTruth(dir / "seq", GtFormat::kAuto).at(0);
  EXPECT_EQ(sequence.first_frame, 1);
  ASSERT_EQ(sequence.frames.size(), 3u);
  EXPECT_EQ(sequence.frames.front().index, 3);
  const SequenceScore score = scoreSequence(sequence, dir / "pred");
  EXPECT_TRUE(score.matched_by_position);
  ASSERT_EQ(score.counted().size(), 3u);
  EXPECT_EQ(score.counted().front().frame, 3);
  EXPECT_EQ(score.meanJ(), 1);
  EXPECT_EQ(score.skipped, 0);
  EXPECT_EQ(score.missing, 0);
  EXPECT_NE(formatScoreTable({score}).find("by their position"), std::string::npos);

  // Predictions numbered as CDnet numbers its frames (bin000003.png) match by number.
  for (int i = 3; i <= 5; ++i) {
    writeImage(dir / "bin", "bin00000" + std::to_string(i) + ".png", rectMask(kSize, kSquare));
  }
  const SequenceScore by_number = scoreSequence(sequence, dir / "bin");
  EXPECT_FALSE(by_number.matched_by_position);
  EXPECT_EQ(by_number.meanJ(), 1);
}

TEST(EvalDataset, ASubsampledSequenceMatchesSegmentNumbering) {
  // Every third frame kept: frames and masks 00000, 00003, 00006, 00009. `movseg segment`
  // writes 00000-00003 for them; its 00002 is frame 6. Positions 1 and 2 right, 3 wrong: J 2/3
  // (by number, 00003 would be frame 3, and frames 6 and 9 missing).
  test::TempDir dir;
  writeDavisSequence(dir / "seq", {0, 3, 6, 9}, {0, 3, 6, 9});
  for (int i = 0; i < 4; ++i) {
    writeImage(dir / "pred", maskName(i), rectMask(kSize, i == 3 ? cv::Rect() : kSquare));
  }
  const GtSequence sequence = loadGroundTruth(dir / "seq", GtFormat::kAuto).at(0);
  const SequenceScore score = scoreSequence(sequence, dir / "pred");
  EXPECT_TRUE(score.matched_by_position);
  ASSERT_EQ(score.counted().size(), 3u);
  EXPECT_NEAR(score.meanJ(), 2.0 / 3, 1e-9);
  EXPECT_EQ(score.missing, 0);

  // Masks named by their frames' numbers match by number.
  for (int i : {0, 3, 6, 9}) writeImage(dir / "by_number", maskName(i), rectMask(kSize, kSquare));
  const SequenceScore by_number = scoreSequence(sequence, dir / "by_number");
  EXPECT_FALSE(by_number.matched_by_position);
  EXPECT_EQ(by_number.meanJ(), 1);

  // One of segment's masks missing (00002, frame 6): still by position, frame 6 missing.
  std::filesystem::remove(dir / ("pred/" + maskName(2)));
  const SequenceScore gap = scoreSequence(sequence, dir / "pred");
  EXPECT_TRUE(gap.matched_by_position);
  EXPECT_EQ(gap.missing, 1);
  EXPECT_NEAR(gap.meanJ(), 1.0 / 2, 1e-9);  // frame 3 right, frame 9 wrong
}

// Frames named without padding (0.png ... 11.png) sort as 0, 1, 10, 11, 2, ...: their numbers
// are 0-11 all the same, so masks named like them match by number (the position in name order
// is not the number).
TEST(EvalDataset, UnpaddedFrameNamesMatchByNumber) {
  test::TempDir dir;
  for (int i = 0; i < 12; ++i) {
    const cv::Rect square(i % 5, 0, 4, 4);  // each frame's own
    writeImage(dir / "seq/frames", std::to_string(i) + ".png", rectMask(kSize, {}));
    writeImage(dir / "seq/masks", std::to_string(i) + ".png", rectMask(kSize, square));
    writeImage(dir / "pred", std::to_string(i) + ".png", rectMask(kSize, square));
  }
  const SequenceScore score =
      scoreSequence(loadGroundTruth(dir / "seq", GtFormat::kAuto).at(0), dir / "pred");
  EXPECT_FALSE(score.matched_by_position);
  EXPECT_EQ(score.meanJ(), 1);
}

TEST(EvalDataset, TwoFilesOfOneFrameInTheFramesFolderAreAnError) {
  test::TempDir dir;
  writeDavisSequence(dir / "seq", {0, 1, 2}, {0, 1, 2});
  writeImage(dir / "seq/frames", "00002.jpg", rectMask(kSize, {}));
  expectError([&] { loadGroundTruth(dir / "seq", GtFormat::kAuto); }, "are both frame 2");
}

TEST(EvalDataset, FramesWithoutGroundTruthAreSkippedNotEmpty) {
  // Five frames, masks for 0, 2 and 4 only; the predictions are all empty.
  test::TempDir dir;
  writeDavisSequence(dir / "seq", {0, 1, 2, 3, 4}, {0, 2, 4});
  for (int i = 0; i < 5; ++i) writeImage(dir / "pred", maskName(i), rectMask(kSize, {}));
  const SequenceScore score =
      scoreSequence(loadGroundTruth(dir / "seq", GtFormat::kAuto).at(0), dir / "pred");
  EXPECT_EQ(score.skipped, 2);
  EXPECT_EQ(score.frames.size(), 3u);
  EXPECT_EQ(score.counted().size(), 2u);  // frames 2 and 4
  EXPECT_EQ(score.meanJ(), 0);            // empty predictions of non-empty truth
}

TEST(EvalDataset, FirstFrameIsNotCountedAndMissingPredictionsAre) {
  // Frame 0 is predicted wrong (not counted), frame 1 right, frame 2 not predicted (missing),
  // frame 3 right: J = 1 over frames 1 and 3.
  test::TempDir dir;
  writeDavisSequence(dir / "seq", {0, 1, 2, 3}, {0, 1, 2, 3});
  writeImage(dir / "pred", maskName(0), rectMask(kSize, {5, 5, 5, 5}));
  writeImage(dir / "pred", maskName(1), rectMask(kSize, kSquare));
  writeImage(dir / "pred", maskName(3), rectMask(kSize, kSquare));
  const SequenceScore score =
      scoreSequence(loadGroundTruth(dir / "seq", GtFormat::kAuto).at(0), dir / "pred");
  EXPECT_EQ(score.first_frame, 0);
  EXPECT_EQ(score.frames.size(), 3u);
  EXPECT_EQ(score.frames.front().j, 0);  // kept, but not counted
  EXPECT_EQ(score.counted().size(), 2u);
  EXPECT_EQ(score.meanJ(), 1);
  EXPECT_EQ(score.missing, 1);
  EXPECT_NE(formatScoreTable({score}).find("first frame of each sequence is not counted"),
            std::string::npos);
}

TEST(EvalDataset, SizeMismatchNamesTheFile) {
  test::TempDir dir;
  writeDavisSequence(dir / "seq", {0, 1}, {0, 1});
  writeImage(dir / "pred", maskName(0), rectMask(kSize, {}));
  writeImage(dir / "pred", maskName(1), rectMask({20, 20}, {}));
  const GtSequence sequence = loadGroundTruth(dir / "seq", GtFormat::kAuto).at(0);
  expectError([&] { scoreSequence(sequence, dir / "pred"); }, maskName(1) + "' is 20x20");
}

TEST(EvalDataset, ColourGroundTruthAnyChannelIsForeground) {
  // A DAVIS-palette mask: dark red (0, 0, 128) on black.
  test::TempDir dir;
  cv::Mat colour(kSize, CV_8UC3, cv::Scalar(0, 0, 0));
  colour(kSquare).setTo(cv::Scalar(0, 0, 128));
  writeImage(dir / "gt", maskName(0), colour);
  const GtSequence sequence = loadGroundTruth(dir / "gt", GtFormat::kAuto).at(0);
  cv::Mat ignore;
  const cv::Mat truth = readGtMask(sequence, sequence.frames.at(0), &ignore);
  EXPECT_TRUE(ignore.empty());
  EXPECT_EQ(cv::countNonZero(truth), 16);
  EXPECT_EQ(cv::countNonZero(truth(kSquare)), 16);
}

TEST(EvalDataset, DatasetGivesOneRowPerSequenceAndAMean) {
  // Sequence a: predictions in PRED/a/, all right. Sequence b: in PRED/b/masks/, all empty.
  test::TempDir dir;
  writeDavisSequence(dir / "gt/a", {0, 1, 2}, {0, 1, 2});
  writeDavisSequence(dir / "gt/b", {0, 1, 2}, {0, 1, 2});
  for (int i = 0; i < 3; ++i) {
    writeImage(dir / "pred/a", maskName(i), rectMask(kSize, kSquare));
    writeImage(dir / "pred/b/masks", maskName(i), rectMask(kSize, {}));
  }
  const std::vector<SequenceScore> scores =
      scoreDataset(loadGroundTruth(dir / "gt", GtFormat::kAuto), dir / "pred");
  ASSERT_EQ(scores.size(), 2u);
  EXPECT_EQ(scores[0].meanJ(), 1);
  EXPECT_EQ(scores[1].meanJ(), 0);
  EXPECT_EQ(scores[1].missing, 0);
  const std::string table = formatScoreTable(scores);
  EXPECT_NE(table.find("\na "), std::string::npos) << table;
  EXPECT_NE(table.find("\nb "), std::string::npos) << table;
  EXPECT_NE(table.find("\nmean "), std::string::npos) << table;
  EXPECT_NE(table.find("0.500"), std::string::npos) << table;  // mean J over the two sequences
}

TEST(EvalDataset, DavisGroundTruthAgainstItselfIsPerfect) {
  const std::string sequence_dir = test::davisSequence("car-shadow");
  if (sequence_dir.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
  const GtSequence sequence = loadGroundTruth(sequence_dir, GtFormat::kAuto).at(0);
  EXPECT_EQ(sequence.format, GtFormat::kDavis);
  const SequenceScore score = scoreSequence(sequence, predictionDir(sequence, sequence_dir));
  EXPECT_EQ(score.missing, 0);
  EXPECT_EQ(score.skipped, 0);
  EXPECT_EQ(score.counted().size(), sequence.frames.size() - 1);
  EXPECT_EQ(score.meanJ(), 1);
  EXPECT_EQ(score.meanF(), 1);
  EXPECT_EQ(score.meanErrorRate(), 0);
}

}  // namespace
}  // namespace movseg
