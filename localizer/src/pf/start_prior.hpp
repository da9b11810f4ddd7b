// What a user knows of where the robot started ("we start in flat B", "near the entrance,
// facing north"): places the start cannot have been are not places the robot can be. The
// filter spreads its particles only there, and neither its pose hypotheses nor the path
// evidence's candidates may imply a start elsewhere. A plan that cannot decide between two
// places (the point-symmetric Duplex) then decides within the prior.
#pragma once

#include "room_index.hpp"

#include <bimloc/pf/particle_filter.hpp>

#include <Eigen/Core>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace bimloc::pf::detail {

class StartPrior {
 public:
  StartPrior() = default;
  // Throws std::invalid_argument naming an unknown room (and listing the storey's rooms).
  StartPrior(const bim::Storey& storey, const RoomIndex& rooms, const ParticleFilterConfig& config);

  bool active() const { return !rooms_.empty() || pose_.has_value(); }
  // Whether the robot may have started at `start` (map x, y, yaw). Always true when inactive.
  bool admits(const Eigen::Vector3d& start) const;
  // A particle drawn from the prior (a room of the prior by area, or around the prior pose).
  Particle draw(std::mt19937_64& rng) const;

 private:
  const RoomIndex* index_ = nullptr;
  std::vector<int> rooms_;
  std::vector<double> areas_;  // of rooms_: a room of the prior is drawn by its area
  std::optional<Eigen::Vector3d> pose_;
  double sigma_m_ = 1.0, sigma_yaw_rad_ = M_PI;
};

}  // namespace bimloc::pf::detail
