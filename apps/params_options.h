// The Params fields a user tunes from the command line, shared by segment, demo and bench.
#pragma once

#include <CLI/CLI.hpp>

#include "movseg/params.h"

namespace movseg::cli {

void addParamsOptions(CLI::App* command, Params* params);

}  // namespace movseg::cli
