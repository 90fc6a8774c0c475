// Independent runs (inputs, benchmark sequences) on several threads at once.
#pragma once

#include <cstddef>
#include <functional>

namespace movseg::cli {

// Calls task(0), ..., task(count - 1), at most `threads` at a time, each call on one thread (the
// calling thread is one of them); returns once every call has ended. Once a call throws, no
// further call starts, and the first exception is rethrown after the running calls end (a task
// that must not stop the others catches its own).
void runConcurrently(size_t count, int threads, const std::function<void(size_t)>& task);

}  // namespace movseg::cli
