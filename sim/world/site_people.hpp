// Walking people on a site: where each one is at a time, where a ray meets one (exactly: a
// vertical cylinder, analytically, no Embree scene to rebuild as they move), and where they
// walk (drawn from the seed in the site's rooms, or given; a given path through a wall is an
// error). The lidar intersects every ray with the people at its firing block's instant (16 cycles, 0.9 ms).
#pragma once

#include "sim/world/site_truth.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <string>

namespace bimloc::sim {

class World;

// The axis of `person` at time t_s (the dataset's clock): phase_m + speed t along the
// there-and-back loop of its polyline.
Eigen::Vector2d personCentreAt(const PersonTruth& person, double t_s);

// The ray origin + t dir (dir unit) against the closed cylinder of axis `centre` (XY), radius
// r, from z0 to z1: the entry t >= t_min, and the outward normal there. false when the ray
// misses, or starts inside (a person never stands where the robot is: it steps aside).
bool rayEntersCylinder(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, const Eigen::Vector2f& centre, float radius,
                       float z0, float z1, float t_min, float& t, Eigen::Vector3f& normal);

// The first leg of `path` that a person of radius_m cannot walk in `world` (storey `storey`):
// "" when every leg is clear, else a sentence naming the leg and where it meets a wall.
std::string personPathProblem(const World& world, std::size_t storey, const PersonPath& path, double radius_m);

// The people of a site: the given paths, then config.count_per_storey per storey drawn from
// `seed` in rooms, each leg clear in `world` (the site, built). What cannot be placed is a
// warning of `truth`, as is a given path the site's walls or clutter block (the scenario's check
// holds it against the plan: checkSiteAgainstWorld). std::invalid_argument for an unknown storey.
void placePeople(const World& world, const SitePeople& config, std::uint64_t seed, SiteTruth& truth);

}  // namespace bimloc::sim
