#include "alloc/counting_malloc.h"

#include <cerrno>
#include <cstddef>

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
}

namespace {

thread_local bool t_counting = false;
thread_local std::int64_t t_count = 0;

void counted() {
  if (t_counting) ++t_count;
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
  t_count = 0;
  t_counting = true;
}

CountAllocations::~CountAllocations() { t_counting = false; }

std::int64_t CountAllocations::count() const { return t_count; }

}  // namespace movseg::test
