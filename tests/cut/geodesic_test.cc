// §3.3 geodesic distances: the raster scan must equal the true shortest path.
#include <limits>
#include <queue>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "cut/geodesic.h"
#include "test_support.h"

namespace movseg {
namespace {

// Dijkstra on the same 8-connected grid and step cost, the reference.
cv::Mat dijkstra(const cv::Mat& colour, double gamma, const std::vector<cv::Point>& seeds) {
  cv::Mat dist(colour.size(), CV_64F, cv::Scalar(std::numeric_limits<double>::infinity()));
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (const cv::Point& s : seeds) {
    dist.at<double>(s) = 0;
    queue.push({0.0, s.y * colour.cols + s.x});
  }
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    const cv::Point p(i % colour.cols, i / colour.cols);
    if (d > dist.at<double>(p)) continue;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const cv::Point q(p.x + dx, p.y + dy);
        if ((dx == 0 && dy == 0) || q.x < 0 || q.y < 0 || q.x >= colour.cols || q.y >= colour.rows) continue;
        const cv::Vec3f c = colour.at<cv::Vec3f>(p) - colour.at<cv::Vec3f>(q);
        const double step = std::sqrt(dx * dx + dy * dy + gamma * gamma * c.dot(c));
        if (d + step < dist.at<double>(q)) {
          dist.at<double>(q) = d + step;
          queue.push({d + step, q.y * colour.cols + q.x});
        }
      }
    }
  }
  return dist;
}

cv::Mat toColour(const cv::Mat& bgr) {
  cv::Mat colour;
  bgr.convertTo(colour, CV_32FC3, 1.0 / 255.0);
  return colour;
}

TEST(Geodesic, FlatImageGivesTheChamferDistance) {
  const cv::Mat colour = toColour(cv::Mat(5, 7, CV_8UC3, cv::Scalar(10, 20, 30)));
  const cv::Mat d = GeodesicGrid(colour, 40).distanceFrom({{0, 0}}, 1);
  EXPECT_FLOAT_EQ(d.at<float>(0, 6), 6.f);                                   // six steps right
  EXPECT_NEAR(d.at<float>(4, 4), 4 * std::sqrt(2.f), 1e-5);                   // four diagonal
  EXPECT_NEAR(d.at<float>(4, 6), 4 * std::sqrt(2.f) + 2, 1e-5);
}

TEST(Geodesic, EqualsDijkstraOnAWindingMaze) {
  // A bright wall with one gap forces paths around it: the raster scan needs its sweeps.
  cv::Mat bgr(40, 50, CV_8UC3, cv::Scalar(40, 40, 40));
  cv::rectangle(bgr, cv::Rect(10, 0, 3, 34), cv::Scalar(250, 250, 250), cv::FILLED);
  cv::rectangle(bgr, cv::Rect(25, 6, 3, 34), cv::Scalar(250, 250, 250), cv::FILLED);
  cv::rectangle(bgr, cv::Rect(38, 0, 3, 34), cv::Scalar(250, 250, 250), cv::FILLED);
  const cv::Mat colour = toColour(bgr);
  const std::vector<cv::Point> seeds{{2, 2}, {45, 3}};
  const cv::Mat expected = dijkstra(colour, 40, seeds);
  const cv::Mat got = GeodesicGrid(colour, 40).distanceFrom(seeds, 4);
  for (int y = 0; y < got.rows; ++y)
    for (int x = 0; x < got.cols; ++x)
      ASSERT_NEAR(got.at<float>(y, x), expected.at<double>(y, x), 1e-3 * expected.at<double>(y, x) + 1e-4)
          << "at " << x << "," << y;
}

TEST(Geodesic, EqualsDijkstraOnTexture) {
  const cv::Mat colour = toColour(test::texture({60, 45}, 11));
  const std::vector<cv::Point> seeds{{5, 5}, {50, 30}, {20, 40}};
  const cv::Mat expected = dijkstra(colour, 10, seeds);
  auto worstRelativeError = [&](const cv::Mat& got) {
    double worst = 0;
    for (int y = 0; y < got.rows; ++y)
      for (int x = 0; x < got.cols; ++x)
        worst = std::max(worst, std::abs(got.at<float>(y, x) - expected.at<double>(y, x)) /
                                    std::max(1.0, expected.at<double>(y, x)));
    return worst;
  };
  const GeodesicGrid grid(colour, 10);
  EXPECT_LT(worstRelativeError(grid.distanceFrom(seeds, 100)), 1e-4);  // run to convergence
  // Few sweeps overestimate only where shortest paths wind a lot (this texture is a hard case).
  EXPECT_LT(worstRelativeError(grid.distanceFrom(seeds, 2)), 0.2);
  EXPECT_LT(worstRelativeError(grid.distanceFrom(seeds, 1)), 0.5);
}

// A column and a row one pixel wide: the sweeps' loops along a row and across rows meet their
// ends at once, and the distances are Dijkstra's.
TEST(Geodesic, OnePixelWideImagesEqualDijkstra) {
  for (const cv::Size size : {cv::Size(1, 40), cv::Size(40, 1), cv::Size(1, 1)}) {
    const cv::Mat colour = toColour(test::texture(size, 3));
    const std::vector<cv::Point> seeds{{0, 0}};
    const cv::Mat expected = dijkstra(colour, 10, seeds);
    const cv::Mat got = GeodesicGrid(colour, 10).distanceFrom(seeds, 1);
    for (int i = 0; i < static_cast<int>(got.total()); ++i) {
      EXPECT_NEAR(got.at<float>(i), expected.at<double>(i), 1e-3 * (1 + expected.at<double>(i)))
          << size << " at " << i;
    }
  }
}

TEST(Geodesic, NoSeedsMeansInfinitelyFar) {
  const cv::Mat colour = toColour(cv::Mat(4, 4, CV_8UC3, cv::Scalar(0)));
  const cv::Mat d = GeodesicGrid(colour, 1).distanceFrom({}, 1);
  EXPECT_TRUE(std::isinf(d.at<float>(2, 2)));
}

}  // namespace
}  // namespace movseg
