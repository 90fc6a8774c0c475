// The committed fuzz corpora (fuzz/corpus/<target>/, crash reproducers regression-* included)
// replayed through the fuzz scenarios in every build, the sanitizer build included.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "readers_input.h"
#include "segmenter_input.h"
#include "video_input.h"
#include "test_support.h"

namespace movseg {
namespace {

std::vector<std::string> corpus(const std::string& target) {
  const std::string folder = std::string(MOVSEG_SOURCE_DIR) + "/fuzz/corpus/" + target;
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

template <typename Run>
void replay(const std::string& target, Run run) {
  const std::vector<std::string> files = corpus(target);
  ASSERT_FALSE(files.empty());
  for (const std::string& file : files) {
    const std::string input = contents(file);
    try {
      run(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": " << e.what();
    }
  }
}

TEST(FuzzCorpus, SegmenterKeepsItsContract) { replay("segmenter", fuzz::runSegmenterInput); }

TEST(FuzzCorpus, ReadersOnlyFailWithRuntimeErrors) {
  test::TempDir dir;
  replay("readers", [&](const std::uint8_t* data, std::size_t size) {
    fuzz::runReadersInput(data, size, dir / "scratch");
  });
}

TEST(FuzzCorpus, VideosOnlyFailWithRuntimeErrors) {
  test::TempDir dir;
  replay("video", [&](const std::uint8_t* data, std::size_t size) {
    fuzz::runVideoInput(data, size, dir / "input.video");
  });
}

}  // namespace
}  // namespace movseg
