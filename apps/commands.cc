#include "commands.h"

#include <filesystem>
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
