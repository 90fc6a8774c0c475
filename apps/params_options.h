// Every movseg::Params field as a command-line option, generated from the field table
// (movseg/params.def through movseg/fields.h): --lk-window 11, --static-camera, ..., and
// --set name=value for the same. Shared by segment, demo and bench.
#pragma once

#include <set>
#include <string>

#include <CLI/CLI.hpp>

#include "movseg/params.h"

namespace movseg::cli {

// For counts and seeds: rejects a leading minus sign with a short message (CLI11's
// NonNegativeNumber would print the largest double as the range's end).
inline const CLI::Validator kNotNegative(
    [](std::string& input) -> std::string {
      return !input.empty() && input[0] == '-' ? "must not be negative" : "";
    },
    "NOT NEGATIVE");

// Adds an option per field of Params except those named in `except`, and --set. Values are
// parsed and range-checked by movseg::setParam as they are read, so a bad value is refused by
// name before anything runs.
void addParamsOptions(CLI::App* command, Params* params, const std::set<std::string>& except = {});

}  // namespace movseg::cli
