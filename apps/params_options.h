// Every movseg::Params field as a command-line option, generated from the field table
// (movseg/params.def through movseg/fields.h): --lk-window 11, --static-camera, ..., and
// --set name=value for the same. Shared by segment, demo and bench, as is their record.
#pragma once

#include <charconv>
#include <cstdint>
#include <set>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "movseg/params.h"

namespace movseg::cli {

// For seeds, 64-bit unsigned: a value outside [0, 2^64 - 1] refused with a short message, as
// --set seed= refuses it (CLI11 clamped a larger one to 2^64 - 1, and its NonNegativeNumber
// would print the largest double as the range's end).
inline const CLI::Validator kSeed(
    [](std::string& input) -> std::string {
      std::uint64_t value = 0;
      const char* begin = input.data() + (input.rfind('+', 0) == 0 ? 1 : 0);  // "+5" is 5
      const char* end = input.data() + input.size();
      const auto [at, error] = std::from_chars(begin, end, value);
      return error == std::errc() && at == end ? "" : "must be an integer in [0, 2^64 - 1]";
    },
    "0..2^64-1");

// Adds an option per field of Params except those named in `except`, and --set, which refuses
// those too. Values are parsed and range-checked by movseg::setParam as they are read, so a bad
// value is refused by name before anything runs.
void addParamsOptions(CLI::App* command, Params* params, const std::set<std::string>& except = {});

// Every field of `params` but those named in `except`, by name, as text (movseg::toText): what
// a run's manifest and bench's JSON record of the settings.
nlohmann::json paramSettings(const Params& params, const std::set<std::string>& except = {});

}  // namespace movseg::cli
