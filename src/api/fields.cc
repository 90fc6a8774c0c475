// movseg/fields.h and Params::check(), generated from params.def and diagnostics.def.
#include "movseg/fields.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <type_traits>

#include "core/text.h"

namespace movseg {

template <>
const std::vector<std::string>& enumNames<Method>() {
  static const std::vector<std::string> names{"paper", "diff", "mog2", "mog2-comp", "dense"};
  return names;
}

template <>
const std::vector<std::string>& enumNames<MotionModel>() {
  static const std::vector<std::string> names{"affine", "homography"};
  return names;
}

namespace {

template <typename T>
constexpr FieldType fieldTypeOf() {
  if constexpr (std::is_same_v<T, bool>) return FieldType::kBool;
  if constexpr (std::is_same_v<T, int>) return FieldType::kInt;
  if constexpr (std::is_same_v<T, std::uint64_t>) return FieldType::kUnsigned;
  if constexpr (std::is_same_v<T, double>) return FieldType::kReal;
  if constexpr (std::is_enum_v<T>) return FieldType::kChoice;
  static_assert(std::is_same_v<T, bool> || std::is_same_v<T, int> ||
                    std::is_same_v<T, std::uint64_t> || std::is_same_v<T, double> ||
                    std::is_enum_v<T> || std::is_same_v<T, cv::Matx33d>,
                "a field type fields.h does not describe");
  return FieldType::kMatrix;
}

template <typename T>
FieldInfo describe(const char* name, double min, double max, int step, const char* unit,
                   const char* doc) {
  FieldInfo info{name, fieldTypeOf<T>(), min, max, step, unit, doc, {}};
  if constexpr (std::is_enum_v<T>) info.choices = enumNames<T>();
  return info;
}

// The shortest text that reads back as the same double: a run's recorded settings (movseg-run.json)
// must give the same masks when set again, which six significant digits did not.
std::string number(double value) {
  char text[32];
  const std::to_chars_result end = std::to_chars(std::begin(text), std::end(text), value);
  return std::string(text, end.ptr);
}

[[noreturn]] void reject(const FieldInfo& info, const std::string& rule, const std::string& got) {
  throw std::invalid_argument("invalid parameter: " + info.name + " must be " + rule + ", got " +
                              got);
}

std::string rangeRule(const FieldInfo& info) {
  std::string range = "in [" + number(info.min) + ", " + number(info.max) + "]";
  if (info.type != FieldType::kInt || info.step <= 1) return range;
  if (info.step == 2) return (std::fmod(info.min, 2) != 0 ? "odd and " : "even and ") + range;
  return range + " in steps of " + std::to_string(info.step);
}

std::string choiceRule(const FieldInfo& info) {
  std::string rule = "one of";
  for (const std::string& name : info.choices) rule += (rule == "one of" ? " " : ", ") + name;
  return rule;
}

// The range (and step) of params.def; NaN and infinity are never in range.
void checkNumber(const FieldInfo& info, double value) {
  bool ok = std::isfinite(value) && value >= info.min && value <= info.max;
  if (ok && info.type == FieldType::kInt && info.step > 1) {
    ok = std::fmod(value - info.min, info.step) == 0;
  }
  if (!ok) reject(info, rangeRule(info), number(value));
}

template <typename T>
void checkField(const FieldInfo& info, T value) {
  if constexpr (std::is_enum_v<T>) {
    const auto index = static_cast<std::size_t>(value);
    if (index >= info.choices.size()) reject(info, choiceRule(info), std::to_string(index));
  } else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, double>) {
    checkNumber(info, static_cast<double>(value));
  }
}

// The whole text as a finite or infinite double (range checks come after).
double parseReal(const FieldInfo& info, const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  reject(info, "a number", "'" + text + "'");
}

template <typename T>
T parseValue(const FieldInfo& info, const std::string& text) {
  if constexpr (std::is_same_v<T, bool>) {
    const std::string word = lowercase(text);
    if (word == "true" || word == "1") return true;
    if (word == "false" || word == "0") return false;
    reject(info, "true, false, 1 or 0", "'" + text + "'");
  } else if constexpr (std::is_enum_v<T>) {
    const auto& names = info.choices;
    const auto found = std::find(names.begin(), names.end(), lowercase(text));
    if (found == names.end()) reject(info, choiceRule(info), "'" + text + "'");
    return static_cast<T>(found - names.begin());
  } else if constexpr (std::is_same_v<T, std::uint64_t>) {
    const bool digits = !text.empty() && text.size() <= 20 &&
                        std::all_of(text.begin(), text.end(), [](unsigned char c) {
                          return std::isdigit(c);
                        });
    try {
      if (digits) return std::stoull(text);
    } catch (const std::out_of_range&) {
    }
    reject(info, "an integer in [0, 2^64 - 1]", "'" + text + "'");
  } else {
    const double value = parseReal(info, text);
    if constexpr (std::is_same_v<T, int>) {
      if (value != std::floor(value)) reject(info, "an integer", "'" + text + "'");
    }
    checkNumber(info, value);
    return static_cast<T>(value);
  }
}

template <typename T>
FieldValue valueOf(const T& value) {
  if constexpr (std::is_enum_v<T>) {
    const auto& names = enumNames<T>();
    const auto index = static_cast<std::size_t>(value);
    return index < names.size() ? names[index] : std::to_string(index);
  } else {
    return value;
  }
}

const FieldInfo* find(const std::vector<FieldInfo>& fields, const std::string& name) {
  for (const FieldInfo& info : fields) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

}  // namespace

const std::vector<FieldInfo>& paramFields() {
  static const std::vector<FieldInfo> fields{
#define MOVSEG_PARAM(type, name, default_value, min, max, step, unit, doc) \
  describe<type>(#name, min, max, step, unit, doc),
#include "movseg/params.def"
#undef MOVSEG_PARAM
  };
  return fields;
}

const FieldInfo& paramField(const std::string& name) {
  const FieldInfo* info = find(paramFields(), name);
  if (info == nullptr) throw std::invalid_argument("unknown parameter '" + name + "'");
  return *info;
}

FieldValue paramValue(const Params& params, const std::string& name) {
#define MOVSEG_PARAM(type, field, default_value, min, max, step, unit, doc) \
  if (name == #field) return valueOf(params.field);
#include "movseg/params.def"
#undef MOVSEG_PARAM
  throw std::invalid_argument("unknown parameter '" + name + "'");
}

void setParam(Params* params, const std::string& name, const std::string& text) {
  const FieldInfo& info = paramField(name);
#define MOVSEG_PARAM(type, field, default_value, min, max, step, unit, doc) \
  if (name == #field) params->field = parseValue<type>(info, text);
#include "movseg/params.def"
#undef MOVSEG_PARAM
}

bool operator==(const Params& a, const Params& b) {
  return true
#define MOVSEG_PARAM(type, name, default_value, min, max, step, unit, doc) && a.name == b.name
#include "movseg/params.def"
#undef MOVSEG_PARAM
      ;
}

void Params::check() const {
#define MOVSEG_PARAM(type, name, default_value, min, max, step, unit, doc) \
  checkField(paramField(#name), name);
#include "movseg/params.def"
#undef MOVSEG_PARAM
}

const std::vector<FieldInfo>& diagnosticFields() {
  static const std::vector<FieldInfo> fields{
#define MOVSEG_DIAGNOSTIC(type, name, default_value, unit, doc) \
  describe<type>(#name, 0, 0, 0, unit, doc),
#include "movseg/diagnostics.def"
#undef MOVSEG_DIAGNOSTIC
  };
  return fields;
}

FieldValue diagnosticValue(const Diagnostics& diagnostics, const std::string& name) {
#define MOVSEG_DIAGNOSTIC(type, field, default_value, unit, doc) \
  if (name == #field) return valueOf(diagnostics.field);
#include "movseg/diagnostics.def"
#undef MOVSEG_DIAGNOSTIC
  throw std::invalid_argument("unknown diagnostic '" + name + "'");
}

std::string toText(const FieldValue& value) {
  struct Printer {
    std::string operator()(bool v) const { return v ? "true" : "false"; }
    std::string operator()(int v) const { return std::to_string(v); }
    std::string operator()(std::uint64_t v) const { return std::to_string(v); }
    std::string operator()(double v) const { return number(v); }
    std::string operator()(const std::string& v) const { return v; }
    std::string operator()(const cv::Matx33d& m) const {
      std::string text = "[";
      for (int i = 0; i < 9; ++i) text += number(m.val[i]) + (i == 8 ? "]" : i % 3 == 2 ? "; " : ", ");
      return text;
    }
  };
  return std::visit(Printer{}, value);
}

std::string helpText(const FieldInfo& field) {
  std::string detail;
  switch (field.type) {
    case FieldType::kChoice:
      for (const std::string& name : field.choices) detail += (detail.empty() ? "" : ", ") + name;
      return field.doc + " {" + detail + "}";
    case FieldType::kInt:
    case FieldType::kReal:
      if (field.min < field.max) {  // a diagnostic's table gives no range (0..0)
        detail = number(field.min) + ".." + number(field.max);
        if (field.step == 2) detail += " odd";
      }
      break;
    default:
      break;
  }
  if (!field.unit.empty()) detail += (detail.empty() ? "" : " ") + field.unit;
  return field.doc + (detail.empty() ? "" : " [" + detail + "]");
}

}  // namespace movseg
