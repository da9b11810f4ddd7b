// One site deviation (docs/oracle.md, "The robust answer"): a rival is ruled out robustly only
// when its deficit against the truth stays above the threshold after the points of any one plan
// wall (both faces; the site model's unit of a wall built off the plan, left out, or a partition
// standing along it) are dropped from both paths' sums. The points are grouped once per check by
// the wall they lie on along the truth's path, so a rival's robust value is exact at each pose
// and the branch-and-bound's bound still never underestimates it.
#pragma once

#include "sim/oracle/path_score.hpp"
#include "sim/oracle/wall_field.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

namespace bimloc::sim::oracle {

// Which plan wall is nearest to a point (the field's nearest segment, exactly; the first of
// equals), out to clamp from the walls; -1 beyond.
class WallLabels {
 public:
  WallLabels(const DistanceField& field, const std::vector<int>& wall_of);
  int at(float x, float y) const {
    const int s = field_->nearest(x, y);
    return s < 0 ? -1 : wall_of_[static_cast<std::size_t>(s)];
  }
  int walls() const { return walls_; }  // one more than the largest wall index

 private:
  const DistanceField* field_;
  std::vector<int> wall_of_;
  int walls_ = 0;
};

// What the robust score needs of a path: each point's group (the wall it lies on along the
// truth's path, renumbered 0..groups-1; -1: on none) and its score on the truth's path.
struct Discount {
  std::vector<std::int32_t> group;
  std::vector<float> truth;
  int groups = 0;
  mutable std::vector<double> scratch;  // per group, during one call (the oracle runs on one thread)
};

// The discount of `path` started at truth_pose (x, y, yaw).
Discount discountOf(const WallLabels& labels, const DistanceField& field, const PointModel& model, const PathCloud& path,
                    const Eigen::Vector3d& truth_pose);

// A rival's robust value at start (x, y, yaw): max over w in {none} + walls of
//   sum over points off w of the rival's score + sum over points on w of the truth's score,
// so that Q - robustScore is the least deficit left after dropping one wall's points from both
// sums (Q the truth's score). Below `stop_below` it may stop early and return any value below it.
float robustScore(const DistanceField& field, const PointModel& model, const PathCloud& path, const Discount& discount, double x,
                  double y, double yaw, float stop_below = -std::numeric_limits<float>::infinity());

// An upper bound of robustScore over every start in the box (as pathBound's box).
float robustBound(const DistanceField& field, const PointModel& model, const PathCloud& path, const Discount& discount, double cx,
                  double cy, double yaw, double half_x, double half_y, double half_yaw,
                  float stop_below = -std::numeric_limits<float>::infinity());

}  // namespace bimloc::sim::oracle
