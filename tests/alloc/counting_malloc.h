// Counts the heap allocations made on any thread while a CountAllocations is alive, by
// standing in for malloc and its kin (operator new and cv::fastMalloc end there). Linked into
// its own test program only: sanitizers replace the allocator themselves.
#pragma once

#include <cstdint>

namespace movseg::test {

class CountAllocations {
 public:
  CountAllocations();
  ~CountAllocations();
  std::int64_t count() const;
};

}  // namespace movseg::test
