// Matching predicted masks to ground-truth frames and scoring them (declared in dataset.h).
#include "eval/dataset.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace movseg {
namespace {

// `movseg segment` numbers its masks by position from 00000. Where the frames' numbers are not
// 0, 1, 2, ... (CDnet's start at in000001; a subsampled sequence holds 00000, 00003, ...),
// predictions that are all positions of the video and not all frames of it give that
// numbering away: a frame 0 the video does not have, 00001 where it skips from 0 to 3. Masks
// named by their frames' numbers (CDnet's bin000001.png) are all frames of the video.
bool numberedByPosition(const GtSequence& sequence, const std::map<int, std::string>& predictions) {
  const std::set<int> video(sequence.video_frames.begin(), sequence.video_frames.end());
  const int frames = static_cast<int>(video.size());
  const bool numbered_from_zero = !video.empty() && *video.begin() == 0 && *video.rbegin() == frames - 1;
  if (video.empty() || numbered_from_zero || predictions.empty()) return false;
  const auto isPosition = [frames](const auto& entry) { return entry.first < frames; };
  const auto isFrame = [&video](const auto& entry) { return video.count(entry.first) > 0; };
  return std::all_of(predictions.begin(), predictions.end(), isPosition) &&
         !std::all_of(predictions.begin(), predictions.end(), isFrame);
}

// Position of frame `index` in the frames folder; -1 when the folder does not hold it.
int positionOf(const GtSequence& sequence, int index) {
  const std::vector<int>& video = sequence.video_frames;
  const auto where = std::find(video.begin(), video.end(), index);
  return where == video.end() ? -1 : static_cast<int>(where - video.begin());
}

// Frames of the video (the frames folder, else the predictions) within the temporal ROI that
// have no ground-truth mask.
int countSkipped(const GtSequence& sequence, const std::map<int, std::string>& predictions) {
  std::vector<int> video = sequence.video_frames;
  if (video.empty()) {
    for (const auto& entry : predictions) video.push_back(entry.first);
  }
  std::set<int> annotated;
  for (const GtFrame& frame : sequence.frames) annotated.insert(frame.index);
  return static_cast<int>(std::count_if(video.begin(), video.end(), [&](int index) {
    return index >= sequence.roi_first && index <= sequence.roi_last && annotated.count(index) == 0;
  }));
}

std::string sizeText(const cv::Mat& image) {
  return std::to_string(image.cols) + "x" + std::to_string(image.rows);
}

FrameScore scoreFiles(const GtSequence& sequence, const GtFrame& frame,
                      const std::string& pred_path) {
  cv::Mat ignore;
  const cv::Mat truth = readGtMask(sequence, frame, &ignore);
  const cv::Mat pred = readMask(pred_path);
  if (pred.size() != truth.size()) {
    throw std::runtime_error("prediction '" + pred_path + "' is " + sizeText(pred) +
                             " but its ground truth '" + frame.mask_path + "' is " +
                             sizeText(truth) + " (masks are compared as they are, never resized)");
  }
  FrameScore score = scoreFrame(pred, truth, ignore);
  score.frame = frame.index;
  return score;
}

// The prediction of each ground-truth frame that has one, by frame number.
std::map<int, std::string> matched(const GtSequence& sequence,
                                   const std::map<int, std::string>& predictions,
                                   bool by_position) {
  std::map<int, std::string> result;
  for (const GtFrame& frame : sequence.frames) {
    const auto prediction =
        predictions.find(by_position ? positionOf(sequence, frame.index) : frame.index);
    if (prediction != predictions.end()) result[frame.index] = prediction->second;
  }
  return result;
}

}  // namespace

std::map<int, std::string> matchPredictions(const GtSequence& sequence,
                                            const std::string& pred_dir) {
  const std::map<int, std::string> predictions = numberedImages(pred_dir);
  return matched(sequence, predictions, numberedByPosition(sequence, predictions));
}

SequenceScore scoreSequence(const GtSequence& sequence, const std::string& pred_dir) {
  const std::map<int, std::string> predictions = numberedImages(pred_dir);
  SequenceScore score;
  score.name = sequence.name;
  score.first_frame = sequence.first_frame;
  score.matched_by_position = numberedByPosition(sequence, predictions);
  const std::map<int, std::string> matches =
      matched(sequence, predictions, score.matched_by_position);
  for (const GtFrame& frame : sequence.frames) {
    const auto prediction = matches.find(frame.index);
    if (prediction != matches.end()) {
      score.frames.push_back(scoreFiles(sequence, frame, prediction->second));
    } else if (frame.index != sequence.first_frame) {
      ++score.missing;
    }
  }
  score.skipped = countSkipped(sequence, predictions);
  return score;
}

std::vector<SequenceScore> scoreDataset(const std::vector<GtSequence>& sequences,
                                        const std::string& pred_path,
                                        const std::function<bool()>& stop) {
  std::vector<SequenceScore> scores;
  for (const GtSequence& sequence : sequences) {
    if (stop && stop()) break;
    scores.push_back(scoreSequence(sequence, predictionDir(sequence, pred_path)));
  }
  return scores;
}

}  // namespace movseg
