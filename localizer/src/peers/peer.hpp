// The seam between bimloc::Localizer and a peer method (AMCL, NDT): what the localizer asks a
// peer on each step. Private to the library.
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/peers/amcl_config.hpp>
#include <bimloc/peers/ndt_config.hpp>
#include <bimloc/peers/peer_report.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bimloc::peers {

struct PeerStep {
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();  // best guess, even unconverged
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();      // of (x, y, yaw)
  PeerReport report;
  std::vector<std::string> warnings;
};

class PeerLocalizer {
 public:
  virtual ~PeerLocalizer() = default;
  // Whether the step for this odometry pose will look at the points (update gates).
  virtual bool wantsPoints(const Eigen::Isometry3d& T_odom_base) const = 0;
  // One lidar turn; points_lidar is null when wantsPoints said no.
  virtual PeerStep step(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>* points_lidar) = 0;
};

// The storey is the plan's (its mesh is the map); T_base_lidar the lidar mount.
std::unique_ptr<PeerLocalizer> makeAmcl(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const AmclConfig& config,
                                        std::uint64_t seed);
std::unique_ptr<PeerLocalizer> makeNdt(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const NdtConfig& config,
                                       std::uint64_t seed);

}  // namespace bimloc::peers
