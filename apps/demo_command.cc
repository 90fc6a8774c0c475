// movseg demo: what `make run` runs.
#include "commands.h"

namespace movseg::cli {

void addDemoCommand(CLI::App& app) {
  app.add_subcommand("demo", "Generate a synthetic moving-camera clip, segment it, print the result");
}

}  // namespace movseg::cli
