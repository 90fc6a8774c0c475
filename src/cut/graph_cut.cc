#include "cut/graph_cut.h"

#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>
#include <opencv2/imgproc/detail/gcgraph.hpp>

#include "cut/geodesic.h"

namespace movseg {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Eq. (9), (10) from the two distance maps; distances are divided by the image width so that
// u(x) does not depend on the working resolution.
struct Unaries {
  cv::Mat cost_fg, cost_bg;  // R_F, R_B of eq. (7) without the seed constraint
  cv::Mat confidence;        // u
};

Unaries geodesicUnaries(const cv::Mat& d_fg, const cv::Mat& d_bg) {
  Unaries out{cv::Mat(d_fg.size(), CV_32F), cv::Mat(d_fg.size(), CV_32F),
              cv::Mat(d_fg.size(), CV_32F)};
  const float norm = 1.0f / static_cast<float>(d_fg.cols);
  for (int y = 0; y < d_fg.rows; ++y) {
    const float* f = d_fg.ptr<float>(y);
    const float* b = d_bg.ptr<float>(y);
    float* rf = out.cost_fg.ptr<float>(y);
    float* rb = out.cost_bg.ptr<float>(y);
    float* u = out.confidence.ptr<float>(y);
    for (int x = 0; x < d_fg.cols; ++x) {
      const float df = f[x] * norm, db = b[x] * norm, sum = df + db;
      if (sum <= 0.f) {  // cannot happen with seeds of both kinds apart; stay finite anyway
        rf[x] = rb[x] = u[x] = 0.f;
        continue;
      }
      u[x] = (df - db) * (df - db) / sum;  // eq. (10)
      rf[x] = u[x] * df / sum;              // u * G_F, eq. (9)
      rb[x] = u[x] * db / sum;
    }
  }
  return out;
}

// Contrast normalisation of eq. (11): |C_i - C_j|^2 is scaled by beta = 1 / (2 <|dC|^2>) so the
// pairwise term reacts to the image's own contrast at any bit depth (as GrabCut does).
double contrastScale(const cv::Mat& colour) {
  double sum = 0;
  long count = 0;
  for (int y = 0; y < colour.rows; ++y) {
    const auto* row = colour.ptr<cv::Vec3f>(y);
    const auto* below = y + 1 < colour.rows ? colour.ptr<cv::Vec3f>(y + 1) : nullptr;
    for (int x = 0; x < colour.cols; ++x) {
      if (x + 1 < colour.cols) sum += cv::norm(row[x] - row[x + 1], cv::NORM_L2SQR), ++count;
      if (below) sum += cv::norm(row[x] - below[x], cv::NORM_L2SQR), ++count;
    }
  }
  return sum > 0 ? count / (2 * sum) : 0;
}

}  // namespace

CutResult geodesicGraphCut(const cv::Mat& bgr, const std::vector<cv::Point>& foreground,
                           const std::vector<cv::Point>& background, const Params& params) {
  const GeodesicGrid grid(bgr, params.geodesic_gamma);
  const Unaries unary =
      geodesicUnaries(grid.distanceFrom(foreground), grid.distanceFrom(background));

  // Eq. (8): seeds are hard constraints.
  cv::Mat cost_fg = unary.cost_fg.clone(), cost_bg = unary.cost_bg.clone();
  for (const cv::Point& p : foreground) cost_bg.at<float>(p) = kInfinity;
  for (const cv::Point& p : background) cost_fg.at<float>(p) = kInfinity;

  cv::Mat colour;
  bgr.convertTo(colour, CV_32FC3, 1.0 / 255.0);
  const double beta = contrastScale(colour);
  const int w = bgr.cols, h = bgr.rows, n = w * h;
  cv::detail::GCGraph<float> graph(static_cast<unsigned>(n), static_cast<unsigned>(4 * n));
  for (int y = 0; y < h; ++y) {
    const auto* c = colour.ptr<cv::Vec3f>(y);
    const float* u = unary.confidence.ptr<float>(y);
    const float* rf = cost_fg.ptr<float>(y);
    const float* rb = cost_bg.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      const int i = graph.addVtx();
      // Source = foreground: the source edge is cut when the pixel is background.
      graph.addTermWeights(i, std::isinf(rb[x]) ? 1e9f : rb[x], std::isinf(rf[x]) ? 1e9f : rf[x]);
      auto pairwise = [&](const cv::Vec3f& other, float u_other) {  // eq. (11)
        const double b = (1.0 + 0.5 * (u[x] + u_other)) /
                         (1.0 + beta * cv::norm(c[x] - other, cv::NORM_L2SQR));
        return static_cast<float>(params.cut_weight * b);
      };
      if (x > 0) {
        const float wgt = pairwise(c[x - 1], u[x - 1]);
        graph.addEdges(i, i - 1, wgt, wgt);
      }
      if (y > 0) {
        const float wgt = pairwise(colour.ptr<cv::Vec3f>(y - 1)[x],
                                   unary.confidence.ptr<float>(y - 1)[x]);
        graph.addEdges(i, i - w, wgt, wgt);
      }
    }
  }
  graph.maxFlow();

  CutResult result;
  result.mask.create(bgr.size(), CV_8U);
  for (int i = 0; i < n; ++i) result.mask.data[i] = graph.inSourceSegment(i) ? 255 : 0;
  result.confidence = unary.confidence;
  result.graph_nodes = n;
  return result;
}

}  // namespace movseg
