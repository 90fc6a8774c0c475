#include "synth/depth_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "synth/depth_camera.h"
#include "synth/random.h"
#include "synth/texture.h"

namespace movseg {
namespace {

// Distances in metres.
constexpr double kClearance = 1;     // between a block and every position of the camera
constexpr double kDepthGap = 0.1;    // between the z ranges of blocks and the sprites' planes
constexpr double kMinBackdrop = 16;  // the backdrop is 16–24 m beyond the farthest camera
constexpr double kMaxBackdrop = 24;  // position
constexpr double kGroundTexelDistance = 8;  // the ground's texture is 1:1 with pixels this far
constexpr double kExtentMargin = 1;         // ground and backdrop reach this beyond what frames see
constexpr double kFrameMargin = 4;          // pixels around each frame counted as seen
constexpr double kMaxTexels = 8e6;          // per texture: bounds memory at large frame sizes
constexpr int kPlacementAttempts = 50;

// What a kind of block looks like and where it stands.
struct BlockKind {
  int min_count, max_count;
  bool square;                  // a post: its depth is its width
  double min_width, max_width;  // along x
  double min_depth, max_depth;  // along z
  double min_height, max_height;
  double min_distance, max_distance;  // horizontally from the camera of a frame that sees it
  // Only beyond the sprites: a wall or box could hide a sprite for the whole clip; thin posts
  // hide them in passing.
  bool behind_sprites;
};

// Near posts come first, to get room: they are what shows the parallax. Posts are taller than
// the camera, so near ones cross the whole frame.
constexpr BlockKind kBlockKinds[] = {
    {2, 2, true, 0.15, 0.35, 0, 0, 2.5, 5.0, 1.8, 3.5, false},     // near posts
    {2, 4, true, 0.15, 0.35, 0, 0, 2.5, 5.0, 3.5, 14.0, false},    // far posts
    {1, 2, false, 1.5, 4.0, 0.1, 0.2, 1.0, 2.5, 8.0, 16.0, true},  // walls
    {1, 3, false, 0.5, 1.4, 0.5, 1.4, 0.4, 1.2, 8.0, 16.0, true},  // boxes
};

// The box of all camera centres.
struct Reach {
  cv::Vec3d low = cv::Vec3d::all(std::numeric_limits<double>::max());
  cv::Vec3d high = cv::Vec3d::all(std::numeric_limits<double>::lowest());
};

Reach cameraReach(const std::vector<SynthPinhole>& views) {
  Reach reach;
  for (const SynthPinhole& view : views) {
    for (int i = 0; i < 3; ++i) {
      reach.low[i] = std::min(reach.low[i], view.centre[i]);
      reach.high[i] = std::max(reach.high[i], view.centre[i]);
    }
  }
  return reach;
}

cv::Vec3d rayThrough(const SynthPinhole& view, double x, double y) {
  return view.rotation.t() * (view.intrinsics.inv() * cv::Vec3d(x, y, 1));
}

// `width` x `height` metres of background texture, about one texel per pixel when seen from
// `distance` metres.
cv::Mat surfaceTexture(double width, double height, double distance, const DepthScene& scene,
                       const Palette& palette, cv::RNG& rng) {
  const double texel = std::max(distance / restFocalLength(scene.frame_size),
                                std::sqrt(width * height / kMaxTexels));
  const cv::Size size(std::max(2, cvRound(width / texel)), std::max(2, cvRound(height / texel)));
  return makeBackgroundTexture(size, palette, scene.frame_size.width / 320.0, rng);
}

// Blurs each row of the ground's texture (rows run from z = far_z towards the camera) by the
// ground a pixel sees there: at distance d, from height h, a pixel of the rest view covers about
// d / f metres across the view and d² / (f h) along it, which far away is many texels. Without
// this, far ground seen at a grazing angle would alias and shimmer as the camera moves; with it,
// the ground is about as sharp in the frame as the plane's canvas (0.6–0.7 px of blur) at every
// distance. Blur levels are at distances a factor √2 apart, and each row blends the two levels
// around its distance, so the blur grows smoothly.
void blurWithDistance(cv::Mat& texture, const cv::Size2d& metres, double far_z,
                      const SynthPinhole& camera) {
  constexpr double kBlurPerFootprint = 0.6;  // Gaussian sigma, in pixel footprints
  constexpr double kMinBlur = 0.3;           // texels: below this a level is the texture as it is
  const double focal = camera.intrinsics(0, 0), height = -camera.centre[1];
  const double texel_u = metres.width / texture.cols, texel_v = metres.height / texture.rows;
  // Level k stands for distance 2^(k/2).
  const auto level = [&](int row) {
    return 2 * std::log2(std::max(1.0, far_z - (row + 0.5) * texel_v - camera.centre[2]));
  };
  cv::Mat source;
  texture.convertTo(source, CV_32F);
  cv::Mat result = cv::Mat::zeros(source.size(), source.type());
  for (int k = cvFloor(level(texture.rows - 1)); k <= cvCeil(level(0)); ++k) {
    // The rows level k contributes to, with weight 1 - |level(row) - k|: contiguous, since the
    // distance falls row by row.
    int first = texture.rows, last = -1;
    for (int row = 0; row < texture.rows; ++row) {
      if (std::abs(level(row) - k) < 1) {
        first = std::min(first, row);
        last = std::max(last, row);
      }
    }
    if (last < first) continue;
    const double d = std::pow(2.0, k / 2.0);
    const double sigma_u = kBlurPerFootprint * d / (focal * texel_u);
    const double sigma_v = kBlurPerFootprint * d * d / (focal * height * texel_v);
    // A submatrix is blurred with the rows around it, as a part of the whole texture.
    const cv::Mat rows = source.rowRange(first, last + 1);
    cv::Mat blurred = rows;
    if (sigma_u >= kMinBlur || sigma_v >= kMinBlur) {
      cv::GaussianBlur(rows, blurred, cv::Size(), std::max(sigma_u, kMinBlur),
                       std::max(sigma_v, kMinBlur));
    }
    for (int row = first; row <= last; ++row) {
      cv::Mat target = result.row(row);
      cv::scaleAdd(blurred.row(row - first), 1 - std::abs(level(row) - k), target, target);
    }
  }
  result.convertTo(texture, CV_8U);
}

// The part of the plane z = far_z and of the ground before it that any frame sees.
struct SeenExtent {
  double x_low = std::numeric_limits<double>::max();
  double x_high = std::numeric_limits<double>::lowest();
  double y_top = 0;
  double z_near = std::numeric_limits<double>::max();
};

// Every ray of a frame lies between its corner rays, so the frame sees the plane z = far_z
// within their hits; the ground before it lies between those hits and the camera.
SeenExtent seenExtent(const DepthScene& scene, double far_z) {
  const double right = scene.frame_size.width - 1 + kFrameMargin;
  const double bottom = scene.frame_size.height - 1 + kFrameMargin;
  const cv::Point2d corners[] = {{-kFrameMargin, -kFrameMargin},
                                 {right, -kFrameMargin},
                                 {-kFrameMargin, bottom},
                                 {right, bottom}};
  SeenExtent seen;
  for (const SynthPinhole& view : scene.views) {
    seen.x_low = std::min(seen.x_low, view.centre[0]);
    seen.x_high = std::max(seen.x_high, view.centre[0]);
    seen.z_near = std::min(seen.z_near, view.centre[2]);
    for (const cv::Point2d& corner : corners) {
      const cv::Vec3d ray = rayThrough(view, corner.x, corner.y);
      // Turns are bounded far below this: the painter's order needs every ray to go forward.
      if (ray[2] < 0.1 * cv::norm(ray)) throw std::logic_error("a synthetic view looks sideways");
      const cv::Vec3d hit = view.centre + ray * ((far_z - view.centre[2]) / ray[2]);
      seen.x_low = std::min(seen.x_low, hit[0]);
      seen.x_high = std::max(seen.x_high, hit[0]);
      seen.y_top = std::min(seen.y_top, hit[1]);
    }
  }
  seen.x_low -= kExtentMargin;
  seen.x_high += kExtentMargin;
  seen.y_top -= kExtentMargin;
  seen.z_near -= kExtentMargin;
  return seen;
}

// The level view at the middle frame's camera position and heading, with the rest focal
// length: what the sprites' motions are drawn in and the textures are sized for.
SynthPinhole referenceView(const DepthScene& scene) {
  const SynthPinhole& middle = scene.views[scene.views.size() / 2];
  const cv::Vec3d axis = middle.rotation.t() * cv::Vec3d(0, 0, 1);
  const double heading = std::atan2(axis[0], axis[2]);
  const double c = std::cos(heading), s = std::sin(heading);
  const double focal = restFocalLength(scene.frame_size);
  SynthPinhole view;
  view.intrinsics = cv::Matx33d(focal, 0, (scene.frame_size.width - 1) / 2.0, 0, focal,
                                (scene.frame_size.height - 1) / 2.0, 0, 0, 1);
  view.rotation = cv::Matx33d(c, 0, -s, 0, 1, 0, s, 0, c);
  view.centre = middle.centre;
  return view;
}

// Sprites are 4–8 m (in z) beyond the reference view, on its optical axis, and at least 2.5 m
// beyond every camera position. Where the ground at a sprite's depth would show above the bottom
// row of the reference view, the sprite is lifted until the ground is at that row: it sinks into
// the ground only where its 2-D motion leaves the frame at the bottom, not whenever it is low.
std::vector<Sprite> placeSprites(std::vector<SynthObject> objects, const DepthScene& scene,
                                 const Reach& reach, cv::RNG& rng) {
  const SynthPinhole reference = referenceView(scene);
  const cv::Vec3d axis = reference.rotation.t() * cv::Vec3d(0, 0, 1);
  const cv::Point2d principal_point(reference.intrinsics(0, 2), reference.intrinsics(1, 2));
  const double nearest = std::max(4.0, reach.high[2] - reference.centre[2] + 2.5);
  std::vector<Sprite> sprites;
  for (SynthObject& object : objects) {
    const double depth = rng.uniform(nearest, nearest + 4);
    Sprite sprite;
    sprite.object = std::move(object);
    sprite.anchor = reference.centre + axis * (depth / axis[2]);
    sprite.metres_per_pixel = depth / reference.intrinsics(0, 0);
    sprite.centre = principal_point;
    const double bottom_row_below_centre =
        sprite.metres_per_pixel * (scene.frame_size.height - 1 - principal_point.y);
    sprite.anchor[1] = std::min(sprite.anchor[1], -bottom_row_below_centre);
    sprites.push_back(std::move(sprite));
  }
  return sprites;
}

bool depthsOverlap(double z0, double z1, const DepthScene& scene) {
  for (const Block& block : scene.blocks) {
    if (z0 < block.high[2] + kDepthGap && block.low[2] < z1 + kDepthGap) return true;
  }
  for (const Sprite& sprite : scene.sprites) {
    if (z0 < sprite.anchor[2] + kDepthGap && sprite.anchor[2] < z1 + kDepthGap) return true;
  }
  return false;
}

double farthestSprite(const DepthScene& scene) {
  double z = std::numeric_limits<double>::lowest();
  for (const Sprite& sprite : scene.sprites) z = std::max(z, sprite.anchor[2]);
  return z;
}

bool nearCamera(const cv::Vec3d& low, const cv::Vec3d& high, const Reach& reach) {
  return low[0] - kClearance < reach.high[0] && reach.low[0] < high[0] + kClearance &&
         low[2] - kClearance < reach.high[2] && reach.low[2] < high[2] + kClearance;
}

// The block's faces but the bottom, each facing out. A block is of one material: the background
// texture around one of the palette's colours.
std::vector<PlanarSurface> blockFaces(const cv::Vec3d& low, const cv::Vec3d& high, double distance,
                                      const DepthScene& scene, const Palette& scene_palette,
                                      cv::RNG& rng) {
  Palette palette = scene_palette;
  std::rotate(palette.begin(), palette.begin() + rng.uniform(0, static_cast<int>(palette.size())),
              palette.end());
  const cv::Vec3d x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  const double width = high[0] - low[0], height = high[1] - low[1], depth = high[2] - low[2];
  const auto face = [&](const cv::Vec3d& corner, const cv::Vec3d& right, double w,
                        const cv::Vec3d& down, double h) {
    cv::Mat texture = surfaceTexture(w, h, distance, scene, palette, rng);
    return rectangleSurface(std::move(texture), corner, right, w, down, h);
  };
  // A braced list is evaluated in order, so the textures are drawn in this order.
  return {
      face(low, x, width, y, height),                                   // front, facing -z
      face(cv::Vec3d(high[0], low[1], high[2]), -x, width, y, height),  // back, facing +z
      face(cv::Vec3d(low[0], low[1], high[2]), -z, depth, y, height),   // left, facing -x
      face(cv::Vec3d(high[0], low[1], low[2]), z, depth, y, height),    // right, facing +x
      face(cv::Vec3d(low[0], low[1], high[2]), x, width, -z, depth),    // top, facing up
  };
}

// Tries a few times to stand a block of `kind` on the ground `distance` metres in front of the
// camera of a random frame, towards a random column of it, clear of the camera's path, of the
// backdrop and of the depths of the other blocks and sprites. Adds it when one fits.
void placeBlock(const BlockKind& kind, const Reach& reach, double far_z, const Palette& palette,
                DepthScene& scene, cv::RNG& rng) {
  for (int attempt = 0; attempt < kPlacementAttempts; ++attempt) {
    const SynthPinhole& view = scene.views[rng.uniform(0, static_cast<int>(scene.views.size()))];
    const double column = rng.uniform(0.1, 0.9) * (scene.frame_size.width - 1);
    const double distance = rng.uniform(kind.min_distance, kind.max_distance);
    const double width = rng.uniform(kind.min_width, kind.max_width);
    const double depth = kind.square ? width : rng.uniform(kind.min_depth, kind.max_depth);
    const double height = rng.uniform(kind.min_height, kind.max_height);
    cv::Vec3d ahead = rayThrough(view, column, view.intrinsics(1, 2));
    ahead[1] = 0;
    const cv::Vec3d foot = view.centre + distance * ahead / cv::norm(ahead);
    const cv::Vec3d low(foot[0] - width / 2, -height, foot[2] - depth / 2);
    const cv::Vec3d high(foot[0] + width / 2, 0, foot[2] + depth / 2);
    if (nearCamera(low, high, reach) || high[2] > far_z - kExtentMargin ||
        depthsOverlap(low[2], high[2], scene) ||
        (kind.behind_sprites && low[2] < farthestSprite(scene) + kDepthGap)) {
      continue;
    }
    scene.blocks.push_back({low, high, blockFaces(low, high, distance, scene, palette, rng)});
    return;
  }
}

// A block or a sprite, by the z of its range.
struct Layer {
  double z = 0;
  const Block* block = nullptr;
  const Sprite* sprite = nullptr;
};

std::vector<Layer> farToNear(const DepthScene& scene) {
  std::vector<Layer> layers;
  for (const Block& block : scene.blocks) layers.push_back({block.low[2], &block, nullptr});
  for (const Sprite& sprite : scene.sprites) layers.push_back({sprite.anchor[2], nullptr, &sprite});
  std::stable_sort(layers.begin(), layers.end(),
                   [](const Layer& a, const Layer& b) { return a.z > b.z; });
  return layers;
}

// The sprite's surface at frame t, without the part below the ground.
PlanarSurface spriteSurface(const Sprite& sprite, int t) {
  const SynthObject& object = sprite.object;
  const double c = std::cos(object.angle[t]), s = std::sin(object.angle[t]);
  const double k = sprite.metres_per_pixel;
  // Texture pixel (u, v) is at centre[t] + rotation * ((u, v) - half) in the reference view, as
  // drawObject() draws it.
  const double half = (object.texture.cols - 1) / 2.0;
  const cv::Point2d pixel_zero =
      object.centre[t] - cv::Point2d((c - s) * half, (s + c) * half) - sprite.centre;
  const cv::Vec3d origin = sprite.anchor + k * cv::Vec3d(pixel_zero.x, pixel_zero.y, 0);
  PlanarSurface surface;
  surface.texture = object.texture;
  surface.to_world =
      cv::Matx33d(k * c, -k * s, origin[0], k * s, k * c, origin[1], 0, 0, origin[2]);
  for (const cv::Point2d& p : object.outline)
    surface.outline.push_back(p + cv::Point2d(half, half));
  // World y <= 0: the ground hides the rest.
  const cv::Vec3d above_ground(-k * s, -k * c, -origin[1]);
  surface.outline = clipPolygon(surface.outline, above_ground);
  return surface;
}

}  // namespace

DepthScene makeDepthScene(const SynthOptions& options) {
  cv::RNG palette_rng = synthRng(options.seed, SynthStream::kPalette);
  const Palette palette = makeBackgroundPalette(palette_rng);
  cv::RNG object_rng = synthRng(options.seed, SynthStream::kObjects);
  std::vector<SynthObject> objects = makeObjects(options, palette, object_rng);
  DepthScene scene;
  scene.frame_size = options.size;
  cv::RNG camera_rng = synthRng(options.seed, SynthStream::kCamera);
  scene.views = makeDepthCameraPath(options.camera, options.frames, options.size, camera_rng);
  const Reach reach = cameraReach(scene.views);
  cv::RNG rng = synthRng(options.seed, SynthStream::kScene);
  const double far_z = reach.high[2] + rng.uniform(kMinBackdrop, kMaxBackdrop);
  scene.sprites = placeSprites(std::move(objects), scene, reach, rng);
  for (const BlockKind& kind : kBlockKinds) {
    const int count = rng.uniform(kind.min_count, kind.max_count + 1);
    for (int i = 0; i < count; ++i) placeBlock(kind, reach, far_z, palette, scene, rng);
  }
  const SeenExtent seen = seenExtent(scene, far_z);
  const double width = seen.x_high - seen.x_low;
  const SynthPinhole reference = referenceView(scene);
  scene.backdrop = rectangleSurface(
      surfaceTexture(width, -seen.y_top, far_z - reference.centre[2], scene, palette, rng),
      cv::Vec3d(seen.x_low, seen.y_top, far_z), cv::Vec3d(1, 0, 0), width, cv::Vec3d(0, 1, 0),
      -seen.y_top);
  const double length = far_z - seen.z_near;
  cv::Mat ground = surfaceTexture(width, length, kGroundTexelDistance, scene, palette, rng);
  blurWithDistance(ground, cv::Size2d(width, length), far_z, reference);
  scene.ground = rectangleSurface(std::move(ground), cv::Vec3d(seen.x_low, 0, far_z),
                                  cv::Vec3d(1, 0, 0), width, cv::Vec3d(0, 0, -1), length);
  return scene;
}

void renderDepthFrame(const DepthScene& scene, int t, bool background, cv::Mat& frame,
                      cv::Mat& mask) {
  const SynthPinhole& view = scene.views[t];
  frame = cv::Mat::zeros(scene.frame_size, CV_8UC3);
  mask = cv::Mat::zeros(scene.frame_size, CV_8U);
  const auto paint = [&](const PlanarSurface& surface, bool moving) {
    const Coverage coverage = surfaceCoverage(surface, view, scene.frame_size);
    if (coverage.box.empty()) return;
    if (moving || background) {
      surfaceColours(surface, view, coverage.box).copyTo(frame(coverage.box), coverage.shape);
    } else {
      frame(coverage.box).setTo(cv::Scalar::all(0), coverage.shape);
    }
    mask(coverage.box).setTo(moving ? 255 : 0, coverage.shape);
  };
  paint(scene.backdrop, false);
  paint(scene.ground, false);
  for (const Layer& layer : farToNear(scene)) {
    if (layer.block != nullptr) {
      for (const PlanarSurface& face : layer.block->faces) paint(face, false);
    } else {
      paint(spriteSurface(*layer.sprite, t), true);
    }
  }
}

}  // namespace movseg
