// The Params fields a user tunes from the command line, shared by segment, demo and bench.
#pragma once

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

void addParamsOptions(CLI::App* command, Params* params);

// Applies "name=value" to the Params field of that name; throws CLI::ValidationError.
void setParam(Params* params, const std::string& assignment);

}  // namespace movseg::cli
