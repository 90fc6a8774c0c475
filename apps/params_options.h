// The Params fields a user tunes from the command line, shared by segment, demo and bench.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "movseg/params.h"

namespace movseg::cli {

void addParamsOptions(CLI::App* command, Params* params);

// Applies "name=value" to the Params field of that name; throws CLI::ValidationError.
void setParam(Params* params, const std::string& assignment);

}  // namespace movseg::cli
