// The runner's snapshot hook: top-view PNGs of the particle filter at initialization, while
// the particles cluster, and at convergence, written into OUT/<scenario>/.
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <string>

namespace bimloc::cli {

// The scenario's name as a file or folder name: letters, digits and '-', the rest '_'.
std::string fileSafe(const std::string& name);

sim::SnapshotHook snapshotWriter(const sim::World& world, const sim::Scenario& scenario, const std::string& out_dir);

}  // namespace bimloc::cli
