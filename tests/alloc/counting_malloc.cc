#include "alloc/counting_malloc.h"

#include <atomic>
#include <cerrno>
#include <cstddef>

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
}

namespace {

// Process-wide, so that what OpenCV's worker threads allocate for a call counts too.
std::atomic<bool> g_counting{false};
std::atomic<std::int64_t> g_count{0};

void counted() {
  if (g_counting.load(std::memory_order_relaxed)) g_count.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

extern "C" {

void* malloc(std::size_t size) {
  counted();
  return __libc_malloc(size);
}

void* calloc(std::size_t count, std::size_t size) {
  counted();
  return __libc_calloc(count, size);
}

void* realloc(void* pointer, std::size_t size) {
  counted();
  return __libc_realloc(pointer, size);
}

void* memalign(std::size_t alignment, std::size_t size) {
  counted();
  return __libc_memalign(alignment, size);
}

void* aligned_alloc(std::size_t alignment, std::size_t size) {
  counted();
  return __libc_memalign(alignment, size);
}

int posix_memalign(void** pointer, std::size_t alignment, std::size_t size) {
  counted();
  *pointer = __libc_memalign(alignment, size);
  return *pointer != nullptr ? 0 : ENOMEM;
}

}  // extern "C"

namespace movseg::test {

CountAllocations::CountAllocations() {
  g_count = 0;
  g_counting = true;
}

CountAllocations::~CountAllocations() { g_counting = false; }

std::int64_t CountAllocations::count() const { return g_count; }

}  // namespace movseg::test
