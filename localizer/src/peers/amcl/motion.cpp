#include "peers/amcl/particles.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::peers::amcl {

void sampleMotion(std::vector<Particle>& particles, const PlanarPose& old_odom, const PlanarPose& delta, const AmclConfig& config,
                  std::mt19937_64& rng) {
  const double trans = std::hypot(delta.x(), delta.y());
  // Turning on the spot: no direction of travel to rotate to (ROS: below 1 cm).
  const double rot1 = trans < 0.01 ? 0.0 : wrapAngle(std::atan2(delta.y(), delta.x()) - old_odom.z());
  const double rot2 = wrapAngle(delta.z() - rot1);
  // Forward and backward motion are alike: the noise grows with the rotation to the line of
  // travel, whichever way along it (ROS's delta_rot*_noise).
  const double rot1_noise = std::min(std::abs(wrapAngle(rot1)), std::abs(wrapAngle(rot1 - M_PI)));
  const double rot2_noise = std::min(std::abs(wrapAngle(rot2)), std::abs(wrapAngle(rot2 - M_PI)));
  const double a1 = config.odom_alpha1, a2 = config.odom_alpha2, a3 = config.odom_alpha3, a4 = config.odom_alpha4;
  const double sigma_rot1 = std::sqrt(a1 * rot1_noise * rot1_noise + a2 * trans * trans);
  const double sigma_trans = std::sqrt(a3 * trans * trans + a4 * rot1_noise * rot1_noise + a4 * rot2_noise * rot2_noise);
  const double sigma_rot2 = std::sqrt(a1 * rot2_noise * rot2_noise + a2 * trans * trans);
  std::normal_distribution<double> n(0.0, 1.0);
  for (Particle& p : particles) {
    const double r1 = wrapAngle(rot1 - sigma_rot1 * n(rng));
    const double t = trans - sigma_trans * n(rng);
    const double r2 = wrapAngle(rot2 - sigma_rot2 * n(rng));
    p.pose.x() += t * std::cos(p.pose.z() + r1);
    p.pose.y() += t * std::sin(p.pose.z() + r1);
    p.pose.z() = wrapAngle(p.pose.z() + r1 + r2);
  }
}

}  // namespace bimloc::peers::amcl
