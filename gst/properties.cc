#include "properties.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <variant>
#include <vector>

#include "movseg/fields.h"

namespace movseg::gst {
namespace {

// "motion_model" -> "motion-model": GObject's canonical property names.
std::string propertyName(const std::string& field) {
  std::string name = field;
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

// A GEnum type per choice field ("GstMovsegMotionModel"), its values named by enumNames<>().
GType choiceType(const FieldInfo& field) {
  std::string type_name = "GstMovseg";
  bool upper = true;
  for (char c : field.name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    type_name += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  // GLib keeps the table for the type's lifetime, the process's; the names live as long as
  // paramFields().
  auto* values = new GEnumValue[field.choices.size() + 1]();
  for (std::size_t i = 0; i < field.choices.size(); ++i) {
    values[i] = {static_cast<gint>(i), field.choices[i].c_str(), field.choices[i].c_str()};
  }
  return g_enum_register_static(g_intern_string(type_name.c_str()), values);
}

GParamSpec* paramSpec(const FieldInfo& field, const FieldValue& default_value) {
  const std::string name = propertyName(field.name);
  const std::string blurb = helpText(field);
  const auto flags = static_cast<GParamFlags>(G_PARAM_READWRITE | GST_PARAM_MUTABLE_PLAYING);
  switch (field.type) {
    case FieldType::kBool:
      return g_param_spec_boolean(name.c_str(), field.name.c_str(), blurb.c_str(),
                                  std::get<bool>(default_value), flags);
    case FieldType::kInt:
      return g_param_spec_int(name.c_str(), field.name.c_str(), blurb.c_str(),
                              static_cast<gint>(field.min), static_cast<gint>(field.max),
                              std::get<int>(default_value), flags);
    case FieldType::kUnsigned:
      return g_param_spec_uint64(name.c_str(), field.name.c_str(), blurb.c_str(), 0,
                                 std::numeric_limits<guint64>::max(),
                                 std::get<std::uint64_t>(default_value), flags);
    case FieldType::kReal:
      return g_param_spec_double(name.c_str(), field.name.c_str(), blurb.c_str(), field.min,
                                 field.max, std::get<double>(default_value), flags);
    case FieldType::kChoice: {
      const auto& choices = field.choices;
      const auto chosen =
          std::find(choices.begin(), choices.end(), std::get<std::string>(default_value));
      return g_param_spec_enum(name.c_str(), field.name.c_str(), blurb.c_str(), choiceType(field),
                               static_cast<gint>(chosen - choices.begin()), flags);
    }
    case FieldType::kMatrix:
      break;
  }
  g_error("movseg: parameter %s has a type no property describes", field.name.c_str());
}

// The property value as the text movseg::setParam parses.
std::string valueText(const FieldInfo& field, const GValue* value) {
  switch (field.type) {
    case FieldType::kBool: return g_value_get_boolean(value) ? "true" : "false";
    case FieldType::kInt: return std::to_string(g_value_get_int(value));
    case FieldType::kUnsigned: return std::to_string(g_value_get_uint64(value));
    case FieldType::kChoice:
      return field.choices.at(static_cast<std::size_t>(g_value_get_enum(value)));
    case FieldType::kReal: {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", g_value_get_double(value));  // exact round trip
      return text;
    }
    case FieldType::kMatrix: break;
  }
  return "";
}

// Fills a GValue initialised to the property's type.
struct PropertyValue {
  const FieldInfo& field;
  GValue* value;
  void operator()(bool v) const { g_value_set_boolean(value, v); }
  void operator()(int v) const { g_value_set_int(value, v); }
  void operator()(std::uint64_t v) const { g_value_set_uint64(value, v); }
  void operator()(double v) const { g_value_set_double(value, v); }
  void operator()(const std::string& choice) const {
    const auto& choices = field.choices;
    g_value_set_enum(value, static_cast<gint>(std::find(choices.begin(), choices.end(), choice) -
                                              choices.begin()));
  }
  void operator()(const cv::Matx33d&) const {}
};

// Adds a diagnostic to a message structure under its name.
struct DiagnosticField {
  GstStructure* structure;
  const char* name;
  void operator()(bool v) const { gst_structure_set(structure, name, G_TYPE_BOOLEAN, v, nullptr); }
  void operator()(int v) const { gst_structure_set(structure, name, G_TYPE_INT, v, nullptr); }
  void operator()(std::uint64_t v) const {
    gst_structure_set(structure, name, G_TYPE_UINT64, static_cast<guint64>(v), nullptr);
  }
  void operator()(double v) const { gst_structure_set(structure, name, G_TYPE_DOUBLE, v, nullptr); }
  void operator()(const std::string& v) const {
    gst_structure_set(structure, name, G_TYPE_STRING, v.c_str(), nullptr);
  }
  void operator()(const cv::Matx33d& m) const {
    GValue array = G_VALUE_INIT;
    gst_value_array_init(&array, 9);
    for (double entry : m.val) {
      GValue number = G_VALUE_INIT;
      g_value_init(&number, G_TYPE_DOUBLE);
      g_value_set_double(&number, entry);
      gst_value_array_append_and_take_value(&array, &number);
    }
    gst_structure_take_value(structure, name, &array);
  }
};

}  // namespace

void installParamProperties(GObjectClass* klass, guint first_id) {
  const Params defaults;
  const std::vector<FieldInfo>& fields = paramFields();
  for (std::size_t i = 0; i < fields.size(); ++i) {
    g_object_class_install_property(
        klass, first_id + static_cast<guint>(i),
        paramSpec(fields[i], paramValue(defaults, fields[i].name)));
  }
}

void setParamProperty(Params* params, std::size_t field, const GValue* value) {
  const FieldInfo& info = paramFields().at(field);
  setParam(params, info.name, valueText(info, value));
}

void getParamProperty(const Params& params, std::size_t field, GValue* value) {
  const FieldInfo& info = paramFields().at(field);
  std::visit(PropertyValue{info, value}, paramValue(params, info.name));
}

GstStructure* diagnosticsStructure(const Diagnostics& diagnostics, guint64 frame,
                                   GstClockTime timestamp) {
  GstStructure* structure = gst_structure_new("movseg", "frame", G_TYPE_UINT64, frame, nullptr);
  if (GST_CLOCK_TIME_IS_VALID(timestamp)) {
    gst_structure_set(structure, "timestamp", G_TYPE_UINT64, timestamp, nullptr);
  }
  for (const FieldInfo& field : diagnosticFields()) {
    std::visit(DiagnosticField{structure, field.name.c_str()},
               diagnosticValue(diagnostics, field.name));
  }
  return structure;
}

std::vector<cv::Rect2d> parseIgnoredRectangles(const std::string& text) {
  std::vector<cv::Rect2d> rectangles;
  std::istringstream list(text);
  std::string item;
  while (std::getline(list, item, ';')) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    std::istringstream numbers(item);
    double v[4];
    char comma[3];
    const bool read = static_cast<bool>(numbers >> v[0] >> comma[0] >> v[1] >> comma[1] >> v[2] >>
                                        comma[2] >> v[3]) &&
                      (numbers >> std::ws).eof() && comma[0] == ',' && comma[1] == ',' &&
                      comma[2] == ',';
    // Within the frame, with a tolerance for fractions written to a few decimals.
    constexpr double kSlack = 1e-6;
    const bool inside = read && v[0] >= 0 && v[1] >= 0 && v[2] > 0 && v[3] > 0 &&
                        v[0] + v[2] <= 1 + kSlack && v[1] + v[3] <= 1 + kSlack;
    if (!inside) {
      throw std::invalid_argument(
          "ignore: \"" + item +
          "\" is not x,y,w,h in fractions of the frame (w, h > 0, within it), as in "
          "\"0,0.8,1,0.2; 0.85,0,0.15,0.06\"");
    }
    rectangles.emplace_back(v[0], v[1], v[2], v[3]);
  }
  return rectangles;
}

cv::Mat ignoredRegion(const std::vector<cv::Rect2d>& rectangles, cv::Size size) {
  if (rectangles.empty()) return cv::Mat();
  cv::Mat region(size, CV_8U, cv::Scalar(0));
  const auto at = [](double fraction, int side) {
    return std::clamp(static_cast<int>(std::lround(fraction * side)), 0, side);
  };
  for (const cv::Rect2d& r : rectangles) {
    const cv::Point first(at(r.x, size.width), at(r.y, size.height));
    const cv::Point last(at(r.x + r.width, size.width), at(r.y + r.height, size.height));
    region(cv::Rect(first, last)).setTo(255);
  }
  return region;
}

}  // namespace movseg::gst
