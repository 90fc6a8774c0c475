// A scratch folder of this fuzzing process's own (libFuzzer may run several), removed at exit;
// in memory where /dev/shm exists, since every run writes and deletes files.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace movseg::fuzz {

class Scratch {
 public:
  Scratch() {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::path base =
        fs::is_directory("/dev/shm", error) ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string pattern = (base / "movseg-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();  // no scratch space, no fuzzing
    path_ = pattern;
  }
  ~Scratch() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace movseg::fuzz
