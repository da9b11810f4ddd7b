// The `bimloc` subcommands. Each file registers one subcommand on the application; its
// callback throws std::exception with a one-line message on failure (main prints it).
#pragma once

#include <CLI/CLI.hpp>

namespace bimloc::cli {

// Raised by a subcommand that has already printed its result and only needs an exit code.
struct ExitCode {
  int code;
};

// The exit statuses of the commands that localize: localize, run, sweep, and report merge
// (which gives run's result back). docs/exit_codes.md.
inline constexpr int kExitLocalized = 0;      // every run localized (and passed its expectations)
inline constexpr int kExitNotLocalized = 1;   // it ran, and a run did not localize, or localized falsely
inline constexpr int kExitUnusableInput = 2;  // the input cannot be used: an error names it, nothing is written
// Whether the command ("bimloc localize", "bimloc report merge") exits with these: its errors
// and bad options exit kExitUnusableInput. The other commands exit 1 on any error.
bool usesLocalizeExitCodes(const std::string& command);

// `--storey`: what findStorey takes, on every command that names a storey.
inline constexpr const char* kStoreyHelp =
    "storey name, index or GlobalId (a name several storeys share: the label `bimloc extract` shows, e.g. 'Ground floor [#1]')";

// `--method`, the same on every command that runs the localizer.
inline constexpr const char* kMethodHelp =
    "sgraph (the paper: the filter, then the S-Graph tracks), pf (the filter tracks), pf-no-rooms (the ablation), "
    "amcl (peer: ROS-style AMCL on a 2D slice of the plan) or ndt (peer: HDL-style branch-and-bound, then NDT)";
inline CLI::IsMember methodCheck() { return CLI::IsMember({"sgraph", "pf", "pf-no-rooms", "amcl", "ndt"}); }

// `--motion tour|disambiguate`, the same on run and sweep (docs/disambiguate.md).
inline constexpr const char* kMotionHelp =
    "how the base moves: tour (the scenarios' own motion; generated starts tour their rooms) or disambiguate (while "
    "the localizer searches, it walks where the localizer suggests looking, then tours; docs/disambiguate.md)";
inline CLI::IsMember motionCheck() { return CLI::IsMember({"tour", "disambiguate"}); }
inline constexpr const char* kNoDeskewHelp =
    "give the localizer each lidar turn as cast, skewed by the base's motion over it (default: de-skewed with the "
    "base's noisy odometry, as a robot's driver does; the scenarios' sensor.deskew)";

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
