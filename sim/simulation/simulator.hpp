// One scenario, simulated: the start pose resolved in the world, the base's trajectory
// planned, and from them the lidar turns, the odometry and the ground truth. Turns are
// independent of each other (each draws its noise from the seed and its index), so they can
// be cast in parallel and still give bit-identical output whatever the thread count.
#pragma once

#include "sim/base/base_trajectory.hpp"
#include "sim/lidar/vlp16.hpp"
#include "sim/odometry/odometry_model.hpp"
#include "sim/odometry/odometry_sample.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/world/world.hpp"

#include <functional>
#include <memory>
#include <vector>

namespace bimloc::sim {

class Simulator {
 public:
  // Resolves the storey and the start, and plans the base's motion: ScenarioError on failure.
  // `world` is the plan's; with a scenario's site (Scenario::site, not exact) the simulator
  // builds its own site world from it, and everything it simulates happens there.
  Simulator(const Scenario& scenario, const World& world);

  const Scenario& scenario() const { return scenario_; }
  // The world simulated: the site's (world().siteTruth() says how it differs from the plan).
  const World& world() const { return world_; }
  std::size_t storey() const { return storey_; }  // where the base starts
  // What the lidar sees: the whole building (World::kAllStoreys: every storey's mesh), wherever
  // the base is. A robot on one storey sees more than that storey's elements: a facade that
  // belongs to the storey above but stands over the basement's low walls, the floors above and
  // below through a stair opening. A world of the start's storey alone let the lidar see over
  // such walls into nothing, and the oracle counted what it saw there (Jesse.1's basement).
  std::size_t lidarStorey() const { return World::kAllStoreys; }
  const Pose2& start() const { return start_; }
  const BaseTrajectory& trajectory() const { return trajectory_; }
  const Vlp16& lidar() const { return lidar_; }

  // Turns that fit entirely in the scenario's duration, at the lidar's rate.
  std::size_t turnCount() const;
  double turnStamp(std::size_t turn) const;
  LidarScan turn(std::size_t turn) const;  // thread-safe
  // The same turn, the same noise, cast into the start storey's elements alone: what one
  // storey's plan can explain (a test of the filter's faces), not what a robot sees.
  LidarScan turnOnItsStoreyAlone(std::size_t turn) const;
  // The same turn with the base moving along `T_map_base` instead of the planned trajectory
  // (a base steered while it runs: motion.disambiguate); the same noise as turn().
  LidarScan turnAlong(std::size_t turn, const std::function<Eigen::Isometry3d(double)>& T_map_base) const;
  // The odometry's noise model, seeded as odometry() is, for a base steered while it runs:
  // step it at the odometry's rate with the true poses.
  NoisyOdometry odometryModel(double floor_z) const;

  // All turns, cast on `threads` threads, delivered in order to `sink` (progress optional).
  void castTurns(int threads, const std::function<void(LidarScan&&)>& sink,
                 const std::function<void(std::size_t done, std::size_t total)>& progress = {}) const;

  // Odometry at its rate over the whole duration, and the ground truth at the same instants.
  std::vector<OdometrySample> odometry() const;
  std::vector<GroundTruthSample> groundTruth() const;
  // True map -> odom (where odometry started), for evaluation.
  Eigen::Isometry3d T_map_odom_true() const;

 private:
  // Turn `turn` cast into `storey`'s scene (or World::kAllStoreys) with the base along T_map_base.
  LidarScan cast(std::size_t turn, std::size_t storey, const std::function<Eigen::Isometry3d(double)>& T_map_base) const;

  const Scenario& scenario_;
  std::unique_ptr<const World> site_;  // the site's world, when it differs from the plan
  const World& world_;
  std::size_t storey_ = 0;
  Pose2 start_;
  BaseTrajectory trajectory_;
  Vlp16 lidar_;
};

}  // namespace bimloc::sim
