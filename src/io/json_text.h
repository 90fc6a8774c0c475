// JSON text of the reports and manifests movseg writes.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace movseg {

// `value` as JSON text (indented by `indent` spaces, on one line for -1). Its strings may hold
// any bytes: a Linux file name need not be UTF-8, which nlohmann::json refuses to write, so each
// byte that is not UTF-8 is written as U+FFFD.
inline std::string jsonText(const nlohmann::json& value, int indent = -1) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

// `text` with each byte that is not UTF-8 replaced by U+FFFD, as jsonText() writes it: for text
// outside JSON that must be UTF-8 too (an HTML page's headings).
inline std::string utf8Text(const std::string& text) {
  return nlohmann::json::parse(jsonText(text)).get<std::string>();
}

}  // namespace movseg
