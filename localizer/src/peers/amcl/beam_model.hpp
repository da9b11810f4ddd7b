// ROS amcl's likelihood field laser model (AMCLLaser::LikelihoodFieldModel; Probabilistic
// Robotics table 6.3): per beam pz = z_hit exp(-d^2 / (2 sigma_hit^2)) + z_rand / range_max,
// d the end point's distance to the nearest obstacle, and per particle the ad-hoc combination
// ROS uses instead of the product: p = 1 + sum of pz^3.
#pragma once

#include "peers/amcl/likelihood_field.hpp"
#include "peers/amcl/particles.hpp"

#include <Eigen/Core>
#include <vector>

namespace bimloc::peers::amcl {

class BeamModel {
 public:
  BeamModel(const LikelihoodField& field, const AmclConfig& config);
  // pz of one beam whose end point is d [m] from the nearest obstacle.
  double beamProbability(double d) const;
  // Each particle's weight times p for the beams (end points in the base frame); the sum of
  // the new weights (ROS's total_weight).
  double weigh(std::vector<Particle>& particles, const std::vector<Eigen::Vector2d>& beams) const;

 private:
  const LikelihoodField& field_;
  double z_hit_, z_rand_density_, two_sigma2_;
  std::vector<float> cube_;  // pz^3 of each cell, computed once
  float off_map_cube_;       // pz^3 at max_dist: ROS's "off-map penalized as max distance"
};

}  // namespace bimloc::peers::amcl
