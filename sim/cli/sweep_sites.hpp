// `bimloc sweep --sites A,B,... --methods M,N,...`: the robustness sweep. The same start rooms
// and seeds on each site preset with each method; a row per preset and method (rate, false
// convergences, convergence-time median and 90th percentile, ATE, losses) as a table or JSON,
// and a PNG of rate and ATE against the deviation level.
#pragma once

#include "sim/cli/run_pool.hpp"

#include <string>
#include <vector>

namespace bimloc::cli {

struct RobustnessOptions {
  std::vector<std::string> sites;    // presets, in the order of the plot's x axis
  std::vector<std::string> methods;  // any --method value
  std::string plot;                  // PNG path, empty for none
  std::string title;
  bool json = false;
  int jobs = 1;
  bool oracle = false;  // --oracle: each run's information limit, and its columns per row
};

// Runs every (site, method) over `base` (the start scenarios); prints; writes the plot.
// Returns the number of false convergences.
int runRobustness(const std::vector<sim::Scenario>& base, WorldCache& worlds, const RobustnessOptions& options);

}  // namespace bimloc::cli
