// libFuzzer entry point: the ground-truth, mask and frame readers on the files of
// readers_input.h.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "readers_input.h"

namespace {

namespace fs = std::filesystem;

// A scratch folder of this process's own (libFuzzer may run several), removed at exit; in
// memory where /dev/shm exists, since every run writes and deletes files.
class Scratch {
 public:
  Scratch() {
    std::error_code error;
    const fs::path base =
        fs::is_directory("/dev/shm", error) ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string pattern = (base / "movseg-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();  // no scratch space, no fuzzing
    path_ = pattern;
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const Scratch scratch;
  movseg::fuzz::runReadersInput(data, size, scratch.path() + "/input");
  return 0;
}
