#include "params_options.h"

#include <map>
#include <stdexcept>
#include <vector>

#include "movseg/fields.h"

namespace movseg::cli {
namespace {

// The shorter names README and earlier versions use, kept beside the generated ones.
const std::map<std::string, std::string> kAliases{
    {"static_camera", "--static"}, {"motion_model", "--model"}, {"gmm_clusters", "--gmm-k"}};

// --name-with-dashes of a field.
std::string longName(const std::string& field) {
  std::string name = "--" + field;
  for (char& c : name) c = c == '_' ? '-' : c;
  return name;
}

std::string optionName(const std::string& field) {
  const auto alias = kAliases.find(field);
  return alias == kAliases.end() ? longName(field) : longName(field) + "," + alias->second;
}

std::string typeName(const FieldInfo& field) {
  switch (field.type) {
    case FieldType::kBool: return "BOOL";
    case FieldType::kInt: return "INT";
    case FieldType::kUnsigned: return "UINT";
    case FieldType::kReal: return "REAL";
    case FieldType::kChoice: return "NAME";
    case FieldType::kMatrix: break;
  }
  return "VALUE";
}

// Runs movseg::setParam, reporting a bad value the way CLI11 reports its own errors.
void set(Params* params, const std::string& name, const std::string& value) {
  try {
    setParam(params, name, value);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError(e.what());
  }
}

}  // namespace

void addParamsOptions(CLI::App* command, Params* params, const std::set<std::string>& except) {
  const Params defaults;
  for (const FieldInfo& field : paramFields()) {
    if (except.count(field.name) > 0) continue;
    const std::string& name = field.name;
    const auto apply = [params, name](const std::string& value) { set(params, name, value); };
    const FieldValue default_value = paramValue(defaults, name);
    // A flag that is on by default says how to turn it off.
    const bool on = field.type == FieldType::kBool && std::get<bool>(default_value);
    const std::string description = helpText(field) + (on ? " (on; =false turns it off)" : "");
    CLI::Option* option = field.type == FieldType::kBool
                              ? command->add_flag(optionName(name), description)
                              : command->add_option(optionName(name), description);
    option->each(apply)->group("Parameters (include/movseg/params.def)");
    if (field.type != FieldType::kBool) {
      option->type_name(typeName(field))->default_str(toText(default_value));
    }
  }
  command
      ->add_option_function<std::vector<std::string>>(
          "--set",
          [command, params, except](const std::vector<std::string>& items) {
            std::map<std::string, std::string> named;  // the values --set gave, as text
            for (const std::string& item : items) {
              const size_t eq = item.find('=');
              if (eq == std::string::npos) {
                throw CLI::ValidationError("--set: expected name=value, got '" + item + "'");
              }
              const std::string name = item.substr(0, eq);
              // A field left out is the command's own (bench's method: its --methods).
              if (except.count(name) > 0) {
                throw CLI::ValidationError("--set: '" + name +
                                           "' is set by this command's own option, not --set");
              }
              // Given twice with two values, one would win silently: refused, as an option
              // given twice is. (The option's own value is in `params` by now: CLI11 runs the
              // callbacks in the order the options were added, --set last.)
              Params given = *params;
              set(&given, name, item.substr(eq + 1));
              const std::string value = toText(paramValue(given, name));
              const CLI::Option* own = command->get_option_no_throw(longName(name));
              const bool differs = value != toText(paramValue(*params, name));
              if (own != nullptr && own->count() > 0 && differs) {
                throw CLI::ValidationError("--set: '" + name + "' is also given by " +
                                           optionName(name) + ", another value: give it once");
              }
              const auto [earlier, first] = named.emplace(name, value);
              if (!first && earlier->second != value) {
                throw CLI::ValidationError("--set: '" + name +
                                           "' is given twice, two values: give it once");
              }
              *params = given;
            }
          },
          "Set any parameter by its name: --set name=value (repeatable)")
      ->group("Parameters (include/movseg/params.def)");
}

nlohmann::json paramSettings(const Params& params, const std::set<std::string>& except) {
  nlohmann::json settings = nlohmann::json::object();
  for (const FieldInfo& field : paramFields()) {
    if (except.count(field.name) > 0) continue;
    settings[field.name] = toText(paramValue(params, field.name));
  }
  return settings;
}

}  // namespace movseg::cli
