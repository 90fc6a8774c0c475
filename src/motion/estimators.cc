#include "motion/estimators.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

#include "motion/model.h"

namespace movseg {
namespace {

// OpenCV built with Eigen (as Ubuntu's and Debian's are) solves in cv::eigen with Eigen's
// SelfAdjointEigenSolver on a dynamic-size matrix, on the heap. The same solver on a dynamic-size
// matrix of fixed capacity takes the same steps without allocating (tests/motion compares the
// two).
template <int n>
bool smallestEigenvectorOf(const cv::Matx<double, n, n>& m, cv::Vec<double, n>* vector) {
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, n, n>;
  Matrix a(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) a(i, j) = m(i, j);
  }
  const Eigen::SelfAdjointEigenSolver<Matrix> solver(a);
  if (solver.info() != Eigen::Success) return false;
  for (int i = 0; i < n; ++i) (*vector)[i] = solver.eigenvectors()(i, 0);  // ascending values
  return true;
}

void squaredTransferErrors(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                           const cv::Matx33d& model, std::vector<double>* residuals) {
  residuals->resize(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const cv::Point2f d = applyModel(model, x[i]) - y[i];
    (*residuals)[i] = static_cast<double>(d.x) * d.x + static_cast<double>(d.y) * d.y;
  }
}

}  // namespace

bool smallestEigenvector(const cv::Matx33d& m, cv::Vec3d* vector) {
  return smallestEigenvectorOf(m, vector);
}

bool smallestEigenvector(const cv::Matx<double, 9, 9>& m, cv::Vec<double, 9>* vector) {
  return smallestEigenvectorOf(m, vector);
}

// Least squares (exact for 3 points) through the normal equations of [x y 1] * row = target,
// in coordinates centred on the points' mean so the system stays well conditioned.
bool AffineEstimator::estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                               cv::Matx33d* model) {
  if (x.size() < kMinNumSamples || x.size() != y.size()) return false;
  cv::Point2d cx(0, 0), cy(0, 0);
  for (size_t i = 0; i < x.size(); ++i) {
    cx += cv::Point2d(x[i]);
    cy += cv::Point2d(y[i]);
  }
  cx /= static_cast<double>(x.size());
  cy /= static_cast<double>(y.size());
  cv::Matx22d normal = cv::Matx22d::zeros();
  cv::Matx22d rhs = cv::Matx22d::zeros();  // columns: target u, target v
  for (size_t i = 0; i < x.size(); ++i) {
    const cv::Point2d p = cv::Point2d(x[i]) - cx, q = cv::Point2d(y[i]) - cy;
    normal += cv::Matx22d(p.x * p.x, p.x * p.y, p.x * p.y, p.y * p.y);
    rhs += cv::Matx22d(p.x * q.x, p.x * q.y, p.y * q.x, p.y * q.y);
  }
  const double det = cv::determinant(normal);
  const double scale = normal(0, 0) + normal(1, 1);
  if (!(std::abs(det) > 1e-9 * scale * scale)) return false;  // collinear or coincident points
  const cv::Matx22d a = (normal.inv() * rhs).t();            // rows: (a1 a2), (a3 a4)
  const cv::Vec2d t = cv::Vec2d(cy.x, cy.y) - a * cv::Vec2d(cx.x, cx.y);
  *model = cv::Matx33d(a(0, 0), a(0, 1), t[0], a(1, 0), a(1, 1), t[1], 0, 0, 1);
  return true;
}

namespace {

// Hartley's normalisation: the similarity that moves the points' centroid to the origin and
// their mean distance from it to sqrt(2), so that the DLT's system is well conditioned.
cv::Matx33d normalisation(const std::vector<cv::Point2f>& points) {
  cv::Point2d centre(0, 0);
  for (const cv::Point2f& p : points) centre += cv::Point2d(p);
  centre /= static_cast<double>(points.size());
  double distance = 0;
  for (const cv::Point2f& p : points) distance += cv::norm(cv::Point2d(p) - centre);
  distance /= static_cast<double>(points.size());
  if (!(distance > 1e-12)) return cv::Matx33d::zeros();  // all points coincide
  const double s = std::sqrt(2.0) / distance;
  return {s, 0, -s * centre.x, 0, s, -s * centre.y, 0, 0, 1};
}

// The normalised DLT in least squares: the unit h minimising |A h|, A's two rows per point
// accumulated straight into the 9x9 A^T A, whose eigenvector of the smallest eigenvalue it is.
// Algebraic rather than geometric error: on the RANSAC inliers it is within a hundredth of a
// pixel of OpenCV's Levenberg-Marquardt refinement (findHomography) at a tenth of the cost
// (docs/design.md, "Speed of dense").
bool leastSquaresHomography(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                            cv::Matx33d* model) {
  const cv::Matx33d tx = normalisation(x), ty = normalisation(y);
  if (tx(2, 2) == 0 || ty(2, 2) == 0) return false;
  cv::Matx<double, 9, 9> ata = cv::Matx<double, 9, 9>::zeros();
  // A point's two rows of A, (0, 0, 0, -p, -1, q1 p, q1) and (p, 1, 0, 0, 0, -q0 p, -q0), each
  // without the three zeros the other row fills: their products would add +-0, which changes
  // no sum (A^T A's entries start at +0 and never become -0), so they are left out.
  constexpr int kFirstRow[6] = {3, 4, 5, 6, 7, 8}, kSecondRow[6] = {0, 1, 2, 6, 7, 8};
  const auto add = [&ata](const int* columns, const double* r) {
    for (int a = 0; a < 6; ++a) {
      for (int b = a; b < 6; ++b) ata(columns[a], columns[b]) += r[a] * r[b];
    }
  };
  for (size_t i = 0; i < x.size(); ++i) {
    const cv::Vec3d p = tx * cv::Vec3d(x[i].x, x[i].y, 1), q = ty * cv::Vec3d(y[i].x, y[i].y, 1);
    const double first[6] = {-p[0], -p[1], -1, q[1] * p[0], q[1] * p[1], q[1]};
    const double second[6] = {p[0], p[1], 1, -q[0] * p[0], -q[0] * p[1], -q[0]};
    add(kFirstRow, first);
    add(kSecondRow, second);
  }
  for (int a = 0; a < 9; ++a) {
    for (int b = 0; b < a; ++b) ata(a, b) = ata(b, a);
  }
  cv::Vec<double, 9> h;
  if (!smallestEigenvector(ata, &h)) return false;
  *model = ty.inv() * cv::Matx33d(h.val) * tx;
  return true;
}

// cv::getPerspectiveTransform's homography through four points, to the bit: its 8x8 system
// (products of floats, as it forms them) solved by the same LU, on fixed-size matrices that
// need no allocation where its cv::Mat result does. False when the system is singular.
bool homographyThroughFour(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                           cv::Matx33d* model) {
  cv::Matx<double, 8, 8> a = cv::Matx<double, 8, 8>::zeros();
  cv::Vec<double, 8> b, h;
  for (int i = 0; i < 4; ++i) {
    a(i, 0) = a(i + 4, 3) = x[i].x;
    a(i, 1) = a(i + 4, 4) = x[i].y;
    a(i, 2) = a(i + 4, 5) = 1;
    a(i, 6) = -x[i].x * y[i].x;
    a(i, 7) = -x[i].y * y[i].x;
    a(i + 4, 6) = -x[i].x * y[i].y;
    a(i + 4, 7) = -x[i].y * y[i].y;
    b[i] = y[i].x;
    b[i + 4] = y[i].y;
  }
  if (!cv::solve(a, b, h, cv::DECOMP_LU)) return false;
  *model = cv::Matx33d(h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], 1);
  return true;
}

}  // namespace

bool HomographyEstimator::estimate(const std::vector<cv::Point2f>& x,
                                   const std::vector<cv::Point2f>& y, cv::Matx33d* model) {
  if (x.size() < kMinNumSamples || x.size() != y.size()) return false;
  if (x.size() == kMinNumSamples) {
    if (!homographyThroughFour(x, y, model)) return false;
  } else if (!leastSquaresHomography(x, y, model)) {
    return false;
  }
  if (!cv::checkRange(*model) || std::abs((*model)(2, 2)) < 1e-12) return false;
  *model *= 1.0 / (*model)(2, 2);
  return cv::determinant(*model) > 1e-6;
}

void AffineEstimator::residuals(const std::vector<cv::Point2f>& x,
                                const std::vector<cv::Point2f>& y, const Model& model,
                                std::vector<double>* residuals) {
  squaredTransferErrors(x, y, model, residuals);
}

void HomographyEstimator::residuals(const std::vector<cv::Point2f>& x,
                                    const std::vector<cv::Point2f>& y, const Model& model,
                                    std::vector<double>* residuals) {
  squaredTransferErrors(x, y, model, residuals);
}

namespace {

// The line through x and y, scaled so that its dot product with (u, v, 1) is the distance of
// the point (u, v) from it; zero when x and y coincide.
cv::Vec3d lineThrough(const cv::Point2f& x, const cv::Point2f& y) {
  const cv::Vec3d line = cv::Vec3d(x.x, x.y, 1).cross(cv::Vec3d(y.x, y.y, 1));
  const double norm = std::hypot(line[0], line[1]);
  return norm > 1e-9 ? line / norm : cv::Vec3d();
}

}  // namespace

bool EpipoleEstimator::estimate(const std::vector<cv::Point2f>& x,
                                const std::vector<cv::Point2f>& y, Model* model) {
  if (x.size() == 2) {  // minimal: where the two lines meet (at infinity when parallel)
    const cv::Vec3d e = lineThrough(x[0], y[0]).cross(lineThrough(x[1], y[1]));
    if (cv::norm(e) < 1e-9) return false;
    *model = e / cv::norm(e);
    return true;
  }
  // Least squares: the unit e that lines' dot products with are smallest, the eigenvector of
  // the smallest eigenvalue of sum(l l^T).
  cv::Matx33d scatter = cv::Matx33d::zeros();
  for (size_t i = 0; i < x.size(); ++i) {
    const cv::Vec3d l = lineThrough(x[i], y[i]);
    scatter += l * l.t();
  }
  return smallestEigenvector(scatter, model);
}

double EpipoleEstimator::offLine(const cv::Point2f& x, const cv::Point2f& y,
                                 const Model& epipole) {
  // The direction from the epipole to x, x * e_w - (e_x, e_y), defined at infinity too.
  const double dx = x.x * epipole[2] - epipole[0];
  const double dy = x.y * epipole[2] - epipole[1];
  const double length = std::hypot(dx, dy);
  const double rx = y.x - x.x, ry = y.y - x.y;
  if (length < 1e-12) return std::hypot(rx, ry);  // at the epipole the direction is undefined
  return std::abs(rx * dy - ry * dx) / length;
}

void EpipoleEstimator::residuals(const std::vector<cv::Point2f>& x,
                                 const std::vector<cv::Point2f>& y, const Model& model,
                                 std::vector<double>* residuals) {
  residuals->resize(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const double off = offLine(x[i], y[i], model);
    (*residuals)[i] = off * off;
  }
}

}  // namespace movseg
