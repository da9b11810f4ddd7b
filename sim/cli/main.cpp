// bimloc: one binary, git-style subcommands.
#include "sim/cli/commands.hpp"
#include "sim/cli/help_format.hpp"
#include "sim/common/printable.hpp"
#include "sim/common/interrupt_cleanup.hpp"

#include <bimloc/verbosity.hpp>

#include <iostream>
#include <map>
#include <memory>
#include <string>

int main(int argc, char** argv) {
  // Before any thread starts: SIGINT and SIGTERM remove unfinished output, exit 130 / 143.
  bimloc::sim::installInterruptCleanup();
  CLI::App app{"bimloc: robot localization from building plans (BIM/IFC), and the simulator that tests it.\n"
               "Run 'bimloc SUBCOMMAND --help' for the options of each subcommand."};
  app.require_subcommand(1);
  app.formatter(std::make_shared<bimloc::cli::HelpFormatter>());  // before the subcommands: they take it
  // Anywhere on the line (`bimloc --verbose localize ...` or `bimloc localize ... --verbose`: the
  // subcommands pass options they do not know to here): the libraries' own messages (PCL) are
  // shown; without it they stay off the results.
  app.add_flag_callback("--verbose", [] { bimloc::setVerbose(true); }, "show the libraries' own messages (PCL)");
  app.fallthrough();
  addExtractCommand(app);
  addWorldgenCommand(app);
  addSimulateCommand(app);
  addRunCommand(app);
  addLocalizeCommand(app);
  addSweepCommand(app);
  addReportCommand(app);
  addEvalCommand(app);
  addCompareCommand(app);
  addBenchCommand(app);
  // The top level's own: a line per subcommand, names in a narrow column (each --help says the
  // rest); set after the subcommands, which keep the one above.
  auto top = std::make_shared<bimloc::cli::HelpFormatter>(std::map<std::string, std::string>{
      {"extract", "an IFC plan's storeys, rooms and walls as planes: building.json, walls.csv, meshes"},
      {"worldgen", "generate synthetic buildings as IFC4 plans (offices, homes, schools, halls, flats)"},
      {"simulate", "walk a scenario and write its dataset: ROS 1 or ROS 2 bag, PCD clouds, TUM files"},
      {"run", "run scenarios in the loop (simulator -> localizer), scored against the truth"},
      {"localize", "localize a recording (ROS 1 / ROS 2 bag, PCD folder) in a plan: map <- odom"},
      {"sweep", "global localization from every start room of plans: rate, time, false fixes"},
      {"report", "merge the shards of a sweep run in parts (`run --shard`, Slurm)"},
      {"eval", "APE and RPE of a TUM trajectory against the truth, as evo does"},
      {"compare", "the paper's method against its ablation, AMCL and NDT on the same runs; a page"},
      {"bench", "benchmarks, each against a reference measured in the same run"}});
  top->column_width(14);
  app.formatter(top);
  // "bimloc localize": the subcommand parsed so far (for messages and exit statuses).
  const auto command = [&app] {
    std::string name = "bimloc";
    for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
      sub = sub->get_subcommands().front();
      name += " " + sub->get_name();
    }
    return name;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints the message (or the help)
    return code != 0 && bimloc::cli::usesLocalizeExitCodes(command()) ? bimloc::cli::kExitUnusableInput : code;
  } catch (const bimloc::cli::ExitCode& e) {
    return e.code;
  } catch (const std::exception& e) {
    std::cerr << command() << ": error: " << bimloc::sim::printable(e.what()) << "\n";
    return bimloc::cli::usesLocalizeExitCodes(command()) ? bimloc::cli::kExitUnusableInput : 1;
  }
  return 0;
}

bool bimloc::cli::usesLocalizeExitCodes(const std::string& command) {
  for (const char* c : {"bimloc localize", "bimloc run", "bimloc sweep", "bimloc report merge"})
    if (command == c) return true;
  return false;
}
