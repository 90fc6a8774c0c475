// Random numbers of the synthetic generator. Each part (palette, background, camera, objects,
// illumination, the 3-D scene, each frame's noise) draws from its own cv::RNG seeded from the
// options' seed, so a part drawing more numbers never shifts another's, and frame t's noise needs
// no earlier frame.
#pragma once

#include <cmath>
#include <cstdint>

#include <opencv2/core.hpp>

namespace movseg {

enum class SynthStream : std::uint64_t {
  kPalette = 1,
  kBackground,
  kCamera,
  kObjects,
  kIllumination,
  kNoise,
  kScene,  // the 3-D scene's layout and textures
};

// SplitMix64's finaliser: neighbouring seeds give unrelated generator states.
inline std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline cv::RNG synthRng(std::uint64_t seed, SynthStream stream, std::uint64_t index = 0) {
  return cv::RNG(
      splitMix64(splitMix64(splitMix64(seed) ^ static_cast<std::uint64_t>(stream)) ^ index));
}

// The camera paths' angles are drawn in degrees.
constexpr double kDegree = CV_PI / 180;

// amplitude * sin(2π t / period + phase): the smooth, bounded motions of the generator.
struct Wave {
  double amplitude = 0;
  double period = 1;
  double phase = 0;
  double at(double t) const { return amplitude * std::sin(2 * CV_PI * t / period + phase); }
};

// A wave of random period and phase whose rate of change peaks at `max_rate` per frame.
inline Wave waveWithRate(double max_rate, double min_period, double max_period, cv::RNG& rng) {
  Wave wave;
  wave.period = rng.uniform(min_period, max_period);
  wave.phase = rng.uniform(0.0, 2 * CV_PI);
  wave.amplitude = max_rate * wave.period / (2 * CV_PI);
  return wave;
}

// A sweep that starts near its top speed `rate` and, over a period of min_period to max_period
// frames, slows down and sweeps back: what the camera sees stays bounded however long the clip.
inline Wave sweepWave(double rate, double min_period, double max_period, cv::RNG& rng) {
  Wave wave;
  wave.period = rng.uniform(min_period, max_period);
  wave.phase = rng.uniform(-0.4, 0.4);
  wave.amplitude = rate * wave.period / (2 * CV_PI);
  return wave;
}

// The sweep of a pan: a period of 200 to 360 frames.
inline Wave panWave(double rate, cv::RNG& rng) { return sweepWave(rate, 200, 360, rng); }

// A fast wobble of hand-held shake: periods of 6 to 24 frames.
inline Wave shakeWave(double amplitude, cv::RNG& rng) {
  Wave wave;
  wave.amplitude = amplitude;
  wave.period = rng.uniform(6.0, 24.0);
  wave.phase = rng.uniform(0.0, 2 * CV_PI);
  return wave;
}

}  // namespace movseg
