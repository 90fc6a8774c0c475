#include "core/worker.h"

#include <unistd.h>

#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

namespace movseg {

struct Worker::State {
  std::mutex mutex;
  std::condition_variable wake, done;
  std::function<void()> task;
  std::exception_ptr error;
  bool quit = false;
  std::thread thread;  // last: it starts once the members above are made
};

Worker::Worker() : process_(::getpid()), state_(std::make_unique<State>()) {
  state_->thread = std::thread(run, state_.get());
}

Worker::~Worker() {
  if (inAnotherProcess()) {
    (void)state_.release();  // the thread is the parent's: nothing here to join or to wake
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    state_->quit = true;
  }
  state_->wake.notify_all();
  state_->thread.join();
}

bool Worker::inAnotherProcess() const { return ::getpid() != process_; }

void Worker::refuseInAnotherProcess() const {
  if (inAnotherProcess()) {
    throw std::runtime_error(
        "this object's thread was started in the process it was forked from, and a forked "
        "process has none: make the object in this process (or use one thread)");
  }
}

void Worker::start(std::function<void()> task) {
  refuseInAnotherProcess();
  {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    state_->task = std::move(task);
  }
  state_->wake.notify_all();
}

void Worker::wait() {
  refuseInAnotherProcess();
  std::unique_lock<std::mutex> lock(state_->mutex);
  state_->done.wait(lock, [this] { return !state_->task; });
  if (state_->error) std::rethrow_exception(std::exchange(state_->error, nullptr));
}

void Worker::run(State* state) {
  std::unique_lock<std::mutex> lock(state->mutex);
  for (;;) {
    state->wake.wait(lock, [state] { return state->task || state->quit; });
    if (state->quit) return;
    lock.unlock();
    std::exception_ptr error;
    try {
      state->task();
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    state->error = error;
    state->task = nullptr;
    state->done.notify_all();
  }
}

}  // namespace movseg
