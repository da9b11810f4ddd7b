// AMCL's particles and the two random steps that move them: the odometry motion model and
// KLD-sampling resampling (ROS amcl amcl_odom.cpp and pf.c; Probabilistic Robotics ch. 5, 8).
#pragma once

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/peers/amcl_config.hpp>

#include <array>
#include <functional>
#include <random>
#include <vector>

namespace bimloc::peers::amcl {

struct Particle {
  PlanarPose pose = PlanarPose::Zero();  // map x, y, yaw
  double weight = 1.0;                   // normalised over the set between updates
};

// ROS amcl's "diff" odometry model (AMCLOdom::UpdateAction, ODOM_MODEL_DIFF; Probabilistic
// Robotics table 5.6 with the noise as standard deviations sqrt(alpha1 rot^2 + alpha2 trans^2)
// ...): the odometry moved from `old_odom` by `delta` (dx, dy in the odom frame, dyaw).
void sampleMotion(std::vector<Particle>& particles, const PlanarPose& old_odom, const PlanarPose& delta, const AmclConfig& config,
                  std::mt19937_64& rng);

// Fox (2003), KLD-sampling, as ROS amcl's pf_resample_limit: the particles needed for k
// occupied histogram bins, n = (k-1)/(2 err) (1 - 2/(9(k-1)) + sqrt(2/(9(k-1))) z)^3, rounded
// up, within [min_particles, max_particles]; max_particles for k <= 1.
int kldLimit(int k, double err, double z, int min_particles, int max_particles);

// The histogram bin of a pose (ROS pf_kdtree: 0.5 m x 0.5 m x 10 deg cells).
std::array<int, 3> binOf(const PlanarPose& pose);

// ROS amcl's pf_update_resample: draw (with replacement, by weight) until the set holds
// kldLimit(k) particles for the k bins it occupies (or max_particles); each draw is instead a
// random pose with probability w_diff (augmented MCL). The new weights are uniform.
std::vector<Particle> resampleKld(const std::vector<Particle>& particles, const AmclConfig& config, double w_diff,
                                  const std::function<PlanarPose(std::mt19937_64&)>& random_pose, std::mt19937_64& rng);

}  // namespace bimloc::peers::amcl
