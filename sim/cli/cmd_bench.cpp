// bimloc bench: benchmarks that print figures, each against a reference measured in the same run.
#include "sim/cli/commands.hpp"

void addBenchCommand(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks, each against a reference measured in the same run (ratios, not timed tests).");
  bench->require_subcommand(1);
  addBenchExtractCommand(*bench);
  addBenchLidarCommand(*bench);
  addBenchSimulateCommand(*bench);
  addBenchOdometryCommand(*bench);
  addBenchLoopCommand(*bench);
  addBenchBagsCommand(*bench);
}
