// A simulated walk through the default world (S100, the corridor, R108, R101, R105; real Embree
// scans, legged odometry, seed 1), or through the apartment world, and the loop that feeds its
// turns to a bimloc::Localizer, as the runner does (mid-turn stamps, the odometry sample there).
// Shared by the Localizer's tests and the peers' (test_localizer.cpp, test_ndt.cpp,
// test_first_weighing.cpp, test_places_interval.cpp).
#pragma once

#include "sim/scenario/scenario.hpp"
#include "sim/simulation/simulator.hpp"

#include <bimloc/localizer.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bimloc::test {

struct SimulatedWalk {
  const sim::World* world = nullptr;  // the walk's world (loaded once per test binary)
  sim::Scenario scenario;
  std::unique_ptr<sim::Simulator> sim;
  std::vector<sim::OdometrySample> odometry;
};

// `tag` names the temporary folder of the scenario file.
std::unique_ptr<SimulatedWalk> officeWalk(double duration_s, const std::string& tag);
// The same in worlds/apartment.ifc: from a random pose in `room` (seed 1), a tour of `tour`.
std::unique_ptr<SimulatedWalk> apartmentWalk(const std::string& room, const std::string& tour, double duration_s, const std::string& tag);

struct WalkStep {
  LocalizationResult result;
  Eigen::Isometry3d truth, odom;  // map <- base (truth), odom <- base (the odometry given)
};

// Every turn of the walk through a localizer made with `config` (its storey the walk's world's
// ground floor); `blind(t)`: that turn's points are withheld.
std::vector<WalkStep> walkThrough(const SimulatedWalk& w, LocalizerConfig config, const std::function<bool(double)>& blind = {});

// Planar position error of a step against its truth.
double positionError(const WalkStep& s);

}  // namespace bimloc::test
