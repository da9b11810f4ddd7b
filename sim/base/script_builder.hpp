// The motion script as it is planned: corners and timing grow together, each flat segment
// checked by a sweep of the body as it is added, on the storey the base is on; a walk up or
// down the stairs moves it to another storey (issue 31), with that storey's free space.
#pragma once

#include "sim/base/base_trajectory.hpp"
#include "sim/base/free_space.hpp"
#include "sim/base/motion_profile.hpp"
#include "sim/base/stair_links.hpp"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

// A plan point as text for errors: "(x, y)" in metres (script_builder.cpp, base_trajectory.cpp).
std::string pointText(const Eigen::Vector2d& p);

class ScriptBuilder {
 public:
  // Starts at `start` on `storey`, whose floor under the start is at floor_z.
  ScriptBuilder(const World& world, std::size_t storey, double floor_z, const Pose2& start, const MotionConfig& motion,
                const MotionLimits& limits);

  const World& world() const { return world_; }
  std::size_t storey() const { return storey_; }
  const bim::Storey& storeyPlan() const;
  FreeSpace& space();  // the current storey's
  Timeline& timeline() { return timeline_; }
  std::vector<Pose2>& corners() { return corners_; }
  const std::vector<StairLink>& links() const { return links_; }
  // The storeys the base stood on, in the order it first reached them.
  const std::vector<std::size_t>& storeysVisited() const { return visited_storeys_; }

  // Straight segments through `points` on this storey, each checked by a sweep of the body;
  // MotionError naming the segment on contact.
  void addLeg(const std::vector<Eigen::Vector2d>& points, std::optional<double> final_yaw = std::nullopt);
  // From here over the stairs to `storey` (fewest flights): to the foot (or head) of each
  // flight on the storey's free space, up or down it, and a step off onto the landing beyond.
  // MotionError when the stairs do not connect the storeys or the flight cannot be reached.
  void goToStorey(std::size_t storey);

 private:
  void walkLink(const StairLink& link);
  void enterStorey(std::size_t storey, double floor_z);

  const World& world_;
  const MotionConfig& motion_;
  std::vector<StairLink> links_;
  std::size_t storey_;
  double floor_ref_;  // the floor the current storey's free space and floor sampler start from
  std::map<std::size_t, std::unique_ptr<FreeSpace>> spaces_;
  Timeline timeline_;
  std::vector<Pose2> corners_;
  std::vector<std::size_t> visited_storeys_;
  int segments_ = 0;
};

}  // namespace bimloc::sim
