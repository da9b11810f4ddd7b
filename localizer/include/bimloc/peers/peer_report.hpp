// What a peer localizer (the paper's baselines: AMCL, HDL-style NDT) said on one step. The
// peers run behind the same bimloc::Localizer::step as the paper's method, so the bench feeds
// them the same scans and odometry and one scorer judges them all.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace bimloc::peers {

struct PeerReport {
  std::string method;        // "amcl" or "ndt"
  bool converged = false;    // by the method's own criterion, on this step
  bool relocalizing = false; // it had converged and gave the pose up (searching again)
  bool updated = false;      // this step used the scan (update gates passed)
  int particles = 0;         // AMCL: the particle count after this step (KLD); NDT: 0
  double score = 0;          // AMCL: the largest sqrt(eigenvalue) of the xy covariance [m];
                             // NDT: the fitness (mean squared distance of matched points) [m^2]
  double hit_fraction = 0;   // NDT: the last global search's share of scan cells on occupied map cells
  double margin_fraction = 0; // NDT: its lead over the best distinct pose, as a share of the scan cells
  std::vector<Eigen::Vector3d> poses;  // AMCL: the particles (x, y, yaw) for pictures; NDT: empty
};

}  // namespace bimloc::peers
