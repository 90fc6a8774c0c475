// Pins the bytes the generator wrote before the 3-D scene, camouflage and speed options were
// added: every option set that existed then must keep giving the same frames, masks and camera
// models (README's tables and the other tests were measured on them). The hashes were taken on
// x86-64 with OpenCV 4.6; another OpenCV build may resample differently and legitimately fail
// here, in which case the other synth tests say whether the generator itself is still right.
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "synth/synth.h"

namespace movseg {
namespace {

// FNV-1a, 64 bits.
class Hash {
 public:
  void add(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) value_ = (value_ ^ bytes[i]) * 0x100000001B3ull;
  }
  void add(const cv::Mat& image) {
    ASSERT_TRUE(image.isContinuous());
    add(image.data, image.total() * image.elemSize());
  }
  std::uint64_t value() const { return value_; }

 private:
  std::uint64_t value_ = 0xCBF29CE484222325ull;
};

// The frame, mask and camera model of the listed frames, in that order.
std::uint64_t sequenceHash(const SynthOptions& options, const std::vector<int>& frames) {
  const SynthSequence sequence(options);
  Hash hash;
  for (const int t : frames) {
    const SynthFrame f = sequence.frame(t);
    hash.add(f.frame);
    hash.add(f.mask);
    hash.add(f.camera.val, sizeof(f.camera.val));
  }
  return hash.value();
}

std::string hex(std::uint64_t value) {
  char text[20];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(value));
  return text;
}

TEST(SynthGolden, DefaultClipIsUnchanged) {
  EXPECT_EQ(hex(sequenceHash(SynthOptions(), {0, 1, 31, 59})), "a923b11cfbe5f8b0");
}

TEST(SynthGolden, EveryCameraMotionIsUnchanged) {
  const std::pair<SynthCamera, const char*> expected[] = {
      {SynthCamera::kPan, "65cbf84e46277a8e"},    {SynthCamera::kZoom, "44a256104468d849"},
      {SynthCamera::kRotate, "13e43a624d9d8436"}, {SynthCamera::kShake, "a9ea9b21d02e14ef"},
      {SynthCamera::kStatic, "67bd915d11d52562"}, {SynthCamera::kMix, "6d6bc440aa8a6abe"},
  };
  for (const auto& [camera, hash] : expected) {
    SynthOptions options;
    options.camera = camera;
    options.frames = 20;
    options.seed = 7;
    EXPECT_EQ(hex(sequenceHash(options, {0, 19})), hash) << synthCameraName(camera);
  }
}

TEST(SynthGolden, NonDefaultOptionsAreUnchanged) {
  SynthOptions options;
  options.frames = 12;
  options.size = cv::Size(160, 96);
  options.seed = 5;
  options.camera = SynthCamera::kPan;
  options.objects = 3;
  options.noise_sigma = 5;
  options.illumination_drift = 0.3;
  EXPECT_EQ(hex(sequenceHash(options, {0, 11})), "94d1512b029c8318");
  options.background = false;
  options.noise_sigma = 0;
  EXPECT_EQ(hex(sequenceHash(options, {3, 7})), "97e2fab5a3512641");
}

}  // namespace
}  // namespace movseg
