// The runner's snapshot hook: top-view PNGs of the particle filter at initialization, while
// the particles cluster, and at convergence, with the S-Graph once it tracks, written into
// OUT/<scenario>/; and the run's error plot next to them.
#pragma once

#include "sim/render/snapshot.hpp"
#include "sim/runner/run_scenario.hpp"

#include <string>

namespace bimloc::cli {

// The scenario's name as a file or folder name: letters, digits and '-', the rest '_'.
std::string fileSafe(const std::string& name);

// The tracker's graph as the picture draws it (`storey`: the tracker's, whose walls its
// indices name).
sim::SnapshotGraph snapshotGraph(const sgraph::SGraphTracker& tracker, const bim::Storey& storey);

// Writes OUT/<scenario>/N_PHASE.png, N counting from 0; `title` over each picture (the
// scenario's name when empty).
sim::SnapshotHook snapshotWriter(const sim::World& world, const sim::Scenario& scenario, const std::string& out_dir,
                                 const std::string& title = {});

// OUT/<scenario>/errors.png: position and yaw error over the run (nothing for a run with no step),
// titled "TITLE: localization error" (TITLE the scenario's name when empty).
void writeErrorPlot(const std::string& out_dir, const std::string& scenario_name, const sim::ScenarioResult& result,
                    const std::string& title = {});

}  // namespace bimloc::cli
