// movseg eval PRED GT ...  (metrics: src/eval/)
#include "commands.h"

namespace movseg::cli {

void addEvalCommand(CLI::App& app) {
  app.add_subcommand("eval", "Score predicted masks against ground truth");
}

}  // namespace movseg::cli
