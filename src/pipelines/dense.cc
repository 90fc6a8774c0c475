// `dense`: movseg's own method. Every pixel's motion is measured (dense flow to the previous
// frame), the camera's share is removed (a homography fitted to the flow of the background), and
// what remains becomes evidence of independent motion, scaled by the pair's own background
// residual. The previous mask, carried by the flow, and colour models learnt over the stream
// add what one pair cannot see; a graph cut on the evidence and the image's edges makes the mask,
// whose outline a guided filter then moves onto the edges themselves.
// A scene cut empties the mask and the memory: what the new scene moves is learnt anew.
#include <algorithm>
#include <bitset>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "classify/scene_cut.h"
#include "core/frame.h"
#include "core/timing.h"
#include "cut/evidence_cut.h"
#include "cut/motion_regions.h"
#include "evidence/colour_model.h"
#include "evidence/evidence_debug.h"
#include "evidence/motion_evidence.h"
#include "flow/dense_flow.h"
#include "flow/flow_camera.h"
#include "motion/compensation.h"
#include "motion/model.h"
#include "pipelines/pipeline.h"
#include "refine/edge_snap.h"
#include "refine/refine_debug.h"

namespace movseg {
namespace {

// Phase 1: the frame at the working scale and its flow to the previous frame — all that does not
// need the previous frame's mask, so that it runs while that mask is made (StreamSegmenter).
struct DenseAnalysis : Analysis {
  cv::Mat bgr;                      // segmentation scale
  cv::Mat grey;
  std::vector<GridSample> samples;  // where the camera is fitted
  cv::Mat flow;                     // to the previous frame; empty on a first frame
  cv::Mat flow_map;                 // where the flow takes each pixel (flowMap)
  BlockContrast contrast;           // the cut's smoothness term
  double scale = 1;                 // bgr = the frame scaled by this
  cv::Size input_size;
  cv::Mat input_grey;  // at the input's size where that is larger: the edges the outline snaps to
  // Analysis::ignored at the working scale, or empty: no mask. And grown by the flow's reach:
  // the still region shapes the flow there too, which then goes the region's way (seen as depth
  // at infinity, a car lost along its epipolar lines, a line of motion along a black bar): no
  // evidence, no camera sample, no say in the photometric check's unit or the scene-cut test.
  cv::Mat working_ignored, near_ignored;
  bool repeat = false;  // the frame equals the previous one (RepeatedFrames)
  double prepare_ms = 0, flow_ms = 0;
};

// The last segmented frame at the working scale, for the next pair (its images outlive the
// analysis that made them, which is reused for a later frame), and the one before it, warped
// onto it only when the user asks for the compensated previous frame.
struct PreviousFrame {
  cv::Mat bgr, grey, before_bgr;
};

// Keeps the frame's images as `previous` on every way out of segment(), without copying them:
// analyse() writes a later frame's into buffers that nothing else refers to (FramePool).
struct Remember {
  const DenseAnalysis& frame;
  PreviousFrame* previous;
  ~Remember() {
    cv::swap(previous->bgr, previous->before_bgr);
    previous->bgr = frame.bgr;
    previous->grey = frame.grey;
  }
};

// A scene cut (classify/scene_cut.h) judged on every other pixel of every other row: eq. (4)'s d
// between the frame and the previous one at the pixel nearest to where the camera puts it, its
// levels mapped by the pair's change of light (a brighter exposure is the same scene), the
// ignored region (CV_8U, or empty) left out. A median over a quarter of the pixels decides as
// well as over all; warping the whole frame for it would cost more than the rest of the pair's
// evidence.
bool isSceneCutUnderCamera(const cv::Mat& bgr, const cv::Mat& previous_bgr,
                           const cv::Mat& camera_map, const LevelMap& levels,
                           const cv::Mat& ignored) {
  uchar table[256];
  levels.table(table);
  long samples = 0, covered = 0, differing = 0;
  for (int y = 0; y < bgr.rows; y += 2) {
    const auto* at = camera_map.ptr<cv::Vec2f>(y);
    const auto* colour = bgr.ptr<cv::Vec3b>(y);
    const uchar* left_out = ignored.empty() ? nullptr : ignored.ptr<uchar>(y);
    for (int x = 0; x < bgr.cols; x += 2) {
      if (left_out != nullptr && left_out[x] != 0) continue;
      ++samples;
      const cv::Point p(cvRound(at[x][0]), cvRound(at[x][1]));
      if (p.x < 0 || p.y < 0 || p.x >= bgr.cols || p.y >= bgr.rows) continue;
      const cv::Vec3b before = previous_bgr.at<cv::Vec3b>(p);
      const cv::Vec3i step =
          cv::Vec3i(colour[x]) - cv::Vec3i(table[before[0]], table[before[1]], table[before[2]]);
      ++covered;
      differing += static_cast<float>(step.dot(step)) / 3.f > kSceneCutMedianDifference;
    }
  }
  return isSceneCut(samples, covered, differing);
}

// DenseAnalysis' working_ignored and near_ignored from each frame's `ignored`. The margin is grown
// again only when the region changes: a region stays for a stream, and a dilation allocates its
// filter on every call.
class IgnoredRegion {
 public:
  // Both empty when `ignored` is; `reach`: the flow's (DenseFlow::reach()).
  void scale(const cv::Mat& ignored, cv::Size size, int reach, cv::Mat* exact, cv::Mat* near) {
    if (ignored.empty()) {
      exact->release();
      near->release();
      return;
    }
    cv::resize(ignored, *exact, size, 0, 0, cv::INTER_NEAREST);
    if (exact->size() == last_exact_.size() && cv::norm(*exact, last_exact_, cv::NORM_INF) == 0) {
      last_near_.copyTo(*near);
      return;
    }
    const int side = 2 * reach + 1;
    cv::dilate(*exact, *near, cv::getStructuringElement(cv::MORPH_RECT, {side, side}));
    exact->copyTo(last_exact_);
    near->copyTo(last_near_);
  }

 private:
  cv::Mat last_exact_, last_near_;  // copies: the analyses' buffers are theirs
};

// The residuals at the samples the photometric check does not confirm as moving (less than
// half confirmed): the background's, whatever the movers' share of the frame, so that the
// scale is the background's spread and not the movers' speed. When nearly everything is
// confirmed (under a quarter left), the check says nothing and all samples count. Returns `all`
// or `kept`, where they are written.
std::vector<float>* unconfirmedResiduals(const FlowCamera& camera, const cv::Mat& confirmation,
                                         std::vector<float>* all, std::vector<float>* kept) {
  residualAtSamples(camera, all);
  kept->clear();
  for (size_t i = 0; i < all->size(); ++i) {
    if (confirmation.at<float>(cv::Point(camera.at[i])) < 0.5f) kept->push_back((*all)[i]);
  }
  return kept->size() >= all->size() / 4 ? kept : all;
}

// *unary += bias, in floats as cv::add adds it, without the copy of the scalar cv::add allocates.
void addBias(double bias, cv::Mat* unary) {
  const auto b = static_cast<float>(bias);
  for (int y = 0; y < unary->rows; ++y) {
    float* u = unary->ptr<float>(y);
    for (int x = 0; x < unary->cols; ++x) u[x] += b;
  }
}

// A frame shown twice — a frame rate padded by repeating frames (24 to 30 per second), a stream
// that repeats its last frame when one is dropped — is no pair of moments: nothing moved between
// them because no time passed, and reading the pair as a still scene would erase every mover.
// A frame equal to the previous one (every pixel at the working scale) is a repeat, but only the
// first of a run: a scene that stays the same for longer is still, and a mover that left a
// noiseless still scene must leave the mask (a real camera's noise never repeats a frame).
class RepeatedFrames {
 public:
  bool isRepeat(const cv::Mat& grey) {
    const bool same = grey.size() == last_.size() && cv::norm(grey, last_, cv::NORM_INF) == 0;
    const bool repeat = same && !last_was_same_;
    last_was_same_ = same;
    if (!same) grey.copyTo(last_);
    return repeat;
  }
  void reset() {
    last_.release();
    last_was_same_ = false;
  }

 private:
  cv::Mat last_;  // the last frame, kept where it differs from the one before
  bool last_was_same_ = false;
};

// Depth read from one pair may be movers agreeing on an epipole by chance, or water; a translating
// camera's view of a static scene shows it pair after pair. So the epipole counts on a pair that
// has one when most of the last kPairs pairs (this one included) had one. A majority rather than
// kPairs in a row: where depth is local (a near ground below a far wall), one pair short of the
// rule's share broke the run and depth was seldom read — the independent dolly 0.142 -> 0.202,
// our 3-D scenes 0.853 -> 0.869, DAVIS J 0.598 -> 0.597. Keeping the last epipole over pairs
// without one, a hysteresis, cost DAVIS 0.011 J where water shows depth now and then
// (docs/design.md, "Parallax").
// A stream's first pairs are judged by the pairs there are: counted as pairs without depth, they
// kept it from the first two, whose mask took the near posts and ground that memory then held
// (the independent dolly). On the first pair, with no other to outvote a mover the camera
// follows, only a reading with the plane counts (blackswan's swan reads as depth otherwise).
class PersistentDepth {
 public:
  void settle(FlowCamera* camera) {
    recent_ <<= 1;
    recent_[0] = camera->epipole.has_value() && (seen_ > 0 || camera->depth_with_the_plane);
    seen_ = std::min(seen_ + 1, kPairs);
    if (static_cast<int>(recent_.count()) <= seen_ / 2) camera->epipole.reset();
  }

 private:
  static constexpr int kPairs = 5;
  std::bitset<kPairs> recent_;  // bit i: the pair i pairs before this one had an epipole
  int seen_ = 0;                // pairs judged since the stream began, up to kPairs
};

class DensePipeline : public Pipeline {
 public:
  explicit DensePipeline(const Params& params)
      : params_(params),
        flow_(params.flow_finest_scale),
        camera_fitter_(params),
        colour_(params),
        rng_(params.seed),
        // The most evidence one flow patch can give a region: its pixels, each at a pair's most.
        one_patch_of_evidence_(params.evidence_max * flow_.reach() * flow_.reach()) {}

  std::unique_ptr<Analysis> newAnalysis() const override {
    return std::make_unique<DenseAnalysis>();
  }

  void analyse(const cv::Mat& bgr, Analysis* analysis) override {
    auto& a = static_cast<DenseAnalysis&>(*analysis);
    Clock::time_point start = Clock::now();
    const cv::Size size = workingSize(bgr.size(), params_.segmentation_width);
    a.scale = static_cast<double>(size.width) / bgr.cols;
    a.input_size = bgr.size();
    a.bgr = bgr_buffers_.take(size, CV_8UC3);
    a.grey = grey_buffers_.take(size, CV_8U);
    downscale(bgr, size, &halved_, &a.bgr);
    cv::cvtColor(a.bgr, a.grey, cv::COLOR_BGR2GRAY);
    if (size != bgr.size() && params_.edge_snap > 0) {
      cv::cvtColor(bgr, a.input_grey, cv::COLOR_BGR2GRAY);
    } else {
      a.input_grey.release();
    }
    ignored_.scale(analysis->ignored, size, flow_.reach(), &a.working_ignored, &a.near_ignored);
    gridSamples(a.grey, params_.flow_sample_step, a.near_ignored, &a.samples);
    blockContrast(a.bgr, params_.smoothness, &a.contrast);
    a.prepare_ms = millisecondsSince(start);
    start = Clock::now();
    if (a.first_frame) {
      flow_.reset();
      repeats_.reset();
    }
    a.repeat = repeats_.isRepeat(a.grey);
    if (a.repeat) return;  // the flow and its warm start stay the previous pair's
    flow_.next(a.grey, &a.flow);
    if (!a.flow.empty()) flowMap(a.flow, &a.flow_map);
    a.flow_ms = millisecondsSince(start);
  }

  cv::Mat segment(const Analysis& analysis, const DebugSink& debug, Result* result) override {
    const auto& a = static_cast<const DenseAnalysis&>(analysis);
    Diagnostics& diag = result->diagnostics;
    diag.prepare_ms = a.prepare_ms;
    diag.motion_ms = a.flow_ms;
    const Remember remember{a, &previous_};
    has_pair_ = false;
    input_size_ = a.input_size;
    diag.repeated_frame = a.repeat;
    if (a.repeat) return repeatedMask(a);
    // A frame too small for the flow (DenseFlow) has no camera to measure: say so.
    diag.motion_fallback = !a.first_frame && a.flow.empty();
    if (a.first_frame || a.flow.empty()) return forget(a.bgr.size());
    Clock::time_point start = Clock::now();
    measureCamera(a);
    diag.motion_ms += millisecondsSince(start);
    describe(camera_, a.scale, &diag);

    start = Clock::now();
    levels_ = photometric_.fitLevels(a.grey);
    diag.scene_cut =
        isSceneCutUnderCamera(a.bgr, previous_.bgr, camera_map_, levels_, a.near_ignored);
    if (diag.scene_cut) return forget(a.bgr.size());
    diag.residual_scale = pairEvidence(a, debug);
    unaryOf(a);
    diag.classify_ms = millisecondsSince(start);

    start = Clock::now();
    cut_.cut(unary_, a.contrast, &diag.cut_nodes, &mask_);
    // Not where no camera was fitted (no motion is measured against it), nor where depth is
    // read: the flow at a near thing's occluding edge is neither its surface's nor the far
    // one's, and its residual across the epipolar lines makes regions there.
    if (params_.motion_regions && !camera_.fallback && !camera_.epipole) {
      diag.motion_regions = regions_.add(evidence_, unary_, one_patch_of_evidence_, &mask_);
    } else {
      regions_.forget(mask_.size());
    }
    if (!a.working_ignored.empty()) clearWhere(a.working_ignored, &mask_);  // nor carried on
    const cv::Mat mask = edge_snap_.snap(mask_, a.grey, params_.edge_snap, a.input_grey);
    diag.cut_ms = millisecondsSince(start);
    debug.put("residual", [&] { return drawResidual(residual_, diag.residual_scale); });
    debug.put("carried", [&] { return drawCarried(carried_, a.grey.size()); });
    debug.put("confirmation", [&] { return drawConfirmation(confirmation_); });
    debug.put("unary", [&] { return drawLogOdds(unary_); });
    debug.put("regions", [&] {  // white: motion apart from the mask taken into it
      cv::Mat picture;
      regions_.draw(&picture);
      return picture;
    });
    debug.put("edges", [&] {  // at the size of the mask returned
      cv::Mat cut;
      upscaledMask(mask_, mask.size(), &cut);
      return drawEdgeSnap(a.input_grey.empty() ? a.grey : a.input_grey, cut, mask);
    });
    return mask;
  }

  void reset() override {
    flow_.reset();
    repeats_.reset();
  }

  cv::Mat compensatedPreviousFrame() const override {
    if (!has_pair_) return cv::Mat();
    cv::Mat full;
    cv::resize(warpPrevious(previous_.before_bgr, previous_.bgr, to_current_), full, input_size_, 0,
               0, cv::INTER_LINEAR);
    return full;
  }

 private:
  // A stream's first pair, or the first after a scene cut: no mask to carry, no colours known.
  cv::Mat forget(cv::Size size) {
    colour_.reset();
    regions_.forget(size);
    depth_ = PersistentDepth();
    last_model_.reset();
    mask_.release();
    return cv::Mat::zeros(size, CV_8U);
  }

  // A repeated frame's mask: the last cut's, its outline snapped to the same edges again.
  cv::Mat repeatedMask(const DenseAnalysis& a) {
    if (mask_.empty()) return cv::Mat::zeros(a.bgr.size(), CV_8U);
    return edge_snap_.snap(mask_, a.grey, params_.edge_snap, a.input_grey);
  }

  // The previous mask carried by the flow (carried_), the camera fitted to the flow of the
  // background (camera_, its map camera_map_) and the residual motion (residual_).
  void measureCamera(const DenseAnalysis& a) {
    photometric_.followFlow(previous_.grey, mask_, a.flow_map, &carried_);
    camera_fitter_.fit(a.flow, a.samples, carried_, rng_, last_model_ ? &*last_model_ : nullptr,
                       &camera_);
    if (!camera_.fallback) last_model_ = camera_.model;
    depth_.settle(&camera_);
    cameraMap(camera_.model, a.grey.size(), &camera_map_);
    // With depth read, the residual and the photometric check measure against the same static
    // scene: one whose points may lie anywhere along their epipolar lines.
    if (camera_.epipole) alongEpipolarLines(a.flow_map, *camera_.epipole, &camera_map_);
    residualMotion(a.flow_map, camera_map_, &residual_);
    // The fit maps current to previous working pixels; eq. (4) warps previous to current.
    to_current_ = camera_.model.inv();
    has_pair_ = true;
  }

  // The pair's own evidence (evidence_): the residual in units of the background's (the scale,
  // returned), confirmed or refuted by the photometric check, none for motion where the last
  // mover uncovered the background, nothing either way within the flow's reach of the ignored
  // region (colour learns nothing there).
  float pairEvidence(const DenseAnalysis& a, const DebugSink& debug) {
    photometric_.confirm(a.grey, camera_map_, levels_, a.near_ignored, params_, &confirmation_);
    sample_residuals_.reserve(a.samples.size());  // at most one per sample: they do not grow
    unconfirmed_.reserve(a.samples.size());
    const float scale = residualScale(
        unconfirmedResiduals(camera_, confirmation_, &sample_residuals_, &unconfirmed_), params_);
    motionEvidence(residual_, scale, params_, &evidence_);
    confirmMotion(confirmation_, params_, &evidence_);
    const bool uncovers = !carried_.empty() && params_.uncovered;
    if (uncovers) dropUncovered(carried_, mask_, camera_map_, &evidence_);
    if (!a.near_ignored.empty()) clearWhere(a.near_ignored, &evidence_);
    // White: background the last frame's mover uncovered (mask_ is still that frame's here).
    debug.put("uncovered", [&] {
      cv::Mat picture = cv::Mat::zeros(a.grey.size(), CV_8U);
      if (uncovers) uncoveredPixels(carried_, mask_, camera_map_, &picture);
      return picture;
    });
    return scale;
  }

  // The cut's unary (unary_): the pair's evidence, memory, colour and the prior; the colour
  // models then learn from this frame.
  void unaryOf(const DenseAnalysis& a) {
    // The pair's evidence is kept for the colour model: memory goes into an image of its own.
    const cv::Mat* remembered = &evidence_;
    if (!carried_.empty()) {
      addMemory(carried_, params_, evidence_, &with_memory_);
      remembered = &with_memory_;
    }
    colour_.addEvidence(a.bgr, *remembered, &unary_);
    addBias(params_.foreground_bias, &unary_);
    colour_.update(a.bgr, *remembered, evidence_);
  }

  static void describe(const FlowCamera& camera, double working_scale, Diagnostics* diag) {
    // The fit maps current to previous working pixels; diagnostics speak of previous to
    // current, at full resolution.
    diag->model = rescaleModel(camera.model.inv(), 1.0 / working_scale);
    diag->model *= 1.0 / diag->model(2, 2);
    diag->model_is_affine = isAffine(diag->model);
    diag->matches = static_cast<int>(camera.at.size());
    diag->motion_fallback = camera.fallback;
    diag->parallax = camera.epipole.has_value();
  }

  Params params_;
  DenseFlow flow_;
  FlowCameraFitter camera_fitter_;
  FlowCamera camera_;  // the pair's, in the buffers of the last
  std::vector<float> sample_residuals_, unconfirmed_;  // scratch of unconfirmedResiduals()
  ColourModel colour_;
  cv::RNG rng_;
  const double one_patch_of_evidence_;
  cv::Mat mask_;  // the last frame's, at the working scale
  // The pair's images, in the buffers of the last pair's.
  cv::Mat carried_, evidence_, unary_, residual_, confirmation_;
  cv::Mat with_memory_;  // the pair's evidence (evidence_) with the carried mask's added
  cv::Mat camera_map_;
  PhotometricCheck photometric_;
  LevelMap levels_;  // the pair's change of light
  EvidenceCut cut_;
  MotionRegions regions_;
  EdgeSnap edge_snap_;
  PersistentDepth depth_;
  RepeatedFrames repeats_;  // phase 1's, as the flow
  IgnoredRegion ignored_;   // phase 1's
  // The last fitted camera model, the next fit's warm start: a pair that fell back to the
  // identity leaves it as it was, a scene cut forgets it (a model must come from the scene it
  // is tried on).
  std::optional<cv::Matx33d> last_model_;
  PreviousFrame previous_;
  bool has_pair_ = false;    // the last frame had a camera model: eq. (4)'s I' can be made
  cv::Matx33d to_current_;  // that model, previous to current working pixels
  cv::Size input_size_;
  cv::Mat halved_;  // scratch of downscale()
  FramePool bgr_buffers_, grey_buffers_;  // of the analyses' images, which Remember keeps
};

}  // namespace

std::unique_ptr<Pipeline> makeDensePipeline(const Params& params) {
  return std::make_unique<DensePipeline>(params);
}

}  // namespace movseg
