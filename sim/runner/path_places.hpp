// The places a run has not told apart: the path evidence's best place and its rivals (the
// filter's UpdateReport), each with its room and relative weight, as a report lists them when
// the localizer did not converge (`bimloc run`, `bimloc localize`).
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <bimloc/bim/building.hpp>
#include <bimloc/pf/particle_filter.hpp>

#include <vector>

namespace bimloc::sim {

// Places of one storey (the path evidence weighs places of other storeys apart: StoreyBank),
// best first; empty when the report has no path_best.
std::vector<ScenarioResult::Place> pathPlaces(const pf::UpdateReport& report, const bim::Storey& storey);

}  // namespace bimloc::sim
