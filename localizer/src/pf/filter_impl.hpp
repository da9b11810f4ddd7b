// The particle filter's state and the steps of its update (particle_filter.cpp runs them in
// the paper's order; filter_steps.cpp holds them). Private to the library.
#pragma once

#include <bimloc/pf/particle_filter.hpp>

#include "hypotheses.hpp"
#include "measurement.hpp"
#include "particle_set.hpp"
#include "path_evidence.hpp"
#include "room_index.hpp"
#include "start_prior.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <atomic>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace bimloc::pf {
namespace detail {

// The rotation without its yaw: roll and pitch.
using bimloc::tiltOf;  // geometry/planar_pose.hpp

}  // namespace detail

struct ParticleFilter::Impl {
  const bim::Storey& storey;
  Eigen::Isometry3d T_base_lidar;
  ParticleFilterConfig config;
  detail::RoomIndex rooms;
  detail::StartPrior prior;
  detail::PathEvidence evidence;
  detail::PoseRefinementConfig refinement;
  std::optional<detail::Pose2> odom_start;  // the first odometry pose: where the prior applies
  std::mt19937_64 rng;
  std::vector<Particle> particles;
  std::optional<Eigen::Isometry3d> last_odom;
  Eigen::Isometry3d odom = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Isometry3d> T_map_odom;
  int agreeing_updates = 0;
  std::size_t best = 0;
  std::optional<Eigen::Isometry3d> odom_at_last_weighing;
  int scans_since_weighing = 0;
  double anneal = 1.0;
  bool weighed_once = false;
  int next_seed_room = 0;  // where the seeds' next share of the rooms starts (seed_poses_per_weighing)
  std::vector<std::string> pending_warnings;  // from predict(), reported by the next update()
  const RangeProfile* profile = nullptr;      // of the scan being weighed (update's argument)
  // particles' version (ParticleFilter::particlesVersion), and their weighted mean under it:
  // T_map_base() is asked at every step, the particles change only when weighed.
  std::uint64_t particles_version = nextParticlesVersion();
  mutable std::optional<std::pair<std::uint64_t, Eigen::Vector3d>> mean_at_version;
  static std::uint64_t nextParticlesVersion();
  Eigen::Vector3d currentMean() const {
    if (!mean_at_version || mean_at_version->first != particles_version) mean_at_version.emplace(particles_version, mean(normalisedWeights()));
    return mean_at_version->second;
  }

  // AMCL-style gate: weigh after enough motion, or after enough scans standing still.
  bool shouldWeigh() const {
    if (!odom_at_last_weighing || scans_since_weighing + 1 >= config.max_static_scans) return true;
    const Eigen::Isometry3d moved = odom_at_last_weighing->inverse() * odom;
    return moved.translation().head<2>().norm() >= config.update_min_translation_m ||
           std::abs(yawOf(moved.linear())) >= config.update_min_rotation_deg * M_PI / 180.0;
  }

  Impl(const bim::Storey& s, const Eigen::Isometry3d& mount, const ParticleFilterConfig& c)
      : storey(s), T_base_lidar(mount), config(c), rooms(s, c.use_rooms, c.neighbour_rooms), prior(s, rooms, c),
        evidence(s, c), rng(c.seed), anneal(c.anneal_start) {
    const auto count = static_cast<std::size_t>(std::max(1, c.particles));
    if (prior.active()) {
      for (std::size_t i = 0; i < count; ++i) particles.push_back(prior.draw(rng));
    } else {
      particles = detail::spreadOverRooms(rooms, count, rng);
    }
  }

  // The start pose a pose now implies, through the odometry since the start.
  detail::Pose2 startOf(const detail::Pose2& now) const {
    if (!odom_start) return now;
    return detail::compose(now, detail::compose(detail::inverse(planarPose(odom)), *odom_start));
  }
  bool admitted(const detail::Pose2& now) const { return !prior.active() || prior.admits(startOf(now)); }

  int inject(const std::vector<detail::Hypothesis>& hyps, std::size_t count, double bonus = 0.0) {
    return detail::inject(particles, hyps, count, bonus, rooms, rng);
  }
  std::size_t heaviest() const { return detail::heaviest(particles); }
  std::vector<double> normalisedWeights() const { return detail::normalisedWeights(particles); }
  Eigen::Vector3d mean(const std::vector<double>& w) const { return detail::weightedMean(particles, w); }
  void resample(const std::vector<double>& w, std::size_t count) {
    best = detail::resample(particles, w, count, best, config.roughening_xy_m, config.roughening_yaw_deg * M_PI / 180.0, rooms, rng);
  }

  double baseZ() const { return storey.elevation_m + odom.translation().z(); }
  void applyMotion();

  std::vector<detail::Observation> observe(const std::vector<planes::ObservedPlane>& walls,
                                           std::vector<std::string>* warnings) const;

  // The steps of update(), in its order (filter_steps.cpp).
  std::vector<detail::Hypothesis> seedHypotheses(const std::vector<detail::Observation>& observations, double z,
                                                 UpdateReport& report);
  double weigh(const std::vector<detail::Observation>& observations, double z, bool& annealing);
  detail::PathVerdict askThePath(const std::vector<detail::Observation>& observations,
                                 const std::vector<detail::Hypothesis>& hyps, double z, UpdateReport& report);
  // The verdict's settling of its lowest rival, counted in the report (path_bound_held).
  void countSettled(const detail::PathVerdict& path, UpdateReport& report) const;
  void resetFromTheScan(const std::vector<detail::Hypothesis>& hyps, double best_raw, bool annealing,
                        const detail::PathVerdict& path, bool decisive, UpdateReport& report);
  void followThePath(const detail::PathVerdict& path, UpdateReport& report);
  // Returns whether it changed the particles' weights (a convergence the cloud had not gathered
  // at yet: the places the path evidence refuted are dropped).
  bool checkConvergence(const std::vector<detail::Observation>& observations, double z, detail::PathVerdict& path,
                        bool decisive, const std::vector<double>& w, const Eigen::Vector3d& mean, UpdateReport& report);
  // The best particle's pose refined within its place, or nothing while that pose is not
  // settled (config.settle_pose).
  std::optional<detail::Pose2> settledPose(const Particle& top, UpdateReport& report) const;
  void resampleAfter(const std::vector<double>& w, UpdateReport& report);
  // The report's places (path_best, then path_rivals) each fitted within itself on the latest
  // scans (FilterAccess::fitPlaces).
  void fitPlaces(UpdateReport& report) const;
  double yawTolerance() const { return config.converged_yaw_deg * M_PI / 180.0; }
  // Whether a pose is at the path evidence's best place (twice the convergence radius: the
  // window's fitted pose carries the drift of its half-window).
  bool atPathBest(const detail::Pose2& pose, const detail::PathVerdict& path) const {
    return detail::near(pose, path.best, 2.0 * config.converged_position_m, 2.0 * yawTolerance());
  }

  Eigen::Isometry3d poseOf(const Particle& p) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * detail::tiltOf(odom.linear());
    T.translation() = Eigen::Vector3d(p.x, p.y, baseZ());
    return T;
  }

};

}  // namespace bimloc::pf
