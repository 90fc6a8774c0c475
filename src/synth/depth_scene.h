// The 3-D scene (SynthScene::kDepth): a ground plane, a far backdrop, and posts, walls and boxes
// standing on the ground at several depths, seen by the camera of depth_camera.h; the moving
// objects are flat sprites in vertical planes at some depth. Drawn by the painter's algorithm,
// each planar surface through its own homography (docs/synth.md).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "synth/objects.h"
#include "synth/render3d.h"
#include "synth/synth.h"

namespace movseg {

// A box standing on the ground, its sides along the world axes: a post, a wall or a crate.
struct Block {
  cv::Vec3d low, high;               // opposite corners (x0, -height, z0) and (x1, 0, z1)
  std::vector<PlanarSurface> faces;  // all but the bottom, each seen from outside only
};

// A moving object in the vertical plane z = anchor[2], facing the camera: pixel p of the object's
// own motion (objects.h, in a reference view) lies at anchor + metres_per_pixel * (p - centre, 0)
// where `centre` is the frame centre. So with the camera at rest at the reference view the
// object moves exactly as on the plane; when the camera moves, the object shows the parallax of
// its depth.
struct Sprite {
  SynthObject object;
  cv::Vec3d anchor;
  double metres_per_pixel = 0;
  cv::Point2d centre;
};

struct DepthScene {
  cv::Size frame_size;
  std::vector<SynthPinhole> views;  // one per frame
  PlanarSurface backdrop;           // a wall far away, behind everything
  PlanarSurface ground;             // the plane y = 0 up to the backdrop
  // The z ranges [low z, high z] of blocks and the sprites' planes never overlap: drawn from far
  // to near, a block or sprite can then only hide the ones drawn before it (every ray the camera
  // sees along goes to increasing z).
  std::vector<Block> blocks;
  std::vector<Sprite> sprites;
};

// The scene of the options (scene kDepth), its sprites the objects makeObjects() makes for them.
// The palette, the objects, the camera, the layout and the textures each come from their own
// random stream of options.seed.
DepthScene makeDepthScene(const SynthOptions& options);

// Frame t before gain and noise, and its mask: 255 exactly on the visible sprite pixels.
// background = false paints every static surface black (still hiding what is behind it).
void renderDepthFrame(const DepthScene& scene, int t, bool background, cv::Mat& frame,
                      cv::Mat& mask);

}  // namespace movseg
