// The field tables (movseg/params.def, movseg/diagnostics.def) and what is generated from them:
// Params::check(), setParam's parsing, the names and docs every binding shows.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <gtest/gtest.h>

#include "movseg/fields.h"
#include "test_support.h"

namespace movseg {
namespace {

// The message of the std::invalid_argument `action` throws ("" when it throws nothing).
template <typename Action>
std::string rejection(Action&& action) {
  try {
    action();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Assigns a number to a field of any arithmetic or enum type, bypassing every check.
template <typename T>
void assignNumber(T* field, double value) {
  if constexpr (std::is_enum_v<T>) {
    *field = static_cast<T>(static_cast<int>(value));
  } else if constexpr (std::is_arithmetic_v<T>) {
    *field = static_cast<T>(value);
  }
}

Params withNumber(const std::string& name, double value) {
  Params p;
#define MOVSEG_PARAM(type, field, default_value, min, max, step, unit, doc) \
  if (name == #field) assignNumber(&p.field, value);
#include "movseg/params.def"
#undef MOVSEG_PARAM
  return p;
}

// Values just outside each field's range, plus the values no number field accepts.
std::vector<double> outsideRange(const FieldInfo& field) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  switch (field.type) {
    case FieldType::kInt: {
      std::vector<double> values{field.min - 1, field.max + 1, field.max * 1000 + 7};
      if (field.step > 1) values.push_back(field.min + 1);
      return values;
    }
    case FieldType::kReal:
      return {field.min - 0.5, field.max * 2 + 1, nan, inf, -inf};
    case FieldType::kChoice:
      return {static_cast<double>(field.choices.size())};
    default:
      return {};
  }
}

TEST(Fields, DefaultsAreValid) { EXPECT_NO_THROW(Params().check()); }

// Params' equality is generated from params.def: a field it forgot would compare equal.
TEST(Fields, ParamsDifferWhereverOneFieldDoes) {
  const Params defaults;
  EXPECT_TRUE(defaults == Params());
  for (const FieldInfo& field : paramFields()) {
    Params other;
    setParam(&other, field.name, test::otherParamValue(field, defaults));
    EXPECT_TRUE(other != defaults) << field.name;
  }
}

TEST(Fields, CheckRejectsEveryFieldOutsideItsRangeByName) {
  int cases = 0;
  for (const FieldInfo& field : paramFields()) {
    for (double value : outsideRange(field)) {
      const Params p = withNumber(field.name, value);
      const std::string message = rejection([&] { p.check(); });
      EXPECT_NE(message.find(field.name), std::string::npos) << field.name << " = " << value;
      ++cases;
    }
  }
  EXPECT_GT(cases, 60);
}

// Integers, reals (NaN and infinities too: "nan", "inf", "-inf") and choices, each as text.
TEST(Fields, SetParamRejectsWhatCheckRejectsAndNamesTheField) {
  std::set<FieldType> types;
  for (const FieldInfo& field : paramFields()) {
    for (double value : outsideRange(field)) {
      Params p;
      std::ostringstream text;
      if (field.type == FieldType::kReal) {
        text << std::setprecision(17) << value;
      } else {  // an integer, or a choice's index past the last (not a name)
        text << static_cast<long long>(value);
      }
      const std::string message = rejection([&] { setParam(&p, field.name, text.str()); });
      EXPECT_EQ(message.rfind("invalid parameter: " + field.name + " must be", 0), 0u)
          << field.name << " = " << text.str() << ": " << message;
      types.insert(field.type);
    }
  }
  EXPECT_EQ(types, (std::set<FieldType>{FieldType::kInt, FieldType::kReal, FieldType::kChoice}));
  Params p;
  EXPECT_NE(rejection([&] { setParam(&p, "lk_window", "4"); }).find("odd"), std::string::npos);
  EXPECT_NE(rejection([&] { setParam(&p, "lambda", "abc"); }).find("a number"), std::string::npos);
  EXPECT_NE(rejection([&] { setParam(&p, "lambda", "nan"); }), "");
  EXPECT_NE(rejection([&] { setParam(&p, "edge_cell", "2.5"); }).find("integer"), std::string::npos);
  EXPECT_NE(rejection([&] { setParam(&p, "ransac_iterations", "1e8"); }), "");
  EXPECT_EQ(rejection([&] { setParam(&p, "nonsense", "1"); }), "unknown parameter 'nonsense'");
}

TEST(Fields, BooleansAreTrueFalseOneOrZeroInAnyCase) {
  Params p;
  for (const char* yes : {"true", "TRUE", "True", "1"}) {
    p.static_camera = false;
    setParam(&p, "static_camera", yes);
    EXPECT_TRUE(p.static_camera) << yes;
  }
  for (const char* no : {"false", "FALSE", "0"}) {
    p.static_camera = true;
    setParam(&p, "static_camera", no);
    EXPECT_FALSE(p.static_camera) << no;
  }
  for (const char* bad : {"yes", "no", "on", "maybe", "", "2", " true"}) {
    EXPECT_NE(rejection([&] { setParam(&p, "gmm_refine", bad); }).find("true, false, 1 or 0"),
              std::string::npos)
        << bad;
  }
}

TEST(Fields, ChoicesAreNamesAndSeedsAreWholeUnsignedNumbers) {
  Params p;
  setParam(&p, "motion_model", "Homography");
  EXPECT_EQ(p.motion_model, MotionModel::kHomography);
  setParam(&p, "method", "mog2-comp");
  EXPECT_EQ(p.method, Method::kMog2Compensated);
  EXPECT_NE(rejection([&] { setParam(&p, "method", "fast"); }).find("paper, diff"),
            std::string::npos);
  setParam(&p, "seed", "18446744073709551615");
  EXPECT_EQ(p.seed, std::numeric_limits<std::uint64_t>::max());
  for (const char* bad : {"-1", "18446744073709551616", "1.5", "", "0x10"}) {
    EXPECT_NE(rejection([&] { setParam(&p, "seed", bad); }), "") << bad;
  }
}

TEST(Fields, EveryValueRoundTripsThroughText) {
  Params changed;
  changed.motion_model = MotionModel::kHomography;
  changed.seed = 77;
  changed.gmm_refine = false;
  // Every real field at a value that needs all 17 significant digits (six were once printed:
  // 123.456789 came back as 123.457).
  for (const FieldInfo& field : paramFields()) {
    if (field.type != FieldType::kReal) continue;
    const double value = std::nextafter(field.min + (field.max - field.min) / 3, field.max);
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    setParam(&changed, field.name, text);
    ASSERT_EQ(std::get<double>(paramValue(changed, field.name)), value) << field.name;
  }
  Params copy;
  for (const FieldInfo& field : paramFields()) {
    setParam(&copy, field.name, toText(paramValue(changed, field.name)));
    EXPECT_EQ(paramValue(copy, field.name), paramValue(changed, field.name)) << field.name;
  }
}

// Each field says what it is in its own words: a doc copied from a neighbour is a defect.
void expectOwnDocs(const std::vector<FieldInfo>& fields) {
  std::set<std::string> names, docs;
  for (const FieldInfo& field : fields) {
    EXPECT_FALSE(field.doc.empty()) << field.name;
    EXPECT_TRUE(names.insert(field.name).second) << field.name;
    EXPECT_TRUE(docs.insert(field.doc).second) << field.name << ": " << field.doc;
  }
}

TEST(Fields, EveryFieldHasItsOwnNameAndDoc) {
  expectOwnDocs(paramFields());
  expectOwnDocs(diagnosticFields());
  EXPECT_GT(paramFields().size(), 25u);
  EXPECT_GT(diagnosticFields().size(), 20u);
}

TEST(Fields, ChoiceRangesMatchTheirNames) {
  for (const FieldInfo& field : paramFields()) {
    if (field.type != FieldType::kChoice) continue;
    EXPECT_EQ(field.min, 0) << field.name;
    EXPECT_EQ(field.max + 1, static_cast<double>(field.choices.size())) << field.name;
  }
}

TEST(Fields, DiagnosticsAreReadByName) {
  Diagnostics d;
  d.matches = 12;
  d.total_ms = 3.5;
  d.model = cv::Matx33d(1, 0, 2, 0, 1, 3, 0, 0, 1);
  EXPECT_EQ(std::get<int>(diagnosticValue(d, "matches")), 12);
  EXPECT_EQ(std::get<double>(diagnosticValue(d, "total_ms")), 3.5);
  EXPECT_EQ(std::get<cv::Matx33d>(diagnosticValue(d, "model")), d.model);
  EXPECT_EQ(toText(diagnosticValue(d, "model")), "[1, 0, 2; 0, 1, 3; 0, 0, 1]");
  EXPECT_THROW(diagnosticValue(d, "nonsense"), std::invalid_argument);
}

// A diagnostic has no range (its table gives 0..0): only its unit is shown.
TEST(Fields, HelpTextShowsTheRange) {
  EXPECT_EQ(helpText(paramField("lk_window")), "Lucas-Kanade window side (odd) [3..101 odd px]");
  EXPECT_NE(helpText(paramField("motion_model")).find("{affine, homography}"), std::string::npos);
  const auto& diagnostics = diagnosticFields();
  const auto total = std::find_if(diagnostics.begin(), diagnostics.end(),
                                  [](const FieldInfo& f) { return f.name == "total_ms"; });
  ASSERT_NE(total, diagnostics.end());
  EXPECT_EQ(helpText(*total), total->doc + " [ms]");
}

}  // namespace
}  // namespace movseg
