#include "eval/dataset.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "io/atomic_write.h"
#include "io/frame_source.h"

namespace movseg {
namespace fs = std::filesystem;
namespace {

// CDnet's grey levels (Goyette et al. 2012).
constexpr uchar kCdnetStatic = 0;
constexpr uchar kCdnetShadow = 50;
constexpr uchar kCdnetOutsideRoi = 85;
constexpr uchar kCdnetUnknown = 170;
constexpr uchar kCdnetMotion = 255;

// Longer digit runs are not frame numbers (and would overflow an int).
constexpr size_t kMaxFrameDigits = 9;

bool isFolder(const std::string& path) {
  std::error_code error;
  return fs::is_directory(path, error);
}

bool isFile(const std::string& path) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

std::string join(const std::string& folder, const std::string& name) {
  return (fs::path(folder) / name).string();
}

bool holdsImages(const std::string& folder) {
  return isFolder(folder) && !listImages(folder).empty();
}

// SegTrack's mask folder: both spellings are in circulation.
std::string segtrackMasks(const std::string& folder) {
  for (const char* name : {"ground-truth", "GroundTruth"}) {
    if (isFolder(join(folder, name))) return join(folder, name);
  }
  return "";
}

bool hasLayout(const std::string& folder, GtFormat format) {
  switch (format) {
    case GtFormat::kCdnet:
      return isFile(join(folder, "temporalROI.txt")) || isFolder(join(folder, "groundtruth"));
    case GtFormat::kDavis:
      return isFolder(join(folder, "masks"));
    case GtFormat::kSegtrack:
      return !segtrackMasks(folder).empty();
    case GtFormat::kPlain:
      return holdsImages(folder);
    case GtFormat::kAuto:
      break;
  }
  return false;
}

// The format of the sequence at `folder`, detected when `requested` is kAuto; kAuto when the
// folder is no sequence of that format.
GtFormat sequenceFormat(const std::string& folder, GtFormat requested) {
  if (requested != GtFormat::kAuto)
    return hasLayout(folder, requested) ? requested : GtFormat::kAuto;
  for (GtFormat format :
       {GtFormat::kCdnet, GtFormat::kDavis, GtFormat::kSegtrack, GtFormat::kPlain}) {
    if (hasLayout(folder, format)) return format;
  }
  return GtFormat::kAuto;
}

std::string expectedLayout(GtFormat format) {
  switch (format) {
    case GtFormat::kPlain:
      return "mask images";
    case GtFormat::kDavis:
      return "a masks/ folder";
    case GtFormat::kSegtrack:
      return "a ground-truth/ or GroundTruth/ folder";
    case GtFormat::kCdnet:
      return "a groundtruth/ folder and temporalROI.txt";
    case GtFormat::kAuto:
      break;
  }
  return "mask images, or a masks/, ground-truth/ or groundtruth/ folder";
}

// Non-hidden subfolders, sorted by name.
std::vector<std::string> subfolders(const std::string& folder) {
  std::vector<std::string> result;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_directory() && entry.path().filename().string()[0] != '.') {
      result.push_back(entry.path().string());
    }
  }
  std::sort(result.begin(), result.end());
  return result;
}

// A mask folder given on its own is named after its sequence: "blackswan/masks" ->
// "blackswan", as the layouts of GtFormat name their mask folders.
std::string sequenceName(const std::string& folder, GtFormat format) {
  const std::string name = folderName(folder);
  const bool layout_mask_folder = name == "masks" || name == "ground-truth" ||
                                  name == "GroundTruth" || name == "groundtruth";
  if (format != GtFormat::kPlain || !layout_mask_folder) return name;
  return folderName(join(folder, ".."));
}

void readTemporalRoi(const std::string& path, GtSequence* sequence) {
  std::ifstream in(path);
  int first = 0;
  int last = 0;
  if (!(in >> first >> last) || first < 0 || last < first) {
    throw std::runtime_error("cannot read the first and last frame numbers from '" + path + "'");
  }
  sequence->roi_first = first;
  sequence->roi_last = last;
}

bool inTemporalRoi(const GtSequence& sequence, int index) {
  return index >= sequence.roi_first && index <= sequence.roi_last;
}

struct Folders {
  std::string masks;
  std::string frames;  // "" when the layout has none
};

Folders foldersOf(const std::string& folder, GtFormat format) {
  switch (format) {
    case GtFormat::kDavis:
      return {join(folder, "masks"), join(folder, "frames")};
    case GtFormat::kSegtrack:
      return {segtrackMasks(folder), folder};
    case GtFormat::kCdnet:
      return {join(folder, "groundtruth"), join(folder, "input")};
    case GtFormat::kPlain:
    case GtFormat::kAuto:
      break;
  }
  return {folder, ""};
}

GtSequence loadSequence(const std::string& folder, GtFormat format, bool in_dataset) {
  GtSequence sequence;
  sequence.name = sequenceName(folder, format);
  sequence.folder = folder;
  sequence.format = format;
  sequence.in_dataset = in_dataset;
  const std::string roi_file = join(folder, "temporalROI.txt");
  if (format == GtFormat::kCdnet && isFile(roi_file)) readTemporalRoi(roi_file, &sequence);

  const Folders folders = foldersOf(folder, format);
  const std::map<int, std::string> masks = numberedImages(folders.masks);
  if (masks.empty()) throw std::runtime_error("no mask images in '" + folders.masks + "'");
  for (const auto& [index, path] : masks) {
    if (inTemporalRoi(sequence, index)) sequence.frames.push_back({index, path});
  }
  if (sequence.frames.empty()) {
    throw std::runtime_error("no mask of '" + folders.masks + "' lies within temporalROI.txt's " +
                             std::to_string(sequence.roi_first) + "-" +
                             std::to_string(sequence.roi_last));
  }
  if (holdsImages(folders.frames)) {
    sequence.frames_dir = folders.frames;
    for (const auto& [number, path] : framesInOrder(folders.frames)) {
      sequence.video_frames.push_back(number);
    }
  }
  sequence.first_frame =
      sequence.video_frames.empty()
          ? masks.begin()->first
          : *std::min_element(sequence.video_frames.begin(), sequence.video_frames.end());
  return sequence;
}

cv::Mat readImage(const std::string& path, int flags) {
  cv::Mat image = decodeImage(path, flags);
  if (image.empty()) throw std::runtime_error("cannot read mask '" + path + "'");
  return image;
}

// 255 where `labels` holds one of `levels`.
cv::Mat labelledAs(const cv::Mat& labels, std::initializer_list<uchar> levels) {
  cv::Mat result = cv::Mat::zeros(labels.size(), CV_8U);
  for (uchar level : levels) result |= labels == level;
  return result;
}

// Throws unless every pixel holds one of CDnet's five grey levels.
void checkCdnetLevels(const cv::Mat& labels, const std::string& path) {
  const cv::Mat known = labelledAs(
      labels, {kCdnetStatic, kCdnetShadow, kCdnetOutsideRoi, kCdnetUnknown, kCdnetMotion});
  cv::Point unknown_at;
  double lowest = 0;
  cv::minMaxLoc(known, &lowest, nullptr, &unknown_at);
  if (lowest != 0) return;
  throw std::runtime_error("'" + path + "' holds grey level " +
                           std::to_string(labels.at<uchar>(unknown_at)) +
                           ", not a CDnet label (0, 50, 85, 170 or 255)");
}

// CDnet's labels are 8-bit grey levels: a 16-bit file, which reading as 8-bit would scale (255
// to 0, motion to static), is refused.
cv::Mat readCdnetMask(const std::string& path, cv::Mat* ignore) {
  const cv::Mat labels = readImage(path, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
  if (labels.depth() != CV_8U) {
    throw std::runtime_error("'" + path + "' is not 8-bit: CDnet's labels are 8-bit grey levels");
  }
  checkCdnetLevels(labels, path);
  const cv::Mat ignored = labelledAs(labels, {kCdnetOutsideRoi, kCdnetUnknown});
  if (ignore != nullptr) *ignore = cv::countNonZero(ignored) > 0 ? ignored : cv::Mat();
  return labels == kCdnetMotion;
}

}  // namespace

const std::map<std::string, GtFormat>& gtFormatNames() {
  static const std::map<std::string, GtFormat> names{{"auto", GtFormat::kAuto},
                                                     {"plain", GtFormat::kPlain},
                                                     {"davis", GtFormat::kDavis},
                                                     {"segtrack", GtFormat::kSegtrack},
                                                     {"cdnet", GtFormat::kCdnet}};
  return names;
}

std::string gtFormatName(GtFormat format) {
  for (const auto& [name, value] : gtFormatNames()) {
    if (value == format) return name;
  }
  return "";
}

std::string folderName(const std::string& folder) { return folderPath(folder).filename().string(); }

int frameNumber(const std::string& path) {
  const std::string stem = fs::path(path).stem().string();
  const auto digits_begin = std::find_if_not(stem.rbegin(), stem.rend(), [](unsigned char c) {
                              return std::isdigit(c);
                            }).base();
  const std::string digits(digits_begin, stem.end());
  if (digits.empty()) {
    throw std::runtime_error("cannot read a frame number from the name of '" + path +
                             "' (expected digits at the end, e.g. 00012.png)");
  }
  if (digits.size() > kMaxFrameDigits) {
    throw std::runtime_error("the frame number of '" + path + "' has more than " +
                             std::to_string(kMaxFrameDigits) + " digits (at most " +
                             std::to_string(kMaxFrameDigits) + " are read)");
  }
  return std::stoi(digits);
}

std::vector<std::pair<int, std::string>> framesInOrder(const std::string& folder) {
  std::vector<std::pair<int, std::string>> frames;
  std::map<int, std::string> seen;
  for (const std::string& path : listImages(folder)) {
    const auto [where, inserted] = seen.emplace(frameNumber(path), path);
    if (!inserted) {
      throw std::runtime_error("'" + where->second + "' and '" + path + "' are both frame " +
                               std::to_string(where->first));
    }
    frames.emplace_back(where->first, path);
  }
  return frames;
}

std::map<int, std::string> numberedImages(const std::string& folder) {
  if (!isFolder(folder)) return {};
  const std::vector<std::pair<int, std::string>> frames = framesInOrder(folder);
  return {frames.begin(), frames.end()};
}

std::vector<GtSequence> loadGroundTruth(const std::string& path, GtFormat format) {
  if (!isFolder(path)) throw std::runtime_error("ground truth '" + path + "' is not a folder");
  const GtFormat own_format = sequenceFormat(path, format);
  if (own_format != GtFormat::kAuto) return {loadSequence(path, own_format, false)};

  std::vector<GtSequence> dataset;
  for (const std::string& folder : subfolders(path)) {
    const GtFormat folder_format = sequenceFormat(folder, format);
    if (folder_format == GtFormat::kAuto) {
      throw std::runtime_error("'" + folder + "' is not a sequence: expected " +
                               expectedLayout(format) +
                               " in it (every subfolder of a dataset folder is a sequence)");
    }
    dataset.push_back(loadSequence(folder, folder_format, true));
  }
  if (dataset.empty()) {
    throw std::runtime_error("ground truth '" + path +
                             "' is empty or not a mask folder: expected " + expectedLayout(format) +
                             " in it, or one such folder per sequence");
  }
  return dataset;
}

std::string predictionDir(const GtSequence& sequence, const std::string& pred_path) {
  const std::string folder = sequence.in_dataset ? join(pred_path, sequence.name) : pred_path;
  const std::string masks = join(folder, "masks");
  return isFolder(masks) ? masks : folder;
}

void requireFramesToScore(const std::vector<GtSequence>& sequences) {
  for (const GtSequence& sequence : sequences) {
    const bool scored = std::any_of(sequence.frames.begin(), sequence.frames.end(),
                                    [&](const GtFrame& f) { return f.index != sequence.first_frame; });
    if (!scored) {
      throw std::runtime_error("sequence '" + sequence.name +
                               "' has no ground-truth frame to score besides its first");
    }
  }
}

std::vector<std::string> sequenceFolders(const std::vector<GtSequence>& sequences,
                                         const std::string& pred_path) {
  std::vector<std::string> folders;
  for (const GtSequence& sequence : sequences) {
    folders.push_back(sequence.folder);
    if (!sequence.frames_dir.empty()) folders.push_back(sequence.frames_dir);
    // One folder holds a sequence's masks; loadGroundTruth() gives none without one.
    folders.push_back(fs::path(sequence.frames.front().mask_path).parent_path().string());
    if (pred_path.empty()) continue;
    folders.push_back(sequence.in_dataset ? join(pred_path, sequence.name) : pred_path);
    folders.push_back(predictionDir(sequence, pred_path));
  }
  return folders;
}

cv::Mat readMask(const std::string& path) {
  std::vector<cv::Mat> channels;
  cv::split(readImage(path, cv::IMREAD_UNCHANGED), channels);
  if (channels.size() == 4) channels.pop_back();  // alpha is no label
  cv::Mat foreground = channels[0] != 0;
  for (size_t c = 1; c < channels.size(); ++c) foreground |= channels[c] != 0;
  return foreground;
}

cv::Mat readGtMask(const GtSequence& sequence, const GtFrame& frame, cv::Mat* ignore) {
  if (sequence.format == GtFormat::kCdnet) return readCdnetMask(frame.mask_path, ignore);
  if (ignore != nullptr) ignore->release();
  return readMask(frame.mask_path);
}

}  // namespace movseg
