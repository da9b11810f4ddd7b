// `bimloc run --trace DIR`: one CSV per scenario, a row per weighing of the filter (truth,
// estimate, the path evidence's best place and margin), to see why a run converged when it
// did, or never.
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <string>
#include <vector>

namespace bimloc::cli {

// Writes DIR/<scenario>.csv atomically; returns its path. Throws naming the path on failure.
std::string writeTrace(const std::string& dir, const std::string& scenario_name, const std::vector<sim::TraceRow>& rows);

// `bimloc run --tum DIR`: DIR/<scenario>/truth.tum (the true map <- base at every step) and
// estimate.tum (the localizer's, at the steps the ATE scores), atomically, for `bimloc eval`
// or evo; `bimloc eval --align none --project xy` on them gives the run's ATE. Returns the folder.
std::string writeTumPair(const std::string& dir, const std::string& scenario_name, const std::vector<sim::PoseRow>& rows);

}  // namespace bimloc::cli
