#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace movseg::cli {

using Clock = std::chrono::steady_clock;

Progress::Progress(std::string label, int total, bool quiet, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      quiet_(quiet),
      terminal_(isatty(fileno(stderr)) != 0),
      start_(Clock::now()),
      last_print_(start_) {}

void Progress::update(int done) {
  if (quiet_) return;
  const Clock::time_point now = Clock::now();
  const double since_print = std::chrono::duration<double>(now - last_print_).count();
  // A terminal is redrawn ten times a second; a log gets a line every five seconds.
  if (since_print < (terminal_ ? 0.1 : 5.0) && done != total_) return;
  last_print_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const double fps = seconds > 0 ? done / seconds : 0;
  if (!terminal_) {
    std::fprintf(stderr, "%s: %d %s, %.1f per second\n", label_.c_str(), done, unit_.c_str(), fps);
    return;
  }
  if (total_ > 0) {
    constexpr int kWidth = 30;
    const int filled = done * kWidth / total_;
    std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d %s, %.1f per second ", label_.c_str(), filled,
                 "##############################", kWidth - filled, "", done, total_,
                 unit_.c_str(), fps);
  } else {
    std::fprintf(stderr, "\r%s %d %s, %.1f per second ", label_.c_str(), done, unit_.c_str(), fps);
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (!quiet_ && terminal_) std::fprintf(stderr, "\n");
}

}  // namespace movseg::cli
