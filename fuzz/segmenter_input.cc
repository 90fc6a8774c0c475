#include "segmenter_input.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "fuzz_input.h"
#include "movseg/fields.h"
#include "movseg/segmenter.h"

namespace movseg::fuzz {
namespace {

// Large enough for LK, the cut and the scale changes to run; small enough for thousands of
// runs a second.
constexpr int kMaxSide = 96;
constexpr int kMaxFrames = 8;

// The scale parameters' interesting values: native size, degenerate, small and the default.
int fuzzedWidth(FuzzInput& in) {
  static const int kWidths[] = {0, 1, 2, 8, 17, 48, 320};
  return kWidths[in.range(0, 6)];
}

int fuzzedOdd(FuzzInput& in, int low, int high) { return low + 2 * in.range(0, (high - low) / 2); }

Params fuzzedParams(FuzzInput& in) {
  Params p;
  if (!in.flag()) return p;  // half of the inputs run the defaults
  const std::uint8_t switches = in.byte();
  p.static_camera = switches & 1;
  p.motion_model = switches & 2 ? MotionModel::kHomography : MotionModel::kAffine;
  p.warm_start = switches & 4;
  p.gmm_refine = switches & 8;
  p.debug_images = switches & 16;
  p.method = static_cast<Method>((switches >> 5) % enumNames<Method>().size());
  p.alignment_width = fuzzedWidth(in);
  p.segmentation_width = fuzzedWidth(in);
  p.max_corners = in.range(0, 400);
  p.edge_cell = in.range(2, 64);
  p.lk_window = fuzzedOdd(in, 3, 31);
  p.lk_levels = in.range(0, 8);
  p.zncc_window = fuzzedOdd(in, 3, 21);
  p.ransac_iterations = in.range(1, 128);
  p.ransac_threshold = in.real(0.05, 10);
  p.ransac_grid = in.range(1, 16);
  p.max_outer_iterations = in.range(1, 8);
  p.seed = in.byte();
  p.lambda = in.real(0, 2000);
  p.lambda_residual_factor = in.real(0, 20);
  p.difference_blur = in.real(0, 20);
  p.gmm_clusters = in.range(1, 12);
  p.cut_weight = in.real(0, 10);
  p.geodesic_gamma = in.real(0, 200);
  p.cut_band = in.range(0, 32);
  return p;
}

cv::Size fuzzedSize(FuzzInput& in) { return {in.range(1, kMaxSide), in.range(1, kMaxSide)}; }

// Smooth random texture: what LK and the ZNCC filter can track.
cv::Mat texture(cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat coarse(std::max(1, size.height / 4), std::max(1, size.width / 4), CV_8UC3);
  rng.fill(coarse, cv::RNG::UNIFORM, 0, 256);
  cv::Mat out;
  cv::resize(coarse, out, size, 0, 0, cv::INTER_LINEAR);
  return out;
}

// A view of a larger texture shifted by up to kMaxSide / 2 pixels: camera motion from none to
// far beyond LK's reach.
cv::Mat shiftedTexture(FuzzInput& in, cv::Size size) {
  const int margin = kMaxSide / 2;
  const cv::Mat world = texture(size + cv::Size(2 * margin, 2 * margin), in.byte());
  const cv::Point shift(in.range(-margin, margin), in.range(-margin, margin));
  return world(cv::Rect(cv::Point(margin, margin) + shift, size)).clone();
}

cv::Mat checkerboard(FuzzInput& in, cv::Size size) {
  const int cell = in.range(1, 16);
  cv::Mat out(size, CV_8UC3);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      out.at<cv::Vec3b>(y, x) = cv::Vec3b::all((x / cell + y / cell) % 2 ? 255 : 0);
    }
  }
  return out;
}

// An independently moving object: a flat or textured rectangle anywhere, even partly outside.
void pasteObject(FuzzInput& in, cv::Mat* picture) {
  const cv::Rect box(in.range(-8, kMaxSide), in.range(-8, kMaxSide), in.range(1, kMaxSide),
                     in.range(1, kMaxSide));
  const cv::Rect inside = box & cv::Rect(cv::Point(), picture->size());
  if (inside.empty()) return;
  if (in.flag()) {
    (*picture)(inside).setTo(cv::Scalar(in.byte(), in.byte(), in.byte()));
  } else {
    texture(inside.size(), in.byte()).copyTo((*picture)(inside));
  }
}

// An 8-bit BGR picture.
cv::Mat fuzzedPicture(FuzzInput& in, cv::Size size) {
  cv::Mat picture;
  switch (in.range(0, 3)) {
    case 0: picture = cv::Mat(size, CV_8UC3, cv::Scalar(in.byte(), in.byte(), in.byte())); break;
    case 1: picture = shiftedTexture(in, size); break;
    case 2:
      picture.create(size, CV_8UC3);
      cv::RNG(in.byte()).fill(picture, cv::RNG::UNIFORM, 0, 256);
      break;
    default: picture = checkerboard(in, size); break;
  }
  if (in.flag()) pasteObject(in, &picture);
  return picture;
}

// Float frames must lie in [0, 1] (NaN counts as 0).
bool inUnitRangeIfFloat(const cv::Mat& frame) {
  if (frame.depth() != CV_32F && frame.depth() != CV_64F) return true;
  cv::Mat real;
  frame.convertTo(real, CV_32F);
  cv::patchNaNs(real, 0.0);
  double low = 0, high = 0;
  cv::minMaxLoc(real.reshape(1), &low, &high);
  return low >= 0 && high <= 1;
}

// Every depth toBgr8 converts, and two it must reject (32S, 16F).
const int kDepths[] = {CV_8U, CV_8S, CV_16U, CV_16S, CV_32F, CV_64F, CV_32S, CV_16F};

bool supported(const cv::Mat& frame) {
  const int channels = frame.channels();
  return frame.depth() != CV_32S && frame.depth() != CV_16F &&
         (channels == 1 || channels == 3 || channels == 4) && inUnitRangeIfFloat(frame);
}

// `picture` in the given depth and channel count, spanning that depth's range.
cv::Mat converted(const cv::Mat& picture, int depth, int channels) {
  cv::Mat shaped;
  switch (channels) {
    case 1: cv::cvtColor(picture, shaped, cv::COLOR_BGR2GRAY); break;
    case 3: shaped = picture; break;
    case 4: cv::cvtColor(picture, shaped, cv::COLOR_BGR2BGRA); break;
    default: {
      std::vector<cv::Mat> planes(static_cast<size_t>(channels));
      cv::extractChannel(picture, planes[0], 0);
      std::fill(planes.begin() + 1, planes.end(), planes[0]);
      cv::merge(planes, shaped);
    }
  }
  cv::Mat out;
  switch (depth) {
    case CV_8S: shaped.convertTo(out, depth, 1.0, -128.0); break;
    case CV_16U: shaped.convertTo(out, depth, 257.0); break;
    case CV_16S: shaped.convertTo(out, depth, 257.0, -32768.0); break;
    case CV_32F:
    case CV_64F:
    case CV_16F: shaped.convertTo(out, depth, 1.0 / 255.0); break;
    default: shaped.convertTo(out, depth); break;
  }
  return out;
}

// The frame's memory filled with input bytes, repeated: extreme values, NaN and infinity.
void overwriteWithRawBytes(FuzzInput& in, cv::Mat* frame) {
  const std::string pattern = in.bytes(static_cast<size_t>(in.range(1, 64)));
  if (pattern.empty()) return;
  for (int y = 0; y < frame->rows; ++y) {
    uchar* row = frame->ptr(y);
    const size_t row_bytes = frame->cols * frame->elemSize();
    for (size_t i = 0; i < row_bytes; ++i) row[i] = static_cast<uchar>(pattern[i % pattern.size()]);
  }
}

cv::Mat fuzzedFrame(FuzzInput& in, cv::Size size, const cv::Mat& previous) {
  if (in.range(0, 7) == 0 && previous.size() == size) return previous;  // a camera at rest
  static const int kChannels[] = {1, 3, 3, 4, 2};
  const int depth = kDepths[in.range(0, 7)];
  const int channels = kChannels[in.range(0, 4)];
  cv::Mat frame = converted(fuzzedPicture(in, size), depth, channels);
  if (in.range(0, 7) == 0) overwriteWithRawBytes(in, &frame);
  return frame;
}

// Every diagnostic of diagnostics.def: counts, thresholds and times finite and not negative,
// the camera model finite.
struct SaneDiagnostic {
  bool operator()(bool) const { return true; }
  bool operator()(int v) const { return v >= 0; }
  bool operator()(std::uint64_t) const { return true; }
  bool operator()(double v) const { return std::isfinite(v) && v >= 0; }
  bool operator()(const std::string&) const { return true; }
  bool operator()(const cv::Matx33d& m) const {
    return std::all_of(m.val, m.val + 9, [](double v) { return std::isfinite(v); });
  }
};

void checkResult(const Segmenter& segmenter, const Result& result, const cv::Mat& frame) {
  require(result.mask.type() == CV_8UC1 && result.mask.size() == frame.size(),
          "mask of the wrong type or size");
  require(cv::countNonZero((result.mask != 0) & (result.mask != 255)) == 0,
          "mask values other than 0 and 255");
  for (const FieldInfo& field : diagnosticFields()) {
    require(std::visit(SaneDiagnostic{}, diagnosticValue(result.diagnostics, field.name)),
            "diagnostic " + field.name + " is negative or not finite");
  }
  for (const Feature& f : result.features) {
    require(f.position.x >= -1 && f.position.x <= frame.cols + 1 && f.position.y >= -1 &&
                f.position.y <= frame.rows + 1,
            "feature outside the frame (or NaN)");
  }
  const cv::Mat warped = segmenter.compensatedPreviousFrame();
  require(warped.empty() || (warped.type() == CV_8UC3 && warped.size() == frame.size()),
          "compensated previous frame of the wrong type or size");
}

// The Result, or nothing when process() rightly rejected an unsupported frame.
std::optional<Result> processOnce(Segmenter& segmenter, const cv::Mat& frame) {
  try {
    Result result = segmenter.process(frame);
    require(supported(frame), "a frame of unsupported type was accepted");
    return result;
  } catch (const std::invalid_argument& e) {
    require(!supported(frame), std::string("a supported frame was rejected: ") + e.what());
    return std::nullopt;
  }
}

}  // namespace

void runSegmenterInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  Segmenter segmenter(fuzzedParams(in));
  cv::Size frame_size = fuzzedSize(in);
  const int frames = in.range(1, kMaxFrames);
  cv::Mat previous;
  for (int i = 0; i < frames; ++i) {
    if (in.range(0, 7) == 0) frame_size = fuzzedSize(in);
    const cv::Mat frame = fuzzedFrame(in, frame_size, previous);
    if (const std::optional<Result> result = processOnce(segmenter, frame)) {
      checkResult(segmenter, *result, frame);
    }
    previous = frame;
  }
}

}  // namespace movseg::fuzz
