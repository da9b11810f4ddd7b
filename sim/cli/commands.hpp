// The `bimloc` subcommands. Each file registers one subcommand on the application; its
// callback throws std::exception with a one-line message on failure (main prints it).
#pragma once

#include <CLI/CLI.hpp>

namespace bimloc::cli {

// Raised by a subcommand that has already printed its result and only needs an exit code.
struct ExitCode {
  int code;
};

// `--method`, the same on every command that runs the localizer.
inline constexpr const char* kMethodHelp =
    "sgraph (the paper: the filter, then the S-Graph tracks), pf (the filter tracks), pf-no-rooms (the ablation), "
    "amcl (peer: ROS-style AMCL on a 2D slice of the plan) or ndt (peer: HDL-style branch-and-bound, then NDT)";
inline CLI::IsMember methodCheck() { return CLI::IsMember({"sgraph", "pf", "pf-no-rooms", "amcl", "ndt"}); }

// `--site PRESET`: one of sim/world/site_config.hpp's presets; a typo gets the nearest one.
CLI::Validator siteCheck();

}  // namespace bimloc::cli

void addExtractCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);  // bench extract | lidar | simulate | odometry | loop | bags
void addBenchExtractCommand(CLI::App& bench);
void addBenchLidarCommand(CLI::App& bench);
void addBenchSimulateCommand(CLI::App& bench);
void addBenchOdometryCommand(CLI::App& bench);
void addBenchLoopCommand(CLI::App& bench);
void addBenchBagsCommand(CLI::App& bench);
void addWorldgenCommand(CLI::App& app);
void addSimulateCommand(CLI::App& app);
void addRunCommand(CLI::App& app);
void addLocalizeCommand(CLI::App& app);
void addSweepCommand(CLI::App& app);
void addReportCommand(CLI::App& app);  // report merge
void addEvalCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
