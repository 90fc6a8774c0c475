#include "commands.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <regex>

#include "io/atomic_write.h"
#include "synth/synth.h"

namespace movseg::cli {

namespace fs = std::filesystem;

cv::Size parseSize(const std::string& option, const std::string& text) {
  // Six digits at most: std::stoi cannot overflow, and no frame side has more.
  const std::regex pattern(R"((\d{1,6})[xX](\d{1,6}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    throw UsageError(option + " must be WIDTHxHEIGHT, e.g. 320x240 (got '" + text + "')");
  }
  return {std::stoi(match[1]), std::stoi(match[2])};
}

void refuseEmptyNames(const CLI::App& command, std::initializer_list<const char*> options) {
  for (const char* name : options) {
    for (const std::string& value : command.get_option(name)->results()) {
      if (value.empty()) throw UsageError(std::string(name) + ": the name is empty");
    }
  }
}

bool isSameOrInside(const std::string& path, const std::string& base) {
  const auto normal = [](const std::string& name) {
    std::error_code error;
    const fs::path absolute = fs::absolute(name);
    fs::path full = fs::weakly_canonical(absolute, error);
    // A link that leads nowhere a path can name (/dev/stdin on a pipe: "pipe:[...]") is taken
    // as written; an empty path would count as the root of everything.
    if (error) full = absolute.lexically_normal();
    return full.filename().empty() ? full.parent_path() : full;  // "frames/" is "frames"
  };
  const fs::path p = normal(path), b = normal(base);
  const auto [end, _] = std::mismatch(b.begin(), b.end(), p.begin(), p.end());
  return end == b.end();
}

bool isSamePlace(const std::string& a, const std::string& b) {
  return isSameOrInside(a, b) && isSameOrInside(b, a);
}

void refuseSharedOutputs(std::initializer_list<std::pair<const char*, std::string>> outputs) {
  for (auto a = outputs.begin(); a != outputs.end(); ++a) {
    for (auto b = std::next(a); b != outputs.end(); ++b) {
      if (a->second.empty() || b->second.empty()) continue;
      if (isSamePlace(a->second, b->second)) {
        throw UsageError(oneLine(std::string(a->first) + " and " + b->first + " both name '" +
                                 b->second + "'"));
      }
    }
  }
}

fs::path temporaryFolder() {
  std::error_code error;
  fs::path folder = fs::temp_directory_path(error);
  if (error) {
    const char* tmpdir = std::getenv("TMPDIR");
    throw std::runtime_error(oneLine("no folder for temporary files: TMPDIR '" +
                                     std::string(tmpdir != nullptr ? tmpdir : "") +
                                     "': " + error.message()));
  }
  return folder;
}

void throwIfInterrupted(int frames, bool interrupted) {
  if (!interrupted) return;
  std::cerr << "movseg: interrupted after " << frames
            << " frames; the files written so far are complete\n";
  throw CLI::RuntimeError(kExitInterrupted);
}

void claimSequenceFolder(const std::string& dir, bool overwrite,
                         std::initializer_list<const char*> owned_folders) {
  std::error_code error;
  if (fs::is_directory(dir, error) && !fs::is_empty(dir, error)) {
    if (!overwrite) {
      throw UsageError("'" + dir +
                       "' is not empty; --overwrite replaces the frames, masks and "
                       "camera.jsonl of a sequence there");
    }
    removeSynthSequence(dir);
    for (const char* folder : owned_folders) {
      for (const std::string& file : frameFilesIn((fs::path(dir) / folder).string())) {
        fs::remove(file);
      }
    }
  }
}

}  // namespace movseg::cli
