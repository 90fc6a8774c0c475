// One task at a time on a thread of its own, kept for the owner's life (a thread per task would
// cost its creation and its stack's page faults every frame). StreamSegmenter analyses the next
// frame on one; `movseg segment --threads 2` reads the next frame on another.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace movseg {

class Worker {
 public:
  Worker();
  ~Worker();  // lets the task in flight end first
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Runs `task` on the worker's thread; the previous one must have been waited for.
  void start(std::function<void()> task);

  // Waits for the task started last, if any; rethrows what it threw.
  void wait();

 private:
  void run();

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::function<void()> task_;
  std::exception_ptr error_;
  bool quit_ = false;
  std::thread thread_;  // last: it starts once the members above are made
};

}  // namespace movseg
