// Textured planar surfaces seen through a pinhole camera: what the 3-D scene is drawn from. A
// plane maps to the frame by a homography, so each surface is drawn exactly by one warp, and its
// outline, clipped to what lies in front of the camera, by one exact polygon fill.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "synth/raster.h"
#include "synth/synth.h"

namespace movseg {

struct PlanarSurface {
  cv::Mat texture;                   // CV_8UC3
  std::vector<cv::Point2d> outline;  // polygon in texture pixel coordinates
  // Texture pixel (u, v) lies at world point to_world * (u, v, 1): the columns are the world
  // steps of one texture column (e_u) and row (e_v) and the world point of pixel (0, 0). The
  // surface is one-sided, a face of a solid: it is seen only from where its texture reads
  // unmirrored, i.e. looking along e_u x e_v.
  cv::Matx33d to_world;
};

// A `width` x `height` metre rectangle with the texture stretched over it: its top-left corner
// at `corner`, its rows along the unit vector `right`, its columns along the unit vector `down`.
PlanarSurface rectangleSurface(cv::Mat texture, const cv::Vec3d& corner, const cv::Vec3d& right,
                               double width, const cv::Vec3d& down, double height);

// Texture pixel -> frame pixel.
cv::Matx33d surfaceHomography(const PlanarSurface& surface, const SynthPinhole& view);

// The part of `polygon` where half_plane · (x, y, 1) >= 0 (Sutherland–Hodgman).
std::vector<cv::Point2d> clipPolygon(const std::vector<cv::Point2d>& polygon,
                                     const cv::Vec3d& half_plane);

// The frame pixels the surface covers: its outline clipped to the part in front of the camera
// and in view, projected and filled exactly. Nothing when it faces away from the camera.
Coverage surfaceCoverage(const PlanarSurface& surface, const SynthPinhole& view,
                         cv::Size frame_size);

// Samples per pixel along each axis of surfaceColours().
constexpr int kSurfaceSupersampling = 2;

// The surface's colours over `box`, each pixel the mean of 2x2 bilinear samples of the texture,
// so that minified surfaces alias less (textures seen at grazing angles need more: depth_scene.cc
// blurs the ground's with distance).
cv::Mat surfaceColours(const PlanarSurface& surface, const SynthPinhole& view, cv::Rect box);

}  // namespace movseg
