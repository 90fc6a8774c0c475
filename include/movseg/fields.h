// Params and Diagnostics described field by field, for code that handles them by name:
// command-line options, language bindings, logs, user interfaces. Generated from
// movseg/params.def and movseg/diagnostics.def, so it always lists every field.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include <opencv2/core.hpp>

#include "movseg/params.h"
#include "movseg/segmenter.h"

namespace movseg {

enum class FieldType { kBool, kInt, kUnsigned, kReal, kChoice, kMatrix };

struct FieldInfo {
  std::string name;
  FieldType type = FieldType::kReal;
  double min = 0, max = 0;  // inclusive range of kInt, kReal and kChoice values
  int step = 0;             // kInt: the valid values are min, min + step, ...
  std::string unit;         // "" when none
  std::string doc;          // one line
  std::vector<std::string> choices;  // kChoice: the names, by value
};

// A field's value; kChoice fields give their name.
using FieldValue = std::variant<bool, int, std::uint64_t, double, std::string, cv::Matx33d>;

// The names of an enum of params.h, by value ("paper", "diff", ...; "affine", "homography").
template <typename Enum>
const std::vector<std::string>& enumNames();
template <>
const std::vector<std::string>& enumNames<Method>();
template <>
const std::vector<std::string>& enumNames<MotionModel>();

// ---- Params ----
const std::vector<FieldInfo>& paramFields();  // in params.def's order
// Throws std::invalid_argument "unknown parameter 'name'" for a name not in the table.
const FieldInfo& paramField(const std::string& name);
FieldValue paramValue(const Params& params, const std::string& name);
// Parses `text` as the field's value — booleans: true, false, 1 or 0 in any case; choices: a
// name of enumNames<>(); numbers: the whole text — and checks its range. Throws
// std::invalid_argument with a one-line message naming the field.
void setParam(Params* params, const std::string& name, const std::string& text);

// ---- Diagnostics ----
const std::vector<FieldInfo>& diagnosticFields();  // in diagnostics.def's order
FieldValue diagnosticValue(const Diagnostics& diagnostics, const std::string& name);

// A value as text: "true", "11", "0.5", "homography"; a matrix as "[a, b, c; d, e, f; g, h, i]".
std::string toText(const FieldValue& value);

// The field's doc line with what check() accepts: "Lucas-Kanade window side [3..101 odd px]",
// "camera model ... {affine, homography}". For --help, docstrings and property blurbs.
std::string helpText(const FieldInfo& field);

}  // namespace movseg
