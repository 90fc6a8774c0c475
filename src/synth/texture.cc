#include "synth/texture.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

cv::Vec3d randomColour(double lo, double hi, cv::RNG& rng) {
  cv::Vec3d colour;
  for (int c = 0; c < 3; ++c) colour[c] = rng.uniform(lo, hi);
  return colour;
}

cv::Vec3d randomUnitVector(cv::RNG& rng) {
  cv::Vec3d v;
  for (int c = 0; c < 3; ++c) v[c] = rng.gaussian(1.0);
  return v * (1.0 / std::max(1e-9, cv::norm(v)));
}

cv::Point2d randomDirection(cv::RNG& rng) {
  const double angle = rng.uniform(0.0, 2 * CV_PI);
  return {std::cos(angle), std::sin(angle)};
}

// Uniform noise in [-1, 1] on a grid of `cell`-pixel cells, interpolated bicubically: a smooth
// random field whose blobs are about `cell` pixels wide.
cv::Mat smoothNoise(cv::Size size, double cell, cv::RNG& rng) {
  const cv::Size grid(std::max(2, cvCeil(size.width / cell) + 1),
                      std::max(2, cvCeil(size.height / cell) + 1));
  cv::Mat coarse(grid, CV_32FC3);
  rng.fill(coarse, cv::RNG::UNIFORM, cv::Scalar::all(-1), cv::Scalar::all(1));
  cv::Mat field;
  cv::resize(coarse, field, size, 0, 0, cv::INTER_CUBIC);
  return field;
}

// Per-pixel uniform noise in [-amplitude, amplitude]: grain for the flat insides of shapes.
void addGrain(cv::Mat& image, double amplitude, cv::RNG& rng) {
  cv::Mat grain(image.size(), image.type());
  rng.fill(grain, cv::RNG::UNIFORM, cv::Scalar::all(-amplitude), cv::Scalar::all(amplitude));
  image += grain;
}

// Clamps a float image to [lo, hi] and rounds it to 8 bits.
cv::Mat toBytes(const cv::Mat& image, double lo, double hi) {
  cv::Mat clamped = cv::max(image, lo);
  clamped = cv::min(clamped, hi);
  cv::Mat bytes;
  clamped.convertTo(bytes, CV_8U);
  return bytes;
}

cv::Scalar shapeColour(const Palette& palette, cv::RNG& rng) {
  const cv::Vec3d& base = palette[rng.uniform(0, static_cast<int>(palette.size()))];
  cv::Scalar colour;
  for (int c = 0; c < 3; ++c)
    colour[c] = std::clamp(base[c] + rng.uniform(-70.0, 70.0), 0.0, 255.0);
  return colour;
}

// One disc, ring, ellipse, rotated rectangle or line of about `radius` pixels, anti-aliased (the
// background may be; only the objects' masks must be exact).
void drawShape(cv::Mat& canvas, cv::Point centre, double radius, const cv::Scalar& colour,
               double scale, cv::RNG& rng) {
  const int r = std::max(1, cvRound(radius));
  switch (rng.uniform(0, 5)) {
    case 0:
      cv::circle(canvas, centre, r, colour, cv::FILLED, cv::LINE_AA);
      break;
    case 1: {
      const int thickness = rng.uniform(1, std::max(2, cvRound(3 * scale)) + 1);
      cv::circle(canvas, centre, r, colour, thickness, cv::LINE_AA);
      break;
    }
    case 2: {
      const int minor = std::max(1, cvRound(r * rng.uniform(0.3, 1.0)));
      cv::ellipse(canvas, centre, cv::Size(r, minor), rng.uniform(0.0, 180.0), 0, 360, colour,
                  cv::FILLED, cv::LINE_AA);
      break;
    }
    case 3: {
      const float height = static_cast<float>(2 * r * rng.uniform(0.2, 1.0));
      const cv::RotatedRect box(centre, cv::Size2f(2.0f * r, height),
                                static_cast<float>(rng.uniform(0.0, 180.0)));
      cv::Point2f corners[4];
      box.points(corners);
      cv::Point points[4];
      for (int i = 0; i < 4; ++i)
        points[i] = cv::Point(cvRound(corners[i].x), cvRound(corners[i].y));
      cv::fillConvexPoly(canvas, points, 4, colour, cv::LINE_AA);
      break;
    }
    default: {
      const cv::Point2d direction = randomDirection(rng);
      const cv::Point end(centre.x + cvRound(2 * r * direction.x),
                          centre.y + cvRound(2 * r * direction.y));
      const int thickness = rng.uniform(1, std::max(2, cvRound(3 * scale)) + 1);
      cv::line(canvas, centre, end, colour, thickness, cv::LINE_AA);
      break;
    }
  }
}

// About one shape per (22 * scale)^2 pixels, radii spread log-uniformly over 2..30 * scale, so
// that every patch an LK window sees has corners and edges.
void drawShapes(cv::Mat& canvas, const Palette& palette, double scale, cv::RNG& rng) {
  const int count = cvCeil(canvas.size().area() / (22.0 * 22.0 * scale * scale));
  for (int i = 0; i < count; ++i) {
    cv::Point centre;
    centre.x = rng.uniform(0, canvas.cols);
    centre.y = rng.uniform(0, canvas.rows);
    const double radius = scale * std::exp(rng.uniform(std::log(2.0), std::log(30.0)));
    const cv::Scalar colour = shapeColour(palette, rng);
    drawShape(canvas, centre, radius, colour, scale, rng);
  }
}

// Parallel bands `period` pixels apart, half of each band set.
void drawStripes(cv::Mat& pattern, double scale, cv::RNG& rng) {
  const double period = scale * rng.uniform(6.0, 16.0);
  const cv::Point2d along = randomDirection(rng);
  const cv::Point2d across(-along.y, along.x);
  const double reach = pattern.cols + pattern.rows;
  const cv::Point2d centre(pattern.cols / 2.0, pattern.rows / 2.0);
  const int thickness = std::max(1, cvRound(period / 2));
  for (double offset = -reach; offset <= reach; offset += period) {
    const cv::Point2d middle = centre + offset * across;
    cv::line(pattern, middle - reach * along, middle + reach * along, cv::Scalar(255), thickness);
  }
}

void drawSpots(cv::Mat& pattern, double scale, cv::RNG& rng) {
  const int count = cvCeil(pattern.size().area() / (14.0 * 14.0 * scale * scale));
  for (int i = 0; i < count; ++i) {
    cv::Point centre;
    centre.x = rng.uniform(0, pattern.cols);
    centre.y = rng.uniform(0, pattern.rows);
    const int radius = std::max(1, cvRound(scale * rng.uniform(2.0, 6.0)));
    cv::circle(pattern, centre, radius, cv::Scalar(255), cv::FILLED);
  }
}

}  // namespace

Palette makeBackgroundPalette(cv::RNG& rng) {
  Palette palette(3);
  for (cv::Vec3d& colour : palette) colour = randomColour(50, 205, rng);
  return palette;
}

cv::Mat makeBackgroundTexture(cv::Size size, const Palette& palette, double scale, cv::RNG& rng) {
  const cv::Vec3d& base = palette[0];
  cv::Mat field(size, CV_32FC3, cv::Scalar(base[0], base[1], base[2]));
  field += 45 * smoothNoise(size, 120 * scale, rng);
  field += 25 * smoothNoise(size, 30 * scale, rng);
  field += 12 * smoothNoise(size, 8 * scale, rng);
  cv::Mat canvas = toBytes(field, 0, 255);
  drawShapes(canvas, palette, scale, rng);
  canvas.convertTo(field, CV_32F);
  field += 8 * smoothNoise(size, 3 * scale, rng);
  addGrain(field, 5, rng);
  // A touch of blur: the plane is resampled every frame, and unblurred single-pixel grain
  // would make bilinear resampling errors rival the sensor noise.
  cv::GaussianBlur(field, field, cv::Size(), 0.7 * std::max(1.0, scale));
  return toBytes(field, 20, 235);
}

cv::Vec3d pickObjectColour(const Palette& palette, cv::RNG& rng) {
  cv::Vec3d best;
  double best_distance = -1;
  for (int i = 0; i < 8; ++i) {
    const cv::Vec3d candidate = randomColour(40, 215, rng);
    double distance = 1e9;
    for (const cv::Vec3d& colour : palette)
      distance = std::min(distance, cv::norm(candidate - colour));
    if (distance > best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

cv::Mat makeObjectTexture(int side, const cv::Vec3d& colour, double scale, cv::RNG& rng) {
  const cv::Size size(side, side);
  cv::Mat texture(size, CV_32FC3, cv::Scalar(colour[0], colour[1], colour[2]));
  texture += 30 * smoothNoise(size, 20 * scale, rng);
  texture += 12 * smoothNoise(size, 5 * scale, rng);
  cv::Mat pattern = cv::Mat::zeros(size, CV_8U);
  if (rng.uniform(0, 2) == 0) {
    drawStripes(pattern, scale, rng);
  } else {
    drawSpots(pattern, scale, rng);
  }
  // The second colour stands out from the first by 40–80 levels.
  const cv::Vec3d shift = randomUnitVector(rng) * rng.uniform(40.0, 80.0);
  cv::add(texture, cv::Scalar(shift[0], shift[1], shift[2]), texture, pattern);
  addGrain(texture, 5, rng);
  cv::GaussianBlur(texture, texture, cv::Size(), 0.7 * std::max(1.0, scale));
  return toBytes(texture, 16, 240);
}

}  // namespace movseg
