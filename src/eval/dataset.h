// Ground truth as the datasets lay it out (DAVIS, SegTrack, CDnet, a plain mask folder), scored
// against a folder of predicted masks, and the reports of those scores. Conventions:
// docs/metrics.md.
#pragma once

#include <limits>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "eval/metrics.h"

namespace movseg {

// Layout of one sequence:
//   kPlain     the folder holds the masks
//   kDavis     <seq>/frames/ + <seq>/masks/ (also the output of `movseg synth`)
//   kSegtrack  <seq>/ holds the frames, <seq>/ground-truth/ (or GroundTruth/) the masks
//   kCdnet     <seq>/input/in000001.jpg, <seq>/groundtruth/gt000001.png, <seq>/temporalROI.txt
// kAuto detects it, in this order: cdnet (temporalROI.txt or groundtruth/), davis (masks/),
// segtrack (ground-truth/), plain (images in the folder).
enum class GtFormat { kAuto, kPlain, kDavis, kSegtrack, kCdnet };

// The names of the formats ("auto", "plain", "davis", "segtrack", "cdnet").
const std::map<std::string, GtFormat>& gtFormatNames();
std::string gtFormatName(GtFormat format);

// A file's frame number: the trailing digits of its name's stem, so that 00012.png, 12.png,
// gt000012.png and bird_00012.png are all frame 12. Throws std::runtime_error when the stem
// does not end in digits or in more than 9.
int frameNumber(const std::string& path);

// A folder's own name, also when given with a trailing slash or as ".": "data/blackswan/" ->
// "blackswan".
std::string folderName(const std::string& folder);

// The images of `folder` (which exists) in name order, each with its frame number. Throws
// std::runtime_error when a file has no frame number or two files have the same one.
std::vector<std::pair<int, std::string>> framesInOrder(const std::string& folder);

// The images of `folder` by frame number (framesInOrder()); none when the folder does not exist.
std::map<int, std::string> numberedImages(const std::string& folder);

struct GtFrame {
  int index = 0;  // frame number of the mask file (frameNumber())
  std::string mask_path;
};

struct GtSequence {
  std::string name;
  std::string folder;           // the sequence's own (a plain layout's: its masks')
  std::string frames_dir;       // the video's frames; empty when the layout has none (plain)
  std::vector<GtFrame> frames;  // by index; CDnet: only those within the temporal ROI
  GtFormat format = GtFormat::kPlain;
  // Frame numbers of frames_dir's images in name order, i.e. in the order `movseg segment`
  // reads them; empty without frames_dir.
  std::vector<int> video_frames;
  int first_frame = 0;  // the lowest frame number of the video (of the masks without frames_dir)
  int roi_first = 0;    // CDnet's temporalROI.txt: frames outside [roi_first, roi_last] are
  int roi_last = std::numeric_limits<int>::max();  // not counted at all
  bool in_dataset = false;  // one sequence of a dataset folder: predictions in PRED/<name>/
};

// The sequences at `path`: one entry when `path` is a sequence of the format, else one per
// subfolder (a dataset, sorted by name; every subfolder must be a sequence of the format).
// Throws std::runtime_error with a one-line reason when `path` is empty, is not a mask folder,
// or a sequence has no mask.
std::vector<GtSequence> loadGroundTruth(const std::string& path, GtFormat format);

// A mask file as 0 / 255 CV_8U: any non-zero pixel (any colour channel; alpha aside) is
// foreground. Throws std::runtime_error naming the file when it cannot be read.
cv::Mat readMask(const std::string& path);

// The ground-truth mask of `frame` as 0 / 255 CV_8U (readMask()), but for CDnet's grey levels:
// 255 foreground; 0 and 50 (shadow) background; 85 (outside the ROI) and 170 (unknown motion)
// ignored, marked non-zero in *ignore; any other level is an error. *ignore is left empty when
// nothing is ignored (`ignore` may be null). Throws std::runtime_error naming the file when it
// cannot be read.
cv::Mat readGtMask(const GtSequence& sequence, const GtFrame& frame, cv::Mat* ignore);

// Where the predictions of `sequence` are: PRED/<name>/ for a sequence of a dataset, else PRED;
// in either case its masks/ subfolder when there is one.
std::string predictionDir(const GtSequence& sequence, const std::string& pred_path);

// Throws std::runtime_error naming the first sequence of `sequences` whose ground truth has no
// frame but the video's first, which no score counts: a mean over the others would pass for
// the whole set's.
void requireFramesToScore(const std::vector<GtSequence>& sequences);

// The folders the sequences are read from: their own, their frames', their masks' and, unless
// `pred_path` is empty, their predictions' (PRED/<name>/ and predictionDir()). A sequence of a
// dataset may be a link to a folder elsewhere, which the dataset's own path does not contain.
std::vector<std::string> sequenceFolders(const std::vector<GtSequence>& sequences,
                                         const std::string& pred_path);

// Scores the masks of `pred_dir` (non-zero = foreground) against the sequence, matched by frame
// number. Ground-truth frames without a prediction are counted as missing (but the first frame,
// which no mean counts); video frames without ground truth as skipped. `movseg segment` numbers
// its masks from 00000 by position in the frames folder: when the frames are not numbered so
// (CDnet's start at in000001, a subsampled sequence's skip) and every prediction is a position
// of the video but not every one a frame of it (a frame 0 the video does not have, 00001 where
// it skips from 0 to 3), predictions are matched to frames by that position instead, and the
// score says so. Throws std::runtime_error naming the file when a
// mask cannot be read or a prediction's size differs from its ground truth's.
SequenceScore scoreSequence(const GtSequence& sequence, const std::string& pred_dir);

// The prediction file of each ground-truth frame of `sequence` that has one in `pred_dir`, by
// frame number, matched as scoreSequence() matches them.
std::map<int, std::string> matchPredictions(const GtSequence& sequence,
                                            const std::string& pred_dir);

// scoreSequence() of every sequence with its predictionDir(); only those scored before `stop`
// (if given) first returns true, asked before each sequence.
std::vector<SequenceScore> scoreDataset(const std::vector<GtSequence>& sequences,
                                        const std::string& pred_path,
                                        const std::function<bool()>& stop = {});

// `value` with `decimals` digits after the point; "-" for NaN (nothing to score).
std::string formatFixed(double value, int decimals);

// The table printed by `movseg eval`: one row per sequence, a mean row when there are several,
// and footnotes (the first frame is not counted; position matching).
std::string formatScoreTable(const std::vector<SequenceScore>& scores);

// One row per counted frame: sequence,frame,J,F,error_rate,precision,recall,f1.
std::string scoresCsv(const std::vector<SequenceScore>& scores);

// Per-sequence figures with their counted frames, and the mean over sequences.
std::string scoresJson(const std::vector<SequenceScore>& scores);

}  // namespace movseg
