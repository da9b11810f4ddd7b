// Storeys built in code for the oracle's tests (tests/test_oracle.cpp, tests/test_oracle_robust.cpp):
// walls from segments, scans cast in 2D against their faces by a ray caster written here (not the
// oracle's distance field), walks at 0.5 m/s, and the oracle run on a walk with exact odometry in
// a frame of its own.
#pragma once

#include "sim/oracle/oracle.hpp"

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <optional>
#include <random>
#include <vector>

namespace bimloc::test {

constexpr double kOracleBaseZ = 0.5;  // base frame above the floor; walls from 0 to 2.8 m

// A wall whose room-side face runs along a -> b at the given side (thickness 0.2 m, the axis
// 0.1 m behind the face), grown 0.2 m at both ends so that corners close.
void addWall(bim::Storey& s, Eigen::Vector2d a, Eigen::Vector2d b, const Eigen::Vector2d& offset = Eigen::Vector2d::Zero());

// The nearest face hit along the ray from p at heading a, within max_range.
std::optional<Eigen::Vector2d> castRay(const bim::Storey& s, const Eigen::Vector2d& p, double a, double max_range);

struct Walk {
  std::vector<double> times;
  std::vector<Eigen::Vector3d> poses;  // map x, y, yaw
};

// Waypoints at 0.5 m/s, heading along each leg, a pose every 0.1 s (a 10 Hz lidar).
Walk walk(const std::vector<Eigen::Vector2d>& waypoints);

// One turn from `pose`: a ray a degree, range noise 1 cm, each return at the band's height and
// again above it (the ceiling's rows, which the oracle must drop). Lidar frame = base frame.
std::vector<Eigen::Vector3f> scanFrom(const bim::Storey& s, const Eigen::Vector3d& pose, double max_range, std::mt19937& rng);

// The keyframes the oracle keeps of the walk (as runOracle records them).
std::vector<sim::oracle::Keyframe> oracleKeyframes(const bim::Storey& s, const Walk& w, double max_range,
                                                    const sim::oracle::OracleConfig& config, const bim::Storey* site = nullptr);

// The oracle's verdict on the walk: odometry exact, in an odom frame turned and moved from the map's.
// The scans are cast in `site` when given (a site that differs from its plan), else in the plan s.
sim::oracle::OracleVerdict runOracle(const bim::Storey& s, const Walk& w, double max_range, const sim::oracle::OracleConfig& config,
                                     const bim::Storey* site = nullptr);

// The default config with a metre round the building (the test buildings stand alone: enough
// room for rivals).
sim::oracle::OracleConfig smallMargin();

// The first time a ray of the walk's scans ends where `seen` says (a door's view, a wall's).
template <typename Seen>
std::optional<double> firstSeen(const bim::Storey& s, const Walk& w, double max_range, Seen seen) {
  for (std::size_t k = 0; k < w.poses.size(); ++k)
    for (int a = 0; a < 360; ++a) {
      const auto hit = castRay(s, w.poses[k].head<2>(), w.poses[k].z() + a * M_PI / 180.0, max_range);
      if (hit && seen(*hit)) return w.times[k];
    }
  return std::nullopt;
}

}  // namespace bimloc::test
