// One task at a time on a thread of its own, kept for the owner's life (a thread per task would
// cost its creation and its stack's page faults every frame). StreamSegmenter analyses the next
// frame on one; `movseg segment --threads 2` reads the next frame on another.
#pragma once

#include <sys/types.h>

#include <functional>
#include <memory>

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
  struct State;
  static void run(State* state);

  // In a process forked from the owner's the thread does not exist: start() and wait() throw
  // std::runtime_error, and the destructor leaves the state as it is (its mutex and condition
  // variables may be held by the thread that is gone; destroying them would wait for it).
  bool inAnotherProcess() const;
  void refuseInAnotherProcess() const;

  pid_t process_;
  std::unique_ptr<State> state_;
};

}  // namespace movseg
