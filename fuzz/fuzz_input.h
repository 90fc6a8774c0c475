// Reads typed values off the front of a fuzz input. Past the end every value is the lowest one
// allowed, so that every input, even an empty one, decodes to a valid scenario and a mutation
// of one byte changes one decision.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace movseg::fuzz {

// A promise of movseg's that a scenario broke: std::logic_error naming it, which the scenario
// functions let out (a finding), apart from the exceptions movseg throws by contract.
inline void require(bool ok, const std::string& broken_promise) {
  if (!ok) throw std::logic_error(broken_promise);
}

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t byte() { return position_ < size_ ? data_[position_++] : 0; }
  bool flag() { return (byte() & 1) != 0; }
  // An integer in [low, high], high - low < 65536: one byte for small ranges, else two.
  int range(int low, int high) {
    const unsigned span = static_cast<unsigned>(high - low) + 1;
    unsigned value = byte();
    if (span > 256) value = value << 8 | byte();
    return low + static_cast<int>(value % span);
  }
  // A real number in [low, high] in 256 steps.
  double real(double low, double high) { return low + (high - low) * byte() / 255.0; }
  // The next `count` bytes, fewer at the end of the input.
  std::string bytes(std::size_t count) {
    const std::size_t n = count < size_ - position_ ? count : size_ - position_;
    std::string out(reinterpret_cast<const char*>(data_ + position_), n);
    position_ += n;
    return out;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

}  // namespace movseg::fuzz
