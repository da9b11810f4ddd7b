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

}  // namespace bimloc::cli
