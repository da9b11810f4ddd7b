// bimloc: one binary, git-style subcommands.
#include "sim/cli/commands.hpp"
#include "sim/common/printable.hpp"
#include "sim/common/interrupt_cleanup.hpp"

#include <bimloc/verbosity.hpp>

#include <iostream>

int main(int argc, char** argv) {
  // Before any thread starts: SIGINT and SIGTERM remove unfinished output, exit 130 / 143.
  bimloc::sim::installInterruptCleanup();
  CLI::App app{"bimloc: robot localization from building plans (BIM/IFC), and the simulator that tests it.\n"
               "Run 'bimloc SUBCOMMAND --help' for the options of each subcommand."};
  app.require_subcommand(1);
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
