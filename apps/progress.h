// Progress on stderr: a redrawn bar with fps on a terminal, a plain line now and then otherwise.
#pragma once

#include <chrono>
#include <string>

namespace movseg::cli {

class Progress {
 public:
  // total < 0 when unknown (camera, stream); `unit` names what is counted.
  Progress(std::string label, int total, bool quiet = false, std::string unit = "frames");
  void update(int done);
  void finish();

 private:
  std::string label_, unit_;
  int total_;
  bool quiet_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace movseg::cli
