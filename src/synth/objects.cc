#include "synth/objects.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "synth/raster.h"

namespace movseg {
namespace {

double polygonArea(const std::vector<cv::Point2d>& polygon) {
  double twice = 0;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    twice += polygon[j].x * polygon[i].y - polygon[i].x * polygon[j].y;
  }
  return std::abs(twice) / 2;
}

double polygonRadius(const std::vector<cv::Point2d>& polygon) {
  double radius = 0;
  for (const cv::Point2d& p : polygon) radius = std::max(radius, std::hypot(p.x, p.y));
  return radius;
}

std::vector<cv::Point2d> ellipseOutline(cv::RNG& rng) {
  const double aspect = rng.uniform(0.45, 1.0);
  std::vector<cv::Point2d> outline;
  for (int i = 0; i < 64; ++i) {
    const double a = 2 * CV_PI * i / 64;
    outline.emplace_back(std::cos(a), aspect * std::sin(a));
  }
  return outline;
}

// 3 to 7 vertices at jittered, increasing angles (gaps below π, so the polygon is simple and
// holds its centre) and random radii: often not convex.
std::vector<cv::Point2d> polygonOutline(cv::RNG& rng) {
  const int vertices = rng.uniform(3, 8);
  std::vector<cv::Point2d> outline;
  for (int i = 0; i < vertices; ++i) {
    const double a = 2 * CV_PI * (i + rng.uniform(0.0, 0.6)) / vertices;
    const double r = rng.uniform(0.55, 1.0);
    outline.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return outline;
}

// A circle whose radius wobbles with a few low harmonics.
std::vector<cv::Point2d> blobOutline(cv::RNG& rng) {
  double amplitude[3], phase[3];
  for (int k = 0; k < 3; ++k) {
    amplitude[k] = rng.uniform(0.0, 0.18);
    phase[k] = rng.uniform(0.0, 2 * CV_PI);
  }
  std::vector<cv::Point2d> outline;
  for (int i = 0; i < 64; ++i) {
    const double a = 2 * CV_PI * i / 64;
    double r = 1;
    for (int k = 0; k < 3; ++k) r += amplitude[k] * std::cos((k + 2) * a + phase[k]);
    outline.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return outline;
}

std::vector<cv::Point2d> makeOutline(double area, cv::RNG& rng) {
  std::vector<cv::Point2d> outline;
  switch (rng.uniform(0, 3)) {
    case 0:
      outline = ellipseOutline(rng);
      break;
    case 1:
      outline = polygonOutline(rng);
      break;
    default:
      outline = blobOutline(rng);
      break;
  }
  const double scale = std::sqrt(area / polygonArea(outline));
  for (cv::Point2d& p : outline) p *= scale;
  return outline;
}

// The centre bounces inside the frame grown by a random margin: a negative margin keeps the
// object nearly whole in view, a margin above its radius lets it leave entirely and come back.
// It starts anywhere in that box, so it may enter from outside.
void simulateMotion(const SynthOptions& options, cv::RNG& rng, SynthObject* object) {
  const cv::Size frame_size = options.size;
  const double scale = frame_size.width / 320.0;
  const double radius = polygonRadius(object->outline);
  const double margin = std::max(radius * rng.uniform(-0.8, 1.3),
                                 -0.4 * std::min(frame_size.width, frame_size.height));
  const cv::Point2d lo(-margin, -margin);
  const cv::Point2d hi(frame_size.width - 1 + margin, frame_size.height - 1 + margin);
  cv::Point2d centre;
  centre.x = rng.uniform(lo.x, hi.x);
  centre.y = rng.uniform(lo.y, hi.y);
  const double speed = scale * rng.uniform(options.object_speed_min, options.object_speed_max);
  double heading = rng.uniform(0.0, 2 * CV_PI);
  double angle = rng.uniform(0.0, 2 * CV_PI);
  const double spin = rng.uniform(-0.02, 0.02);
  double turn = 0;
  for (int t = 0; t < options.frames; ++t) {
    object->centre.push_back(centre);
    object->angle.push_back(angle);
    turn = std::clamp(turn + rng.gaussian(0.006), -0.04, 0.04);
    heading += turn;
    cv::Point2d step(std::cos(heading), std::sin(heading));
    if ((centre.x < lo.x && step.x < 0) || (centre.x > hi.x && step.x > 0)) step.x = -step.x;
    if ((centre.y < lo.y && step.y < 0) || (centre.y > hi.y && step.y > 0)) step.y = -step.y;
    heading = std::atan2(step.y, step.x);
    centre += speed * step;
    angle += spin;
  }
}

}  // namespace

std::vector<SynthObject> makeObjects(const SynthOptions& options, const Palette& palette,
                                     cv::RNG& rng) {
  const double scale = options.size.width / 320.0;
  const double max_fraction = 0.25 / std::sqrt(options.objects);
  std::vector<SynthObject> objects(options.objects);
  for (SynthObject& object : objects) {
    object.outline = makeOutline(rng.uniform(0.05, max_fraction) * options.size.area(), rng);
    const int side = 2 * cvCeil(polygonRadius(object.outline)) + 5;
    if (options.camouflage) {
      object.texture = makeBackgroundTexture(cv::Size(side, side), palette, scale, rng);
    } else {
      const cv::Vec3d colour = pickObjectColour(palette, rng);
      object.texture = makeObjectTexture(side, colour, scale, rng);
    }
    simulateMotion(options, rng, &object);
  }
  return objects;
}

void drawObject(const SynthObject& object, int t, cv::Mat& frame, cv::Mat& mask) {
  const cv::Point2d centre = object.centre[t];
  const double c = std::cos(object.angle[t]), s = std::sin(object.angle[t]);
  std::vector<cv::Point2d> outline;
  for (const cv::Point2d& p : object.outline)
    outline.emplace_back(c * p.x - s * p.y + centre.x, s * p.x + c * p.y + centre.y);
  const Coverage coverage = polygonCoverage(outline, frame.size());
  const cv::Rect box = coverage.box;
  if (box.empty()) return;
  // Texture pixel -> box pixel: turn about the texture's centre, then move onto the object's.
  const double half = (object.texture.cols - 1) / 2.0;
  const cv::Matx23d to_box(c, -s, centre.x - box.x - (c - s) * half, s, c,
                           centre.y - box.y - (s + c) * half);
  cv::Mat pixels;
  cv::warpAffine(object.texture, pixels, to_box, box.size(), cv::INTER_LINEAR,
                 cv::BORDER_REPLICATE);
  pixels.copyTo(frame(box), coverage.shape);
  mask(box).setTo(255, coverage.shape);
}

}  // namespace movseg
