#include "peers/amcl/beam_model.hpp"

#include <cmath>

namespace bimloc::peers::amcl {

BeamModel::BeamModel(const LikelihoodField& field, const AmclConfig& config)
    : field_(field),
      z_hit_(config.z_hit),
      z_rand_density_(config.z_rand / config.laser_max_range_m),  // ROS: z_rand * (1 / range_max)
      two_sigma2_(2.0 * config.sigma_hit_m * config.sigma_hit_m) {
  const auto cube = [this](double d) {
    const double pz = beamProbability(d);
    return static_cast<float>(pz * pz * pz);
  };
  cube_.resize(field.distances().size());
  for (std::size_t c = 0; c < cube_.size(); ++c) cube_[c] = cube(field.distances()[c]);
  off_map_cube_ = cube(field.maxDistance());
}

double BeamModel::beamProbability(double d) const {
  // ROS leaves out the Gaussian's 1/(sqrt(2 pi) sigma) ("NOTE: this should have a
  // normalization"), and so does this: the weights are the same up to the mix of z_hit and z_rand.
  return z_hit_ * std::exp(-d * d / two_sigma2_) + z_rand_density_;
}

double BeamModel::weigh(std::vector<Particle>& particles, const std::vector<Eigen::Vector2d>& beams) const {
  const Grid& grid = field_.grid();
  const double inv_res = 1.0 / grid.resolution_m;
  double total = 0;
  for (Particle& particle : particles) {
    const double c = std::cos(particle.pose.z()), s = std::sin(particle.pose.z());
    // Grid coordinates of the particle (cells, fractional), and each beam's offset in cells.
    const double gx = (particle.pose.x() - grid.origin.x()) * inv_res, gy = (particle.pose.y() - grid.origin.y()) * inv_res;
    double p = 1.0;
    for (const Eigen::Vector2d& b : beams) {
      const double fx = gx + (c * b.x() - s * b.y()) * inv_res, fy = gy + (s * b.x() + c * b.y()) * inv_res;
      // Off the map (and far off it: no int overflow) counts as max_dist.
      if (!(fx >= 0 && fy >= 0 && fx < grid.width && fy < grid.height)) {
        p += off_map_cube_;
        continue;
      }
      p += cube_[grid.index(static_cast<int>(fx), static_cast<int>(fy))];
    }
    particle.weight *= p;
    total += particle.weight;
  }
  return total;
}

}  // namespace bimloc::peers::amcl
