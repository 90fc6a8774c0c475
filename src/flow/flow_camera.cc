#include "flow/flow_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/core/hal/intrin.hpp>

#include "core/quantile.h"
#include "motion/estimators.h"
#include "motion/model.h"
#include "motion/ransac.h"
#include "motion/support.h"

namespace movseg {
namespace {

// A fit needs this many samples, and this share of them, before the ones believed to move can
// be left out (a large mover would otherwise leave a few background samples to be outvoted).
constexpr size_t kMinBackgroundSamples = 50;
constexpr double kMinBackgroundShare = 0.3;

// Index v of a row or column of n pixels, reflected as OpenCV's default border (101) outside.
int reflected(int v, int n) {
  return v >= 0 && v < n ? v : cv::borderInterpolate(v, n, cv::BORDER_REFLECT_101);
}

// `textures`: scratch.
float textureQuantile(const std::vector<GridSample>& samples, double q,
                      std::vector<float>* textures) {
  if (samples.empty()) return 0.f;
  textures->clear();
  for (const GridSample& s : samples) textures->push_back(s.texture);
  return quantile(textures, q);
}

float squaredDistance(const cv::Point2f& x, const cv::Point2f& y) {
  const float dx = y.x - x.x, dy = y.y - x.y;
  return dx * dx + dy * dy;
}

// Residual motion of a point: from where the camera puts it, x, to where the flow does, y.
float residualOf(const cv::Point2f& x, const cv::Point2f& y, const FlowCamera& camera) {
  if (camera.epipole) return static_cast<float>(EpipoleEstimator::offLine(x, y, *camera.epipole));
  // Flow distances cannot overflow: hypot's care is not needed.
  return std::sqrt(squaredDistance(x, y));
}

// Depth is read from the samples off the camera's plane (more than twice the inlier distance)
// when enough of them agree on one epipole and they show depth in one of three ways (DepthRule).
// A few stray vectors say nothing about the scene: never fewer than kMinOffPlane.
// All samples count, also those the carried mask says move (the camera's own fit leaves them
// out): a post the mask once took for a mover must still show as depth, or the mistake would
// keep itself.
constexpr size_t kMinOffPlane = 20;

// How a static 3-D scene seen by a translating camera shows itself: off-plane samples, at
// least `share` of all samples, of which at least `agreement` agree on the epipole, over at
// least `cells` of CoverageSupportMeasurer's 8x8 cells, and of those at least `with_plane`
// displaced the way the plane itself is.
struct DepthRule {
  double share;
  int cells;
  double with_plane;
  double agreement;
};
// Depth everywhere: the ground, near posts, walls, while movers that happen to agree on an
// epipole are local. On our synthetic sets (three seeds) a dolly past posts covers 28 cells or
// more on 31 to 48 pairs of 59, the planar scenes with movers on none.
constexpr DepthRule kDepthEverywhere{0.2, 28, 0.0, 0.5};
// Less of it (a ground below a far wall, a few posts: scripts/indep_synth.py's dolly shows
// 13-22 % of the samples over 16-29 cells), displaced with the plane: when the plane is the far
// background, nearer static points move as it does, only further (parallax has the sign of
// inverse depth), and a camera that moves shifts the plane by more than the inlier distance. A
// mover the camera follows stands still in the image, against the plane: per pair 0-26 % of the
// agreeing samples with the plane on DAVIS's cars, swan, scooter, kite-surf and goat, whose
// movers agree on an epipole over 18-28 cells as well; 70-100 % on the dolly.
constexpr DepthRule kDepthWithThePlane{0.1, 16, 0.75, 0.5};
// Less still, agreeing better: fewer samples must agree more to say the same. The independent
// dolly's ground below its wall shows 5-10 % of the samples off the plane on most pairs, of
// which 91-99 % agree on the epipole where it is fitted (rather than half): depth read there
// takes the independent dolly 0.202 -> 0.213 (seeds 24-47: 0.193 -> 0.214), DAVIS, our 57
// sequences and the independent planes the same (docs/design.md, "Parallax").
// Of those agreeing, only more than a followed mover shows with the plane (its 0-26 % above):
// where the plane is fitted at a middle depth (the ground) the static scene lies on both sides
// of it, nearer points displaced with it and farther ones against (the independent dolly seed
// 16: 25-64 % with it on its pairs, 87-96 % agreeing; with three quarters asked here it never
// read depth, J 0.00 -> 0.27). Movers on a plane that happen to agree on an epipole show both
// signs too, but agree less (our planar pans: 52-76 %). The independent dolly 0.364 -> 0.384
// (seeds 24-47: 0.308 -> 0.316); DAVIS, our 57 sequences, the independent planes the same.
constexpr DepthRule kDepthAgreed{0.05, 16, 0.3, 0.9};
constexpr DepthRule kDepthRules[] = {kDepthEverywhere, kDepthWithThePlane, kDepthAgreed};

bool shows(const DepthRule& rule, double share, int cells, double with_plane, double agreement) {
  return share >= rule.share && cells >= rule.cells && with_plane >= rule.with_plane &&
         agreement >= rule.agreement;
}

// Of the off-plane samples x -> y that agree on the epipole (residuals within the inlier
// distance), the share displaced the way the plane displaces them (plane_step), by more than
// the inlier distance.
double shareWithThePlane(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                         const std::vector<cv::Point2f>& plane_step,
                         const std::vector<double>& residuals, const RansacOptions& options) {
  const double inlier = options.max_error * options.max_error;
  size_t agreeing = 0, with_plane = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (residuals[i] > inlier) continue;
    ++agreeing;
    with_plane += (y[i] - x[i]).dot(plane_step[i]) > 0 &&
                  cv::norm(plane_step[i]) > options.max_error;
  }
  return agreeing == 0 ? 0.0 : static_cast<double>(with_plane) / static_cast<double>(agreeing);
}

}  // namespace

namespace {

// minEigenValueAt's window and its sums of products of 3x3 Sobel derivatives (exact integers).
constexpr int kWindow = 5;
struct StructureSums {
  std::int64_t xx = 0, xy = 0, yy = 0;
};

// The sums where the window reaches the frame's border. Reflected as OpenCV reflects the
// derivative images: a window pixel outside the frame takes the derivatives of its mirror image
// inside, whose 3x3 neighbourhood is reflected in turn. Row and column indices are worked out
// once per sample, not once per derivative.
StructureSums reflectedStructureSums(const cv::Mat& grey, cv::Point p) {
  const uchar* rows[kWindow][3];
  int columns[kWindow][3];
  for (int j = 0; j < kWindow; ++j) {
    const int y = reflected(p.y + j - kWindow / 2, grey.rows);
    const int x = reflected(p.x + j - kWindow / 2, grey.cols);
    for (int k = 0; k < 3; ++k) {
      rows[j][k] = grey.ptr<uchar>(reflected(y + k - 1, grey.rows));
      columns[j][k] = reflected(x + k - 1, grey.cols);
    }
  }
  StructureSums sums;
  for (int j = 0; j < kWindow; ++j) {
    const uchar* const* r = rows[j];
    for (int i = 0; i < kWindow; ++i) {
      const int* c = columns[i];
      const int dx = (r[0][c[2]] - r[0][c[0]]) + 2 * (r[1][c[2]] - r[1][c[0]]) +
                     (r[2][c[2]] - r[2][c[0]]);
      const int dy = (r[2][c[0]] - r[0][c[0]]) + 2 * (r[2][c[1]] - r[0][c[1]]) +
                     (r[2][c[2]] - r[0][c[2]]);
      sums.xx += dx * dx;
      sums.xy += dx * dy;
      sums.yy += dy * dy;
    }
  }
  return sums;
}

// Whether the sample's window and the derivatives' neighbourhoods are inside the frame, with one
// more column on the left for insideStructureSums' loads of eight pixels.
bool insideFrame(const cv::Mat& grey, cv::Point p) {
  const int reach = kWindow / 2 + 1;
  return p.x >= reach + 1 && p.x + reach < grey.cols && p.y >= reach && p.y + reach < grey.rows;
}

// The same sums inside the frame, the window's five columns in eight 16-bit lanes: each of the
// seven rows that the window's derivatives read is loaded once (columns x - 4 to x + 3) and
// gives its difference across (x + 1 - (x - 1)) and its smoothing across (1 2 1) at the five
// columns, which the rows below combine into Sobel's derivatives. Every value fits its lanes:
// derivatives within +-1020, a window's sums of products under 2^31 (25 x 1020^2).
StructureSums insideStructureSums(const cv::Mat& grey, cv::Point p) {
  constexpr int kRows = kWindow + 2;
  cv::v_int16x8 across[kRows], smoothed[kRows];
  for (int k = 0; k < kRows; ++k) {
    const uchar* row = grey.ptr<uchar>(p.y - kRows / 2 + k) + p.x - kWindow / 2 - 2;
    const auto pixels = cv::v_reinterpret_as_s16(cv::v_load_expand(row));
    const cv::v_int16x8 left = cv::v_rotate_right<1>(pixels);  // lane i: column x - 3 + i
    const cv::v_int16x8 centre = cv::v_rotate_right<2>(pixels);
    const cv::v_int16x8 right = cv::v_rotate_right<3>(pixels);
    across[k] = right - left;
    smoothed[k] = left + centre + centre + right;
  }
  const cv::v_int16x8 window_columns(-1, -1, -1, -1, -1, 0, 0, 0);
  cv::v_int32x4 xx = cv::v_setzero_s32(), xy = xx, yy = xx;
  for (int j = 0; j < kWindow; ++j) {
    const cv::v_int16x8 dx = across[j] + across[j + 1] + across[j + 1] + across[j + 2];
    const cv::v_int16x8 dy = smoothed[j + 2] - smoothed[j];
    const cv::v_int16x8 dx_window = dx & window_columns, dy_window = dy & window_columns;
    xx += cv::v_dotprod(dx_window, dx);
    xy += cv::v_dotprod(dx_window, dy);
    yy += cv::v_dotprod(dy_window, dy);
  }
  return {cv::v_reduce_sum(xx), cv::v_reduce_sum(xy), cv::v_reduce_sum(yy)};
}

}  // namespace

float minEigenValueAt(const cv::Mat& grey, cv::Point p) {
  const StructureSums sums =
      insideFrame(grey, p) ? insideStructureSums(grey, p) : reflectedStructureSums(grey, p);
  // cornerMinEigenVal's normalisation: Sobel's weight (4), the window side, 8-bit range. The
  // sums of products of integer derivatives are exact; the scale comes last.
  constexpr double kScale = 1.0 / (4 * kWindow * 255.0);
  const double a = static_cast<double>(sums.xx) * kScale * kScale / 2;
  const double b = static_cast<double>(sums.xy) * kScale * kScale;
  const double c = static_cast<double>(sums.yy) * kScale * kScale / 2;
  return static_cast<float>((a + c) - std::sqrt((a - c) * (a - c) + b * b));
}

void gridSamples(const cv::Mat& grey, int step, const cv::Mat& ignored,
                 std::vector<GridSample>* samples) {
  samples->clear();
  for (int y = step / 2; y < grey.rows; y += step) {
    for (int x = step / 2; x < grey.cols; x += step) {
      if (!ignored.empty() && ignored.at<uchar>(y, x) != 0) continue;
      samples->push_back({{x, y}, minEigenValueAt(grey, {x, y})});
    }
  }
}

namespace {

RansacOptions ransacOptions(const Params& params) {
  RansacOptions options;
  options.max_trials = params.ransac_iterations;
  options.max_error = params.flow_inlier_distance;
  options.sample_grid = params.ransac_grid;
  return options;
}

}  // namespace

FlowCameraFitter::FlowCameraFitter(const Params& params)
    : params_(params),
      options_(ransacOptions(params)),
      homography_(options_),
      epipole_(options_) {}

void FlowCameraFitter::fit(const cv::Mat& flow, const std::vector<GridSample>& grid,
                           const cv::Mat& moving, cv::RNG& rng,
                           const cv::Matx33d* previous_model, FlowCamera* camera) {
  camera->model = cv::Matx33d::eye();
  camera->at.clear();
  camera->to.clear();
  camera->background.clear();
  camera->fallback = false;
  camera->epipole.reset();
  camera->depth_with_the_plane = false;
  // An element per sample at most: reserved at once, the vectors do not grow pair after pair as
  // more samples are kept.
  for (auto* points : {&camera->at, &camera->to, &x_, &y_, &plane_step_}) {
    points->reserve(grid.size());
  }
  camera->background.reserve(grid.size());
  residuals_.reserve(grid.size());
  coverage_.reserve(grid.size());
  homography_.reserve(grid.size());
  epipole_.reserve(grid.size());
  const float flat = textureQuantile(grid, params_.flow_texture_quantile, &textures_);
  size_t background = 0;
  for (const GridSample& s : grid) {
    // No gradient in the window, no motion to measure: DIS gives such a sample its neighbours'
    // flow or none, so a flat frame (or a letterbox's bars) would otherwise fit the identity.
    if (s.texture < flat || s.texture <= 0) continue;
    const cv::Vec2f f = flow.at<cv::Vec2f>(s.at);
    camera->at.emplace_back(s.at);
    camera->to.emplace_back(static_cast<float>(s.at.x) + f[0], static_cast<float>(s.at.y) + f[1]);
    camera->background.push_back(moving.empty() || moving.at<uchar>(s.at) <= 127);
    background += camera->background.back();
  }
  if (background < std::max<size_t>(kMinBackgroundSamples,
                                    static_cast<size_t>(kMinBackgroundShare * camera->at.size()))) {
    std::fill(camera->background.begin(), camera->background.end(), 1);
  }
  if (params_.static_camera) return;  // §4.1: the identity, nothing to fit
  x_.clear();
  y_.clear();
  for (size_t i = 0; i < camera->at.size(); ++i) {
    if (!camera->background[i]) continue;
    x_.push_back(camera->at[i]);
    y_.push_back(camera->to[i]);
  }
  const auto& report = homography_.estimate(x_, y_, flow.size(), rng, previous_model);
  camera->fallback = !report.success;
  if (report.success) camera->model = report.model;
  if (report.success && params_.parallax) findEpipole(flow.size(), rng, camera);
}

void FlowCameraFitter::findEpipole(cv::Size size, cv::RNG& rng, FlowCamera* camera) {
  x_.clear();
  y_.clear();
  plane_step_.clear();
  for (size_t i = 0; i < camera->at.size(); ++i) {
    const cv::Point2f on_plane = applyModel(camera->model, camera->at[i]);
    if (cv::norm(camera->to[i] - on_plane) <= 2 * options_.max_error) continue;
    x_.push_back(on_plane);
    y_.push_back(camera->to[i]);
    plane_step_.push_back(on_plane - camera->at[i]);
  }
  const double share = static_cast<double>(x_.size()) / static_cast<double>(camera->at.size());
  // Too few off the plane, or too few of them agreeing, for any rule: no epipole.
  double least_share = 1, least_agreement = 1;
  for (const DepthRule& rule : kDepthRules) {
    least_share = std::min(least_share, rule.share);
    least_agreement = std::min(least_agreement, rule.agreement);
  }
  if (x_.size() < kMinOffPlane || share < least_share) return;
  const auto& report = epipole_.estimate(x_, y_, size, rng);
  const double agreement =
      static_cast<double>(report.num_inliers) / static_cast<double>(x_.size());
  if (!report.success || agreement < least_agreement) return;
  EpipoleEstimator::residuals(x_, y_, report.model, &residuals_);
  coverage_.reset(x_, size);
  const int cells =
      coverage_.evaluate(residuals_, options_.max_error * options_.max_error).cells;
  const double with_share = shareWithThePlane(x_, y_, plane_step_, residuals_, options_);
  const auto depth = [&](const DepthRule& rule) {
    return shows(rule, share, cells, with_share, agreement);
  };
  if (std::none_of(std::begin(kDepthRules), std::end(kDepthRules), depth)) return;
  camera->epipole = report.model;
  camera->depth_with_the_plane =
      std::any_of(std::begin(kDepthRules), std::end(kDepthRules),
                  [&](const DepthRule& rule) { return rule.with_plane > 0 && depth(rule); });
}

void residualMotion(const cv::Mat& flow_map, const cv::Mat& camera_map, cv::Mat* residual) {
  residual->create(flow_map.size(), CV_32F);
  for (int y = 0; y < flow_map.rows; ++y) {
    const auto* by_flow = flow_map.ptr<cv::Point2f>(y);
    const auto* by_scene = camera_map.ptr<cv::Point2f>(y);
    float* r = residual->ptr<float>(y);
    // Squared here, rooted below: std::sqrt (errno) would keep this loop from vectorising.
    for (int x = 0; x < flow_map.cols; ++x) r[x] = squaredDistance(by_scene[x], by_flow[x]);
  }
  cv::sqrt(*residual, *residual);
}

void alongEpipolarLines(const cv::Mat& flow_map, const cv::Vec3d& epipole, cv::Mat* camera_map) {
  const cv::Vec3f e(epipole);
  for (int y = 0; y < flow_map.rows; ++y) {
    const auto* by_flow = flow_map.ptr<cv::Point2f>(y);
    auto* on_plane = camera_map->ptr<cv::Point2f>(y);
    for (int x = 0; x < flow_map.cols; ++x) {
      // The line's direction from the epipole, x * e_w - (e_x, e_y): defined at infinity too.
      const cv::Point2f p = on_plane[x];
      const cv::Point2f direction(p.x * e[2] - e[0], p.y * e[2] - e[1]);
      const float length2 = direction.dot(direction);
      if (length2 > 0) on_plane[x] = p + direction * ((by_flow[x] - p).dot(direction) / length2);
    }
  }
}

void flowMap(const cv::Mat& flow, cv::Mat* map) {
  map->create(flow.size(), CV_32FC2);
  const int floats = 2 * flow.cols;
  for (int y = 0; y < flow.rows; ++y) {
    const float* f = flow.ptr<float>(y);
    float* m = map->ptr<float>(y);
    // Two pixels (x, y) and (x + 1, y) at a time, interleaved as the flow is.
    const auto fy = static_cast<float>(y);
    const cv::v_float32x4 two_pixels(0.f, fy, 1.f, fy), two(2.f, 0.f, 2.f, 0.f);
    cv::v_float32x4 at = two_pixels;
    int i = 0;
    for (; i + 4 <= floats; i += 4, at += two) cv::v_store(m + i, at + cv::v_load(f + i));
    for (; i < floats; i += 2) m[i] = static_cast<float>(i / 2) + f[i], m[i + 1] = fy + f[i + 1];
  }
}

void cameraMap(const cv::Matx33d& model, cv::Size size, cv::Mat* map) {
  map->create(size, CV_32FC2);
  const cv::Matx33f m(model);
  using cv::v_float32x4;
  const auto all = [](float v) { return cv::v_setall_f32(v); };
  for (int y = 0; y < size.height; ++y) {
    float* out = map->ptr<float>(y);
    const float fy = static_cast<float>(y);
    // Each row's terms in y once; the sums in the order of the scalar expression below.
    const float wy = m(2, 1) * fy, xy = m(0, 1) * fy, yy = m(1, 1) * fy;
    int x = 0;
    for (v_float32x4 fx(0.f, 1.f, 2.f, 3.f); x + 4 <= size.width; x += 4, fx += all(4.f)) {
      const v_float32x4 w = all(m(2, 0)) * fx + all(wy) + all(m(2, 2));
      const v_float32x4 to_x = (all(m(0, 0)) * fx + all(xy) + all(m(0, 2))) / w;
      const v_float32x4 to_y = (all(m(1, 0)) * fx + all(yy) + all(m(1, 2))) / w;
      v_float32x4 pixels[2];
      cv::v_zip(to_x, to_y, pixels[0], pixels[1]);
      cv::v_store(out + 2 * x, pixels[0]);
      cv::v_store(out + 2 * x + 4, pixels[1]);
    }
    for (; x < size.width; ++x) {
      const float fx = static_cast<float>(x);
      const float w = m(2, 0) * fx + wy + m(2, 2);
      out[2 * x] = (m(0, 0) * fx + xy + m(0, 2)) / w;
      out[2 * x + 1] = (m(1, 0) * fx + yy + m(1, 2)) / w;
    }
  }
}

void residualAtSamples(const FlowCamera& camera, std::vector<float>* residuals) {
  residuals->resize(camera.at.size());
  for (size_t i = 0; i < camera.at.size(); ++i) {
    (*residuals)[i] = residualOf(applyModel(camera.model, camera.at[i]), camera.to[i], camera);
  }
}

}  // namespace movseg
