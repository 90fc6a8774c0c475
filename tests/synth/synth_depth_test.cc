// The 3-D scene (SynthScene::kDepth): deterministic and random-access, every pixel drawn, masks
// exactly the visible object pixels, parallax when the camera travels and none when it only
// turns, objects hidden by nearer surfaces.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "synth/depth_scene.h"
#include "synth/render3d.h"
#include "synth/synth.h"
#include "synth/synth_checks.h"

namespace movseg {
namespace {

SynthOptions depthOptions(SynthCamera camera, int frames, std::uint64_t seed) {
  SynthOptions options;
  options.scene = SynthScene::kDepth;
  options.camera = camera;
  options.frames = frames;
  options.seed = seed;
  return options;
}

cv::Point2d project(const SynthPinhole& view, const cv::Vec3d& world) {
  const cv::Vec3d p = view.intrinsics * (view.rotation * (world - view.centre));
  return {p[0] / p[2], p[1] / p[2]};
}

cv::Point2d apply(const cv::Matx33d& homography, const cv::Point2d& p) {
  const cv::Vec3d q = homography * cv::Vec3d(p.x, p.y, 1);
  return {q[0] / q[2], q[1] / q[2]};
}

// Where the patch `box` of `previous` went in `current`: the best sum-of-squared-differences
// match within `reach` pixels, refined by a parabola through the best score and its neighbours.
std::optional<cv::Point2d> patchMotion(const cv::Mat& previous, const cv::Mat& current,
                                       cv::Rect box, int reach) {
  const cv::Rect search(box.x - reach, box.y - reach, box.width + 2 * reach,
                        box.height + 2 * reach);
  if ((search & cv::Rect(cv::Point(), current.size())) != search) return std::nullopt;
  cv::Mat scores;
  cv::matchTemplate(current(search), previous(box), scores, cv::TM_SQDIFF);
  cv::Point best;
  cv::minMaxLoc(scores, nullptr, nullptr, &best);
  if (best.x == 0 || best.y == 0 || best.x == scores.cols - 1 || best.y == scores.rows - 1)
    return std::nullopt;  // at the edge of the search: no true minimum
  const auto vertex = [](float before, float at, float after) {
    const double curvature = before - 2.0 * at + after;
    return curvature > 0 ? (before - after) / (2 * curvature) : 0.0;
  };
  const float* row = scores.ptr<float>(best.y);
  const double dx = vertex(row[best.x - 1], row[best.x], row[best.x + 1]);
  const double dy = vertex(scores.at<float>(best.y - 1, best.x), row[best.x],
                           scores.at<float>(best.y + 1, best.x));
  return cv::Point2d(best.x + dx - reach, best.y + dy - reach);
}

bool isPost(const Block& block) {
  return block.high[0] - block.low[0] < 0.5 && block.high[2] - block.low[2] < 0.5;
}

// One frame-to-frame motion of the nearest post and of the backdrop at the same pixel.
struct PostMotion {
  double distance = 0;    // of the post's front face, along z
  cv::Point2d measured;   // of a patch of the post's front face, by template matching
  cv::Point2d predicted;  // of the face's centre, projected with both poses
  cv::Point2d backdrop;   // of the backdrop at that pixel (its homography)
};

// The nearest post's motion from frame t-1 to t, measured on its front face at the camera's
// height, if that face is wide enough in view, in the frame in both and clear of objects.
std::optional<PostMotion> nearestPostMotion(const DepthScene& scene, const SynthFrame& previous,
                                            const SynthFrame& current, int t) {
  const Block* nearest = nullptr;
  for (const Block& block : scene.blocks) {
    if (isPost(block) && block.low[2] > scene.views[t - 1].centre[2] + 0.5 &&
        (nearest == nullptr || block.low[2] < nearest->low[2])) {
      nearest = &block;
    }
  }
  if (nearest == nullptr) return std::nullopt;
  const SynthPinhole& before = scene.views[t - 1];
  const SynthPinhole& after = scene.views[t];
  const cv::Vec3d face_centre((nearest->low[0] + nearest->high[0]) / 2, before.centre[1],
                              nearest->low[2]);
  PostMotion motion;
  motion.distance = nearest->low[2] - before.centre[2];
  const cv::Point2d from = project(before, face_centre);
  motion.predicted = project(after, face_centre) - from;
  const double face_width =
      before.intrinsics(0, 0) * (nearest->high[0] - nearest->low[0]) / motion.distance;
  const int width = cvFloor(face_width) - 6;
  if (width < 6) return std::nullopt;
  const cv::Rect box(cvRound(from.x) - width / 2, cvRound(from.y) - 10, width, 21);
  const cv::Rect moved = box + cv::Point(cvRound(motion.predicted.x), cvRound(motion.predicted.y));
  const cv::Rect frame(cv::Point(), previous.frame.size());
  if ((box & frame) != box || (moved & frame) != moved) return std::nullopt;
  if (cv::countNonZero(previous.mask(box)) > 0 || cv::countNonZero(current.mask(moved)) > 0)
    return std::nullopt;
  const std::optional<cv::Point2d> measured = patchMotion(previous.frame, current.frame, box, 14);
  if (!measured) return std::nullopt;
  motion.measured = *measured;
  const cv::Matx33d backdrop =
      surfaceHomography(scene.backdrop, after) * surfaceHomography(scene.backdrop, before).inv();
  motion.backdrop = apply(backdrop, from) - from;
  return motion;
}

SynthFrame renderFrame(const DepthScene& scene, int t) {
  SynthFrame f;
  renderDepthFrame(scene, t, true, f.frame, f.mask);
  return f;
}

// With neither noise nor gain change, the sequence's frames are the scene's as drawn, its camera
// models the ground's motion (checked on ground points seen in both frames), its poses the
// scene's views.
TEST(SynthDepth, SequenceShowsTheSceneAndTheGroundMotion) {
  SynthOptions options = depthOptions(SynthCamera::kMix, 6, 3);
  options.noise_sigma = 0;
  options.illumination_drift = 0;
  const SynthSequence sequence(options);
  const DepthScene scene = makeDepthScene(options);
  cv::RNG rng(5);
  for (int t = 0; t < sequence.size(); ++t) {
    const SynthFrame f = sequence.frame(t), drawn = renderFrame(scene, t);
    EXPECT_TRUE(sameBytes(f.frame, drawn.frame)) << "frame " << t;
    EXPECT_TRUE(sameBytes(f.mask, drawn.mask)) << "frame " << t;
    ASSERT_TRUE(f.pose.has_value());
    EXPECT_EQ(f.pose->intrinsics, scene.views[t].intrinsics);
    EXPECT_EQ(f.pose->rotation, scene.views[t].rotation);
    EXPECT_EQ(f.pose->centre, scene.views[t].centre);
    if (t == 0) {
      EXPECT_EQ(f.camera, cv::Matx33d::eye());
      continue;
    }
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
      const cv::Vec3d ground(rng.uniform(-5.0, 5.0), 0, rng.uniform(2.0, 20.0));
      const cv::Point2d before = project(scene.views[t - 1], ground);
      const cv::Point2d after = project(scene.views[t], ground);
      if (!cv::Rect(0, 0, 320, 240).contains(before) || !cv::Rect(0, 0, 320, 240).contains(after))
        continue;
      EXPECT_LT(cv::norm(apply(f.camera, before) - after), 1e-6) << "frame " << t;
      ++checked;
    }
    EXPECT_GT(checked, 20) << "frame " << t;
  }
  const SynthSequence still(depthOptions(SynthCamera::kStatic, 3, 3));
  EXPECT_EQ(still.frame(2).camera, cv::Matx33d::eye());
}

TEST(SynthDepth, SameOptionsGiveIdenticalBytesInAnyOrder) {
  SynthOptions options = depthOptions(SynthCamera::kMix, 10, 7);
  options.size = cv::Size(160, 120);
  const SynthSequence a(options), b(options);
  std::vector<SynthFrame> shuffled(a.size());
  for (const int t : {7, 2, 9, 0, 5, 1, 8, 3, 6, 4}) shuffled[t] = b.frame(t);
  for (int t = 0; t < a.size(); ++t) {
    const SynthFrame x = a.frame(t), &y = shuffled[t];
    EXPECT_TRUE(sameBytes(x.frame, y.frame)) << "frame " << t;
    EXPECT_TRUE(sameBytes(x.mask, y.mask)) << "frame " << t;
    EXPECT_EQ(x.camera, y.camera) << "frame " << t;
    EXPECT_EQ(x.pose->centre, y.pose->centre) << "frame " << t;
  }
  options.seed = 8;
  EXPECT_FALSE(sameBytes(a.frame(3).frame, SynthSequence(options).frame(3).frame));
}

TEST(SynthDepth, SmallestClipWorks) {
  SynthOptions options = depthOptions(SynthCamera::kMix, 1, 1);
  options.size = cv::Size(16, 16);
  const SynthFrame f = SynthSequence(options).frame(0);
  EXPECT_EQ(f.frame.size(), options.size);
  EXPECT_EQ(f.camera, cv::Matx33d::eye());
}

// A tall portrait frame looks forward as a landscape one does: the focal length follows the
// longer side (from the width alone, a frame 20 times taller than wide saw over 170° high: "a
// synthetic view looks sideways"). Every pixel drawn, as below.
TEST(SynthDepth, TallPortraitFramesRender) {
  SynthOptions options = depthOptions(SynthCamera::kMix, 3, 2);
  options.size = cv::Size(32, 640);
  const DepthScene scene = makeDepthScene(options);
  const SynthFrame f = renderFrame(scene, 2);
  ASSERT_EQ(f.frame.size(), options.size);
  double darkest;
  cv::minMaxLoc(f.frame.reshape(1), &darkest);
  EXPECT_GE(darkest, 16);
}

// The ground and backdrop reach as far as any frame looks: a pixel left undrawn would be black
// (every texture is at least 16). Long clips for the sweeping motions.
TEST(SynthDepth, EveryPixelIsDrawn) {
  for (const SynthCamera camera : kAllCameras) {
    const bool sweeps = camera == SynthCamera::kPan || camera == SynthCamera::kForward ||
                        camera == SynthCamera::kDolly;
    SynthOptions options = depthOptions(camera, sweeps ? 200 : 60, 4);
    options.size = cv::Size(160, 120);
    const DepthScene scene = makeDepthScene(options);
    for (int t = 0; t < options.frames; t += 7) {
      double darkest;
      cv::minMaxLoc(renderFrame(scene, t).frame.reshape(1), &darkest);
      ASSERT_GE(darkest, 16) << synthCameraName(camera) << " frame " << t;
    }
  }
}

// On a black static scene (background = false), an object pixel is exactly a non-black pixel, so
// the mask can neither miss a visible object pixel nor claim a hidden one; with the scene drawn,
// the object pixels are the same.
TEST(SynthDepth, MaskIsExactlyTheVisibleObjectPixels) {
  for (const SynthCamera camera : {SynthCamera::kDolly, SynthCamera::kMix}) {
    SynthOptions options = depthOptions(camera, 30, 5);
    options.size = cv::Size(160, 120);
    options.objects = 3;
    options.noise_sigma = 0;
    EXPECT_GT(expectMasksAreTheDrawnObjects(options, 3), 0) << synthCameraName(camera);
  }
}

// A near post's image motion, measured by template matching on the frames, against the
// backdrop's at the same pixel: a sideways camera (dolly) separates them by several pixels per
// frame (measured 4.9–7.2 at 320x240), a camera turning about its centre (pan, roll, focal
// change) moves both alike (measured within 0.3 px, the matching's own error).
TEST(SynthDepth, TravelGivesParallaxAndTurnsDoNot) {
  struct Case {
    SynthCamera camera;
    std::uint64_t seed;
  };
  for (const Case& c :
       {Case{SynthCamera::kDolly, 1}, Case{SynthCamera::kDolly, 2}, Case{SynthCamera::kPan, 1},
        Case{SynthCamera::kRotate, 1}, Case{SynthCamera::kZoom, 1}}) {
    SynthOptions options = depthOptions(c.camera, 20, c.seed);
    options.objects = 1;
    const DepthScene scene = makeDepthScene(options);
    const bool travels = c.camera == SynthCamera::kDolly;
    SynthFrame previous = renderFrame(scene, 0);
    int measured = 0;
    for (int t = 1; t < options.frames; ++t) {
      const SynthFrame current = renderFrame(scene, t);
      const std::optional<PostMotion> motion = nearestPostMotion(scene, previous, current, t);
      previous = current;
      if (!motion) continue;
      ++measured;
      const std::string where = synthCameraName(c.camera) + " seed " + std::to_string(c.seed) +
                                " frame " + std::to_string(t);
      EXPECT_LT(cv::norm(motion->measured - motion->predicted), 0.5) << where;
      const double parallax = cv::norm(motion->measured - motion->backdrop);
      if (travels) {
        EXPECT_GT(parallax, 3.0) << where << " post at " << motion->distance << " m";
      } else {
        EXPECT_LT(parallax, 0.5) << where;
      }
    }
    EXPECT_GT(measured, 10) << synthCameraName(c.camera) << " seed " << c.seed;
  }
}

cv::Mat flat(const cv::Scalar& colour, int side = 4) {
  return cv::Mat(side, side, CV_8UC3, colour);
}

cv::Mat pixelsOf(const cv::Mat& frame, const cv::Scalar& colour) {
  cv::Mat same;
  cv::inRange(frame, colour, colour, same);
  return same;
}

// A green square sprite at z = 6 crosses, from left to right, behind a red post at z = 3 and in
// front of a blue wall at z = 10, seen by a still camera. Every colour is flat, so each pixel
// says what it shows.
TEST(SynthDepth, NearerSurfacesHideObjects) {
  const cv::Scalar grey(128, 128, 128), brown(40, 70, 110), red(0, 0, 200), blue(200, 0, 0),
      green(0, 200, 0);
  const double focal = 144;
  DepthScene scene;
  scene.frame_size = cv::Size(160, 120);
  SynthPinhole view;
  view.intrinsics = cv::Matx33d(focal, 0, 79.5, 0, focal, 59.5, 0, 0, 1);
  view.rotation = cv::Matx33d::eye();
  view.centre = cv::Vec3d(0, -1.5, 0);
  scene.views.assign(9, view);
  const cv::Vec3d x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  scene.backdrop = rectangleSurface(flat(grey), cv::Vec3d(-30, -30, 20), x, 60, y, 30);
  scene.ground = rectangleSurface(flat(brown), cv::Vec3d(-30, 0, 20), x, 60, -z, 21);
  Block post{cv::Vec3d(-0.15, -3, 3), cv::Vec3d(0.15, 0, 3.3), {}};
  post.faces = {rectangleSurface(flat(red), post.low, x, 0.3, y, 3)};
  Block wall{cv::Vec3d(-4, -2, 10), cv::Vec3d(4, 0, 10.1), {}};
  wall.faces = {rectangleSurface(flat(blue), wall.low, x, 8, y, 2)};
  Sprite sprite;
  sprite.object.texture = flat(green, 41);
  sprite.object.outline = {{-15, -15}, {15, -15}, {15, 15}, {-15, 15}};
  for (int t = 0; t < 9; ++t) {
    sprite.object.centre.emplace_back(30 + 12.5 * t, 50);
    sprite.object.angle.push_back(0);
  }
  sprite.anchor = cv::Vec3d(0, -1.5, 6);
  sprite.metres_per_pixel = 6 / focal;
  sprite.centre = cv::Point2d(79.5, 59.5);
  scene.sprites = {sprite};
  scene.blocks = {wall};
  const DepthScene unhidden = scene;
  scene.blocks.push_back(post);

  int hidden_pixels = 0;
  for (int t = 0; t < 9; ++t) {
    const SynthFrame f = renderFrame(scene, t);
    const cv::Mat silhouette = renderFrame(unhidden, t).mask;
    EXPECT_EQ(cv::countNonZero(f.mask != pixelsOf(f.frame, green)), 0) << "frame " << t;
    EXPECT_EQ(cv::countNonZero(f.mask != (silhouette & ~pixelsOf(f.frame, red))), 0)
        << "frame " << t;
    EXPECT_EQ(cv::countNonZero(f.mask & pixelsOf(f.frame, blue)), 0) << "frame " << t;
    hidden_pixels += cv::countNonZero(silhouette & ~f.mask);
  }
  EXPECT_GT(hidden_pixels, 0);
  // Frame 4: the square (x 65..95) straddles the post (x 72..87): two parts, the post between.
  const SynthFrame middle = renderFrame(scene, 4);
  cv::Mat labels;
  EXPECT_EQ(cv::connectedComponents(middle.mask, labels), 3);  // background and two parts
  EXPECT_EQ(cv::countNonZero(middle.mask.colRange(74, 86)), 0);
  EXPECT_GT(cv::countNonZero(pixelsOf(middle.frame, red).colRange(74, 86)), 30 * 12);
}

// Horizontal distance from a point to a block's footprint.
double footprintDistance(const Block& block, const cv::Vec3d& point) {
  const double dx = std::max({block.low[0] - point[0], 0.0, point[0] - block.high[0]});
  const double dz = std::max({block.low[2] - point[2], 0.0, point[2] - block.high[2]});
  return std::hypot(dx, dz);
}

// What the painter's order and the parallax rest on: the z ranges of blocks and sprites never
// overlap, nothing stands within 1 m of the camera's path, the sprites stay 2.5 m ahead of it,
// and there are near posts: seen, at some frame, less than 4 m away.
TEST(SynthDepth, LayoutKeepsItsPromises) {
  struct Case {
    SynthCamera camera;
    std::uint64_t seed;
  };
  for (const Case& c : {Case{SynthCamera::kDolly, 1}, Case{SynthCamera::kForward, 1},
                        Case{SynthCamera::kForward, 2}, Case{SynthCamera::kMix, 1}}) {
    SynthOptions options = depthOptions(c.camera, 60, c.seed);
    options.size = cv::Size(160, 120);
    const DepthScene scene = makeDepthScene(options);
    const std::string which = synthCameraName(c.camera) + " seed " + std::to_string(c.seed);
    std::vector<cv::Vec2d> depths;
    for (const Block& block : scene.blocks) depths.emplace_back(block.low[2], block.high[2]);
    for (const Sprite& sprite : scene.sprites)
      depths.emplace_back(sprite.anchor[2], sprite.anchor[2]);
    std::sort(depths.begin(), depths.end(),
              [](const cv::Vec2d& a, const cv::Vec2d& b) { return a[0] < b[0]; });
    for (size_t i = 1; i < depths.size(); ++i) EXPECT_GT(depths[i][0], depths[i - 1][1]) << which;
    EXPECT_GE(scene.blocks.size(), 6u) << which;
    int near_posts = 0;
    for (const Block& block : scene.blocks) {
      bool near = false;
      for (const SynthPinhole& view : scene.views) {
        EXPECT_GE(footprintDistance(block, view.centre), 1 - 1e-9) << which;
        const cv::Vec3d face((block.low[0] + block.high[0]) / 2, view.centre[1], block.low[2]);
        const double ahead = block.low[2] - view.centre[2];
        near = near || (isPost(block) && ahead > 0 && ahead < 4 &&
                        cv::Rect(0, 0, 160, 120).contains(project(view, face)));
      }
      near_posts += near;
    }
    EXPECT_GE(near_posts, 2) << which;
    for (const Sprite& sprite : scene.sprites) {
      for (const SynthPinhole& view : scene.views)
        EXPECT_GE(sprite.anchor[2] - view.centre[2], 2.5 - 1e-9) << which;
    }
  }
}

// With a still camera a sprite's centre appears exactly where the object's own motion puts it,
// raised by a constant: the objects' speeds are the option's, as on the plane.
TEST(SynthDepth, StillCameraSeesTheObjectsOwnMotion) {
  SynthOptions options = depthOptions(SynthCamera::kStatic, 40, 6);
  options.objects = 3;
  const DepthScene scene = makeDepthScene(options);
  ASSERT_EQ(scene.sprites.size(), 3u);
  for (const Sprite& sprite : scene.sprites) {
    const SynthObject& object = sprite.object;
    std::optional<double> raise;
    for (int t = 0; t < options.frames; ++t) {
      const cv::Point2d offset = (object.centre[t] - sprite.centre) * sprite.metres_per_pixel;
      const cv::Point2d seen =
          project(scene.views[t], sprite.anchor + cv::Vec3d(offset.x, offset.y, 0));
      EXPECT_NEAR(seen.x, object.centre[t].x, 1e-9) << "frame " << t;
      if (!raise) raise = object.centre[t].y - seen.y;
      EXPECT_NEAR(object.centre[t].y - seen.y, *raise, 1e-9) << "frame " << t;
    }
    EXPECT_GE(*raise, -1e-9);  // raised, or not moved at all
  }
}

}  // namespace
}  // namespace movseg
