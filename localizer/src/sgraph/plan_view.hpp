// What the plan says a lidar at a keyframe's position sees: which plan faces stand between it
// and a point, and which plan faces are in clear view. The loss monitor (loss_monitor.cpp)
// asks it what contradicts the plan: a plane seen behind a solid plan face, a plan face in
// clear view that no plane matched. Plan-view only: the plan holds the walls, the site also
// its clutter (furniture, stacked material, columns, people), which can hide a wall but never
// show a plane behind one.
#pragma once

#include "graph.hpp"

#include <Eigen/Core>
#include <vector>

namespace bimloc::sgraph::detail {

struct PlanFaceRef {
  int node = -1;
  int face = 0;
};

class PlanView {
 public:
  // The active plan faces within range_m of `from` (the keyframe's position in the map).
  PlanView(const Graph& g, const Eigen::Vector2d& from, double range_m);

  // A plan face (not at an opening, not within end_margin of its ends) lies between `from` and
  // `to`, `to` more than behind_m behind it.
  bool blocked(const Eigen::Vector2d& to, double behind_m, int skip_node = -1) const;

  // Something the scan saw, as a segment on the floor plane: it hides what lies behind it.
  struct Occluder {
    Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  };

  // The plan faces that look at `from` and of which at least min_length_m is in clear view:
  // no other plan face between, none of `occluders` (the scan's own planes: a wall hidden
  // behind a cupboard is not missing), not seen at a grazing angle, not an opening, in range.
  std::vector<PlanFaceRef> facesInClearView(double min_length_m, const std::vector<Occluder>& occluders) const;

 private:
  const Graph& g_;
  Eigen::Vector2d from_;
  double range_m_;
  std::vector<PlanFaceRef> near_;  // the active plan faces within range
};

}  // namespace bimloc::sgraph::detail
