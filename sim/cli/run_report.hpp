// The results of `bimloc run`: one JSON object (the documented schema) and a terminal table.
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <nlohmann/json.hpp>

#include <ostream>
#include <vector>

namespace bimloc::cli {

// The middle value (the mean of the middle two for an even count); NaN for none.
double median(std::vector<double> values);

nlohmann::json runReport(const std::vector<sim::ScenarioResult>& results, double wall_seconds);
void printRunTable(const std::vector<sim::ScenarioResult>& results, const nlohmann::json& report, std::ostream& out);

}  // namespace bimloc::cli
