#include "synth/render3d.h"

#include <utility>

#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

constexpr double kNearPlane = 0.05;  // metres: nothing nearer the camera is drawn
// Pixels beyond the frame edge the clipped outline may reach: fillPoly then draws the frame's
// edge pixels the same as any other.
constexpr double kClipMargin = 2;

cv::Matx33d columns(const cv::Vec3d& a, const cv::Vec3d& b, const cv::Vec3d& c) {
  return {a[0], b[0], c[0], a[1], b[1], c[1], a[2], b[2], c[2]};
}

// Camera coordinates of texture pixel (u, v) are A * (u, v, 1): its world point less the camera
// centre, in the camera's axes.
cv::Matx33d textureToCamera(const PlanarSurface& surface, const SynthPinhole& view) {
  cv::Matx33d from_centre = surface.to_world;
  for (int i = 0; i < 3; ++i) from_centre(i, 2) -= view.centre[i];
  return view.rotation * from_centre;
}

// The half-spaces of camera space that are drawn, as n · (x, y, z) + d >= 0 in (n, d): in
// front of the near plane, and within the frame grown by the margin.
std::vector<cv::Vec4d> viewVolume(const SynthPinhole& view, cv::Size frame_size) {
  const cv::Matx33d& k = view.intrinsics;
  const cv::Vec3d row_x(k(0, 0), k(0, 1), k(0, 2)), row_y(k(1, 0), k(1, 1), k(1, 2)),
      row_w(k(2, 0), k(2, 1), k(2, 2));
  const double right = frame_size.width - 1 + kClipMargin;
  const double bottom = frame_size.height - 1 + kClipMargin;
  const auto through_centre = [](const cv::Vec3d& n) { return cv::Vec4d(n[0], n[1], n[2], 0); };
  return {cv::Vec4d(0, 0, 1, -kNearPlane),
          through_centre(row_x + kClipMargin * row_w),  // x >= -margin
          through_centre(right * row_w - row_x),        // x <= right
          through_centre(row_y + kClipMargin * row_w),  // y >= -margin
          through_centre(bottom * row_w - row_y)};      // y <= bottom
}

}  // namespace

PlanarSurface rectangleSurface(cv::Mat texture, const cv::Vec3d& corner, const cv::Vec3d& right,
                               double width, const cv::Vec3d& down, double height) {
  const double columns_count = texture.cols, rows_count = texture.rows;
  const cv::Vec3d step_u = right * (width / columns_count);
  const cv::Vec3d step_v = down * (height / rows_count);
  PlanarSurface surface;
  surface.to_world = columns(step_u, step_v, corner + 0.5 * (step_u + step_v));
  // Pixel centres are at integers, so the texture's edges are half a pixel beyond them.
  const double u_end = columns_count - 0.5, v_end = rows_count - 0.5;
  surface.outline = {{-0.5, -0.5}, {u_end, -0.5}, {u_end, v_end}, {-0.5, v_end}};
  surface.texture = std::move(texture);
  return surface;
}

cv::Matx33d surfaceHomography(const PlanarSurface& surface, const SynthPinhole& view) {
  return view.intrinsics * textureToCamera(surface, view);
}

std::vector<cv::Point2d> clipPolygon(const std::vector<cv::Point2d>& polygon,
                                     const cv::Vec3d& half_plane) {
  const auto side = [&](const cv::Point2d& p) {
    return half_plane[0] * p.x + half_plane[1] * p.y + half_plane[2];
  };
  std::vector<cv::Point2d> kept;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const cv::Point2d& a = polygon[i];
    const cv::Point2d& b = polygon[(i + 1) % polygon.size()];
    const double side_a = side(a), side_b = side(b);
    if (side_a >= 0) kept.push_back(a);
    if ((side_a >= 0) != (side_b >= 0)) kept.push_back(a + (b - a) * (side_a / (side_a - side_b)));
  }
  return kept;
}

Coverage surfaceCoverage(const PlanarSurface& surface, const SynthPinhole& view,
                         cv::Size frame_size) {
  const cv::Matx33d to_camera = textureToCamera(surface, view);
  const cv::Vec3d step_u(to_camera(0, 0), to_camera(1, 0), to_camera(2, 0));
  const cv::Vec3d step_v(to_camera(0, 1), to_camera(1, 1), to_camera(2, 1));
  const cv::Vec3d origin(to_camera(0, 2), to_camera(1, 2), to_camera(2, 2));
  if (origin.dot(step_u.cross(step_v)) <= 0) return {};  // seen from behind
  // A camera-space half-space is a half-plane of texture space: n · A (u, v, 1) + d >= 0.
  std::vector<cv::Point2d> outline = surface.outline;
  for (const cv::Vec4d& h : viewVolume(view, frame_size)) {
    const cv::Vec3d n(h[0], h[1], h[2]);
    outline = clipPolygon(outline, to_camera.t() * n + cv::Vec3d(0, 0, h[3]));
    if (outline.size() < 3) return {};
  }
  const cv::Matx33d to_frame = view.intrinsics * to_camera;
  std::vector<cv::Point2d> projected;
  for (const cv::Point2d& p : outline) {
    const cv::Vec3d q = to_frame * cv::Vec3d(p.x, p.y, 1);
    projected.emplace_back(q[0] / q[2], q[1] / q[2]);
  }
  return polygonCoverage(projected, frame_size);
}

cv::Mat surfaceColours(const PlanarSurface& surface, const SynthPinhole& view, cv::Rect box) {
  // Frame pixel (x, y) is covered by the fine pixels S (x, y) + (0..S-1); their centres average
  // back to (x, y).
  constexpr double s = kSurfaceSupersampling;
  const cv::Matx33d to_fine(s, 0, (s - 1) / 2 - s * box.x, 0, s, (s - 1) / 2 - s * box.y, 0, 0, 1);
  cv::Mat fine, colours;
  cv::warpPerspective(surface.texture, fine, to_fine * surfaceHomography(surface, view),
                      box.size() * kSurfaceSupersampling, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  cv::resize(fine, colours, box.size(), 0, 0, cv::INTER_AREA);
  return colours;
}

}  // namespace movseg
