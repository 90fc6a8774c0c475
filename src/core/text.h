// Small text helpers shared by the parameter parser and the file readers and writers.
#pragma once

#include <algorithm>
#include <cctype>
#include <string>

namespace movseg {

// `text` in lower case, byte by byte (ASCII: names, extensions, keywords).
inline std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// `text` on one line, whatever it holds (a file name may contain a newline): errors and table
// rows are one line.
inline std::string oneLine(std::string text) {
  for (char& c : text) c = c == '\n' || c == '\r' ? ' ' : c;
  return text;
}

}  // namespace movseg
