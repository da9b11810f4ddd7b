// AMCL as a peer of the paper's method: the ROS amcl node's loop (amcl_node.cpp laserReceived)
// on the storey's slice: the update gates, the odometry model, the likelihood field, KLD
// resampling every resample_interval updates, and the pose of the heaviest cluster. What ROS
// does not have: the map comes from the plan, the scan from a 3D lidar, and convergence is
// declared from the particles' covariance (AmclConfig). Private to the library.
#pragma once

#include "peers/amcl/beam_model.hpp"
#include "peers/amcl/clusters.hpp"
#include "peers/amcl/free_space.hpp"
#include "peers/amcl/grid.hpp"
#include "peers/amcl/likelihood_field.hpp"
#include "peers/peer.hpp"

#include <memory>
#include <random>

namespace bimloc::peers::amcl {

class Amcl : public PeerLocalizer {
 public:
  Amcl(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const AmclConfig& config, std::uint64_t seed);
  bool wantsPoints(const Eigen::Isometry3d& T_odom_base) const override;
  PeerStep step(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>* points_lidar) override;

  // For tests and pictures.
  const Grid& grid() const { return slice_.grid; }
  const LikelihoodField& field() const { return *field_; }
  const FreeSpace& freeSpace() const { return free_; }
  const std::vector<Particle>& particles() const { return particles_; }

 private:
  PlanarPose randomFreePose(std::mt19937_64& rng) const;
  bool gatePasses(const PlanarPose& odom) const;
  void update(double stamp_s, const PlanarPose& odom, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>& points,
              PeerStep& s);
  void weigh(const std::vector<Eigen::Vector2d>& beams);
  void publish(const PlanarPose& odom);  // the statistics and map <- odom, as amcl_node after a resample
  Eigen::Isometry3d poseOf(const PlanarPose& map_base, const Eigen::Isometry3d& T_odom_base) const;

  AmclConfig config_;
  Eigen::Isometry3d T_base_lidar_;
  std::string storey_name_;
  double elevation_m_;
  StoreySlice slice_;
  std::unique_ptr<LikelihoodField> field_;
  std::unique_ptr<BeamModel> model_;
  FreeSpace free_;
  bool no_obstacles_ = false;
  std::mt19937_64 rng_;
  std::vector<Particle> particles_;
  bool initialized_ = false;                // ROS pf_init_: the first scan has been used
  PlanarPose odom_ = PlanarPose::Zero();    // ROS pf_odom_pose_: odometry at the last filter update
  int resample_count_ = 0;
  double w_slow_ = 0, w_fast_ = 0;          // ROS pf->w_slow, pf->w_fast
  SetStats stats_;
  PlanarPose map_odom_ = PlanarPose::Zero();  // map <- odom of the last published pose
  bool published_ = false;
  bool converged_ = false, ever_converged_ = false;
  int weighed_updates_ = 0;
  std::vector<std::string> pending_warnings_;
  bool warned_non_finite_ = false, warned_empty_ = false, warned_odometry_ = false;
  Eigen::Isometry3d last_T_odom_base_ = Eigen::Isometry3d::Identity();  // the last finite odometry pose
};

}  // namespace bimloc::peers::amcl
