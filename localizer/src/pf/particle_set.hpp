// The particle set and what is done to it as a whole: the uniform spread over the rooms,
// injection at pose hypotheses, low-variance resampling, the weights and the weighted mean.
#pragma once

#include "hypotheses.hpp"
#include "room_index.hpp"

#include <bimloc/pf/particle_filter.hpp>

#include <random>
#include <vector>

namespace bimloc::pf::detail {

// Uniform over the free space of the storey: a room by area, a point in it, any heading.
std::vector<Particle> spreadOverRooms(const RoomIndex& rooms, std::size_t count, std::mt19937_64& rng);

// Moves the `count` lightest particles to poses around the hypotheses (round robin over the
// good ones), as heavy as the heaviest particle plus `bonus`: the evidence then weighs them.
int inject(std::vector<Particle>& particles, const std::vector<Hypothesis>& hyps, std::size_t count, double bonus,
           const RoomIndex& rooms, std::mt19937_64& rng);

// Low-variance resampling (Probabilistic Robotics, Table 4.4) to `count` particles, then
// roughening. Returns the new index of a copy of particle `best` (any, if it was not drawn).
std::size_t resample(std::vector<Particle>& particles, const std::vector<double>& w, std::size_t count, std::size_t best,
                     double roughening_xy_m, double roughening_yaw_rad, const RoomIndex& rooms, std::mt19937_64& rng);

std::size_t heaviest(const std::vector<Particle>& particles);
std::vector<double> normalisedWeights(const std::vector<Particle>& particles);
// x, y and the circular mean of the heading.
Eigen::Vector3d weightedMean(const std::vector<Particle>& particles, const std::vector<double>& w);

}  // namespace bimloc::pf::detail
