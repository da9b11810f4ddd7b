// The figures of a group of runs, as `bimloc sweep` prints them: rate, false convergences,
// convergence-time quantiles, ATE, losses (one row of a sweep's table or JSON).
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace bimloc::cli {

// Linear interpolation between order statistics (R's type 7); NaN for no values.
double quantile(std::vector<double> v, double q);

nlohmann::json summariseRuns(const std::vector<const sim::ScenarioResult*>& runs);

// Of a summary's runs, those that ran: a start that could not be run (no spot outside the
// rooms where the body fits, a plan that fails to load) counts in "errors", and is no run.
inline int runsThatRan(const nlohmann::json& summary) { return summary["runs"].get<int>() - summary["errors"].get<int>(); }

// A JSON number or "-" for null, with `decimals`.
std::string cell(const nlohmann::json& v, int decimals);

}  // namespace bimloc::cli
