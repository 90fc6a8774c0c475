// The subcommands of build/movseg. Each add*Command registers its options and its callback;
// a callback reports failure by throwing std::exception with a one-line message.
#pragma once

#include <CLI/CLI.hpp>

namespace movseg::cli {

void addSegmentCommand(CLI::App& app);
void addSynthCommand(CLI::App& app);
void addDemoCommand(CLI::App& app);
void addEvalCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);

}  // namespace movseg::cli
