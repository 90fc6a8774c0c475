#include "commands.h"

#include <regex>

namespace movseg::cli {

cv::Size parseSize(const std::string& option, const std::string& text) {
  // Six digits at most: std::stoi cannot overflow, and no frame side has more.
  const std::regex pattern(R"((\d{1,6})[xX](\d{1,6}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    throw UsageError(option + " must be WIDTHxHEIGHT, e.g. 320x240 (got '" + text + "')");
  }
  return {std::stoi(match[1]), std::stoi(match[2])};
}

}  // namespace movseg::cli
