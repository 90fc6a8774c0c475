// movseg synth -o DIR ...  (generator: src/synth/)
#include "commands.h"

namespace movseg::cli {

void addSynthCommand(CLI::App& app) {
  app.add_subcommand("synth", "Write a deterministic synthetic sequence with exact ground truth");
}

}  // namespace movseg::cli
