#include "synth/synth.h"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "synth/synth_checks.h"

namespace movseg {
namespace {

// Every camera motion the plane has (dolly and forward are the 3-D scene's only).
constexpr SynthCamera kPlaneCameras[] = {SynthCamera::kPan,    SynthCamera::kZoom,
                                         SynthCamera::kRotate, SynthCamera::kShake,
                                         SynthCamera::kStatic, SynthCamera::kMix};

SynthOptions makeOptions(SynthCamera camera, int frames, std::uint64_t seed = 1) {
  SynthOptions options;
  options.camera = camera;
  options.frames = frames;
  options.seed = seed;
  return options;
}

bool touchesBorder(const cv::Mat& mask) {
  const int w = mask.cols, h = mask.rows;
  return cv::countNonZero(mask.row(0)) + cv::countNonZero(mask.row(h - 1)) +
             cv::countNonZero(mask.col(0)) + cv::countNonZero(mask.col(w - 1)) >
         0;
}

// Mean absolute difference, over channels, between `current` and `previous` warped by `model`
// on the background both frames see: away from the image border and from either frame's objects.
double alignmentError(const SynthFrame& previous, const SynthFrame& current,
                      const cv::Matx33d& model) {
  const cv::Size size = current.frame.size();
  cv::Mat warped, warped_mask, seen;
  cv::warpPerspective(previous.frame, warped, model, size, cv::INTER_LINEAR);
  cv::warpPerspective(previous.mask, warped_mask, model, size, cv::INTER_NEAREST);
  cv::warpPerspective(cv::Mat(previous.mask.size(), CV_8U, cv::Scalar(255)), seen, model, size,
                      cv::INTER_NEAREST);
  cv::erode(seen, seen, cv::Mat(), cv::Point(-1, -1), 2);
  cv::Mat objects = warped_mask | current.mask;
  cv::dilate(objects, objects, cv::Mat(), cv::Point(-1, -1), 2);
  const cv::Mat background = seen & ~objects;
  cv::Mat difference;
  cv::absdiff(warped, current.frame, difference);
  const cv::Scalar mean = cv::mean(difference, background);
  return (mean[0] + mean[1] + mean[2]) / 3;
}

double maxDisplacement(const cv::Matx33d& model, cv::Size size) {
  const double w = size.width - 1, h = size.height - 1;
  double largest = 0;
  for (const cv::Vec3d& p : {cv::Vec3d(0, 0, 1), cv::Vec3d(w, 0, 1), cv::Vec3d(0, h, 1),
                             cv::Vec3d(w, h, 1), cv::Vec3d(w / 2, h / 2, 1)}) {
    const cv::Vec3d q = model * p;
    largest = std::max(largest, std::hypot(q[0] / q[2] - p[0], q[1] / q[2] - p[1]));
  }
  return largest;
}

TEST(Synth, SameSeedGivesIdenticalBytesInAnyOrder) {
  const SynthOptions options = makeOptions(SynthCamera::kMix, 12, 7);
  const SynthSequence a(options), b(options);
  const SynthFrame late = b.frame(9);  // random access first: nothing may depend on call order
  for (int t = 0; t < a.size(); ++t) {
    const SynthFrame x = a.frame(t), y = t == 9 ? late : b.frame(t);
    EXPECT_TRUE(sameBytes(x.frame, y.frame)) << "frame " << t;
    EXPECT_TRUE(sameBytes(x.mask, y.mask)) << "frame " << t;
    EXPECT_EQ(x.camera, y.camera) << "frame " << t;
  }
}

TEST(Synth, DifferentSeedsGiveDifferentSequences) {
  const SynthSequence a(makeOptions(SynthCamera::kMix, 3, 1)),
      b(makeOptions(SynthCamera::kMix, 3, 2));
  const SynthFrame x = a.frame(2), y = b.frame(2);
  EXPECT_FALSE(sameBytes(x.frame, y.frame));
  EXPECT_FALSE(sameBytes(x.mask, y.mask));
  EXPECT_NE(x.camera, y.camera);
}

TEST(Synth, FramesAndMasksHaveTheDocumentedFormat) {
  SynthOptions options = makeOptions(SynthCamera::kPan, 5);
  options.size = cv::Size(200, 120);
  const SynthSequence sequence(options);
  ASSERT_EQ(sequence.size(), 5);
  for (int t = 0; t < sequence.size(); ++t) {
    const SynthFrame f = sequence.frame(t);
    EXPECT_EQ(f.frame.type(), CV_8UC3);
    EXPECT_EQ(f.frame.size(), options.size);
    ASSERT_EQ(f.mask.type(), CV_8U);
    EXPECT_EQ(f.mask.size(), options.size);
    EXPECT_EQ(cv::countNonZero(f.mask == 0) + cv::countNonZero(f.mask == 255), f.mask.total())
        << "mask values other than 0 and 255 in frame " << t;
  }
  EXPECT_EQ(sequence.frame(0).camera, cv::Matx33d::eye());
  EXPECT_THROW(sequence.frame(5), std::out_of_range);
  EXPECT_THROW(sequence.frame(-1), std::out_of_range);
}

// On black, an object pixel is exactly a non-black pixel: the mask can neither miss an object
// pixel nor claim a background one. With the background drawn, the object pixels are unchanged.
TEST(Synth, MaskIsExactlyWhereObjectsWereDrawn) {
  SynthOptions options = makeOptions(SynthCamera::kMix, 40, 5);
  options.objects = 3;
  options.noise_sigma = 0;
  EXPECT_GT(expectMasksAreTheDrawnObjects(options, 1), 0);
}

// Warping frame t-1 by the true model reproduces frame t's background up to resampling (noise
// off), and better than any model a quarter pixel off: the model is right to well under a pixel.
TEST(Synth, CameraModelAlignsConsecutiveBackgrounds) {
  const cv::Vec2d quarter_pixel_shifts[] = {{0.25, 0}, {-0.25, 0}, {0, 0.25}, {0, -0.25}};
  for (const SynthCamera camera : kPlaneCameras) {
    SynthOptions options = makeOptions(camera, 5, 11);
    options.noise_sigma = 0;
    const SynthSequence sequence(options);
    SynthFrame previous = sequence.frame(0);
    for (int t = 1; t < sequence.size(); ++t) {
      const SynthFrame current = sequence.frame(t);
      const double error = alignmentError(previous, current, current.camera);
      EXPECT_LT(error, 2.0) << synthCameraName(camera) << " frame " << t;
      for (const cv::Vec2d& shift : quarter_pixel_shifts) {
        const cv::Matx33d off =
            cv::Matx33d(1, 0, shift[0], 0, 1, shift[1], 0, 0, 1) * current.camera;
        EXPECT_LT(error, alignmentError(previous, current, off))
            << synthCameraName(camera) << " frame " << t << " shift " << shift;
      }
      previous = current;
    }
  }
}

TEST(Synth, CameraModelAlignsNoisyFramesToWithinNoise) {
  const SynthSequence sequence(makeOptions(SynthCamera::kMix, 4, 12));
  for (int t = 1; t < sequence.size(); ++t) {
    const SynthFrame current = sequence.frame(t);
    EXPECT_LT(alignmentError(sequence.frame(t - 1), current, current.camera), 4.0) << "frame " << t;
  }
}

TEST(Synth, CameraMotionHasRealisticMagnitudes) {
  for (const SynthCamera camera : kPlaneCameras) {
    const SynthSequence sequence(makeOptions(camera, 60, 3));
    double largest = 0, total = 0;
    for (int t = 1; t < sequence.size(); ++t) {
      const cv::Matx33d model = sequence.frame(t).camera;
      if (camera == SynthCamera::kStatic) {
        EXPECT_EQ(model, cv::Matx33d::eye());
      }
      const double moved = maxDisplacement(model, sequence.options().size);
      largest = std::max(largest, moved);
      total += moved;
    }
    EXPECT_LE(largest, 8.0) << synthCameraName(camera);
    if (camera != SynthCamera::kStatic) {
      EXPECT_GT(total / 59, 0.3) << synthCameraName(camera);
    }
  }
}

// The canvas holds everything any frame sees: a frame pixel outside it would come out black.
TEST(Synth, BackgroundCoversEveryPixelOfEveryFrame) {
  for (const SynthCamera camera : {SynthCamera::kPan, SynthCamera::kMix}) {
    SynthOptions options = makeOptions(camera, 150, 4);
    options.noise_sigma = 0;
    const SynthSequence sequence(options);
    for (int t = 0; t < sequence.size(); ++t) {
      double darkest;
      cv::minMaxLoc(sequence.frame(t).frame.reshape(1), &darkest);
      ASSERT_GE(darkest, 15) << synthCameraName(camera) << " frame " << t;
    }
  }
}

// Corners (Shi–Tomasi, as the motion stage detects them) in every 80x80 cell of the frame.
TEST(Synth, BackgroundIsTexturedEverywhere) {
  const SynthSequence sequence(makeOptions(SynthCamera::kStatic, 1, 8));
  cv::Mat grey;
  cv::cvtColor(sequence.frame(0).frame, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(grey, corners, 2000, 0.01, 4);
  int counts[3][4] = {};
  for (const cv::Point2f& p : corners)
    ++counts[static_cast<int>(p.y) / 80][static_cast<int>(p.x) / 80];
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col)
      EXPECT_GE(counts[row][col], 8) << "cell " << row << "," << col;
  }
}

// How far the mask's centroid moves between consecutive frames in which the (single) object is
// wholly in view.
std::vector<double> centroidSteps(const SynthSequence& sequence) {
  std::vector<double> steps;
  cv::Point2d last_centre(-1, -1);
  for (int t = 0; t < sequence.size(); ++t) {
    const cv::Mat mask = sequence.frame(t).mask;
    if (touchesBorder(mask) || cv::countNonZero(mask) == 0) {
      last_centre = cv::Point2d(-1, -1);
      continue;
    }
    const cv::Moments m = cv::moments(mask, true);
    const cv::Point2d centre(m.m10 / m.m00, m.m01 / m.m00);
    if (last_centre.x >= 0) steps.push_back(cv::norm(centre - last_centre));
    last_centre = centre;
  }
  return steps;
}

SynthOptions singleObjectOnBlack(std::uint64_t seed) {
  SynthOptions options = makeOptions(SynthCamera::kStatic, 40, seed);
  options.objects = 1;
  options.background = false;
  options.noise_sigma = 0;
  return options;
}

TEST(Synth, ObjectsHaveTheSpecifiedSizesAndSpeeds) {
  int whole_views = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const SynthSequence sequence(singleObjectOnBlack(seed));
    for (int t = 0; t < sequence.size(); ++t) {
      const cv::Mat mask = sequence.frame(t).mask;
      if (touchesBorder(mask) || cv::countNonZero(mask) == 0) continue;
      ++whole_views;
      const double fraction = static_cast<double>(cv::countNonZero(mask)) / mask.total();
      EXPECT_GE(fraction, 0.045) << "seed " << seed << " frame " << t;
      EXPECT_LE(fraction, 0.255) << "seed " << seed << " frame " << t;
    }
    for (const double speed : centroidSteps(sequence)) {
      EXPECT_GE(speed, 0.7) << "seed " << seed;
      EXPECT_LE(speed, 6.5) << "seed " << seed;
    }
  }
  EXPECT_GT(whole_views, 20);
}

// Every step within the range (give or take the centroid's turn with the object), and the range
// is used: the objects' mean speeds spread over most of it.
TEST(Synth, ObjectSpeedRangeIsRespected) {
  double slowest = 1e9, fastest = 0;
  int steps = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    SynthOptions options = singleObjectOnBlack(seed);
    options.frames = 60;
    options.object_speed_min = 1;
    options.object_speed_max = 3.5;
    const std::vector<double> speeds = centroidSteps(SynthSequence(options));
    if (speeds.empty()) continue;
    double sum = 0;
    for (const double speed : speeds) {
      EXPECT_GE(speed, 0.75) << "seed " << seed;
      EXPECT_LE(speed, 3.75) << "seed " << seed;
      sum += speed;
    }
    slowest = std::min(slowest, sum / speeds.size());
    fastest = std::max(fastest, sum / speeds.size());
    steps += static_cast<int>(speeds.size());
  }
  EXPECT_GT(steps, 60);
  EXPECT_LT(slowest, 2.0);
  EXPECT_GT(fastest, 2.5);
}

// Colour statistics of a frame's object pixels against its background pixels: the distance
// between their mean colours and the largest per-channel ratio of standard deviations (>= 1).
struct ColourContrast {
  double mean_distance = 0;
  double deviation_ratio = 1;
};

ColourContrast colourContrast(const SynthFrame& f) {
  cv::Scalar object_mean, object_deviation, background_mean, background_deviation;
  cv::meanStdDev(f.frame, object_mean, object_deviation, f.mask);
  cv::meanStdDev(f.frame, background_mean, background_deviation, ~f.mask);
  ColourContrast contrast;
  contrast.mean_distance = cv::norm(object_mean - background_mean);
  for (int c = 0; c < 3; ++c) {
    const double ratio = object_deviation[c] / background_deviation[c];
    contrast.deviation_ratio = std::max(contrast.deviation_ratio, std::max(ratio, 1 / ratio));
  }
  return contrast;
}

ColourContrast meanContrastOverSeeds(bool camouflage) {
  constexpr int kSeeds = 8;
  ColourContrast mean{0, 0};
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    SynthOptions options = makeOptions(SynthCamera::kStatic, 1, seed);
    options.objects = 1;
    options.noise_sigma = 0;
    options.camouflage = camouflage;
    const ColourContrast contrast = colourContrast(SynthSequence(options).frame(0));
    mean.mean_distance += contrast.mean_distance / kSeeds;
    mean.deviation_ratio += contrast.deviation_ratio / kSeeds;
  }
  return mean;
}

// Camouflaged objects have the background's colour statistics (measured: mean colours 20 levels
// apart, deviations within a factor 1.4 — what a patch of background of the object's size gives
// against the rest); objects of their own colour do not (146 levels, a factor 3). Averaged over
// seeds: a single object may sit on an unusual patch.
TEST(Synth, CamouflagedObjectsMatchTheBackgroundStatistics) {
  const ColourContrast own = meanContrastOverSeeds(false);
  const ColourContrast camouflaged = meanContrastOverSeeds(true);
  EXPECT_LT(camouflaged.mean_distance, 30);
  EXPECT_LT(camouflaged.deviation_ratio, 1.6);
  EXPECT_GT(own.mean_distance, 80);
  EXPECT_GT(own.deviation_ratio, 2);
  EXPECT_LT(camouflaged.mean_distance, 0.25 * own.mean_distance);
}

TEST(Synth, ObjectsEnterAndLeaveTheFrame) {
  SynthOptions options = makeOptions(SynthCamera::kMix, 200, 1);
  options.background = false;
  options.noise_sigma = 0;
  const SynthSequence sequence(options);
  int at_border = 0, with_objects = 0;
  for (int t = 0; t < sequence.size(); ++t) {
    const cv::Mat mask = sequence.frame(t).mask;
    at_border += touchesBorder(mask);
    with_objects += cv::countNonZero(mask) > 0;
  }
  EXPECT_GT(at_border, 0);
  EXPECT_GT(with_objects, 100);
}

// The defaults, and the sensor of the sequences movseg is checked on elsewhere (sigma 2, ±10 %).
TEST(Synth, NoiseAndIlluminationFollowTheOptions) {
  for (const auto& [sigma, drift] : {std::pair{2.5, 0.04}, std::pair{2.0, 0.1}}) {
    SynthOptions options = makeOptions(SynthCamera::kStatic, 150, 6);
    options.noise_sigma = 0;
    options.illumination_drift = drift;
    SynthOptions noisy = options;
    noisy.noise_sigma = sigma;
    const SynthSequence clean(options), sensor(noisy);
    cv::Mat difference;
    cv::subtract(sensor.frame(0).frame, clean.frame(0).frame, difference, cv::noArray(), CV_32F);
    cv::Scalar mean, deviation;
    cv::meanStdDev(difference.reshape(1), mean, deviation);
    EXPECT_NEAR(deviation[0], sigma, 0.3);
    // Gain relative to frame 0, on the background of both frames.
    const SynthFrame first = clean.frame(0);
    double largest_change = 0;
    for (int t = 10; t < clean.size(); t += 10) {
      const SynthFrame f = clean.frame(t);
      const cv::Mat background = ~(first.mask | f.mask);
      const double ratio = cv::mean(f.frame, background)[1] / cv::mean(first.frame, background)[1];
      largest_change = std::max(largest_change, std::abs(ratio - 1));
    }
    EXPECT_GT(largest_change, drift / 4) << "drift " << drift;
    EXPECT_LT(largest_change, 2 * drift + 0.005) << "drift " << drift;
  }
}

TEST(Synth, InvalidOptionsThrow) {
  const auto throws = [](auto change) {
    SynthOptions options;
    change(options);
    EXPECT_THROW(SynthSequence{options}, std::invalid_argument);
  };
  throws([](SynthOptions& o) { o.frames = 0; });
  throws([](SynthOptions& o) { o.size = cv::Size(10, 10); });
  throws([](SynthOptions& o) { o.size = cv::Size(320, 15); });
  throws([](SynthOptions& o) { o.objects = 0; });
  throws([](SynthOptions& o) { o.objects = 4; });
  throws([](SynthOptions& o) { o.noise_sigma = -1; });
  throws([](SynthOptions& o) { o.illumination_drift = 0.9; });
  throws([](SynthOptions& o) { o.object_speed_min = 0; });
  throws([](SynthOptions& o) { o.object_speed_min = 4, o.object_speed_max = 3; });
  throws([](SynthOptions& o) { o.object_speed_max = 31; });
  throws([](SynthOptions& o) { o.camera = SynthCamera::kDolly; });  // the plane has no depth
  throws([](SynthOptions& o) { o.camera = SynthCamera::kForward; });
  SynthOptions smallest;
  smallest.size = cv::Size(16, 16);
  smallest.frames = 1;
  EXPECT_NO_THROW(SynthSequence{smallest}.frame(0));
}

TEST(Synth, CameraAndSceneNamesRoundTrip) {
  for (const SynthCamera camera : kPlaneCameras) {
    EXPECT_EQ(parseSynthCamera(synthCameraName(camera)), camera);
  }
  EXPECT_EQ(parseSynthCamera("mix"), SynthCamera::kMix);
  EXPECT_EQ(parseSynthCamera("dolly"), SynthCamera::kDolly);
  EXPECT_EQ(parseSynthCamera("forward"), SynthCamera::kForward);
  EXPECT_THROW(parseSynthCamera("tilt"), std::invalid_argument);
  EXPECT_THROW(parseSynthCamera("Pan"), std::invalid_argument);
  EXPECT_EQ(parseSynthScene("plane"), SynthScene::kPlane);
  EXPECT_EQ(parseSynthScene("depth"), SynthScene::kDepth);
  EXPECT_EQ(synthSceneName(SynthScene::kDepth), "depth");
  EXPECT_THROW(parseSynthScene("3d"), std::invalid_argument);
}

}  // namespace
}  // namespace movseg
