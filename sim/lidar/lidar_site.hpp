// What a site adds to one lidar turn, past the static Embree scene: the walking people (each
// ray against their cylinders where they are at its firing block's instant, exactly, nearest
// of the mesh's hit and theirs), and the sensor effects (dropout on glass and dark surfaces,
// mixed points at depth edges). Its random draws come from their own stream of (seed, turn),
// so the noise of a plan's world is unchanged and a turn is the same on any thread.
#pragma once

#include "sim/lidar/fast_random.hpp"
#include "sim/world/world.hpp"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace bimloc::sim {

class LidarSite {
 public:
  LidarSite(const World& world, std::size_t storey, std::uint64_t turn_seed, int lasers);

  bool hasPeople() const { return !people_.empty(); }
  bool hasEffects() const { return any_effect_; }

  // The people's cylinders at t_s (the dataset's clock): call once per firing block.
  void moveTo(double t_s);
  // Before a cycle's rays: which people they can meet. `look` is one of its rays, `spread_rad`
  // bounds the angle between the horizontal directions of any two of them (tilt and spin).
  void aim(const Eigen::Vector3f& origin, const Eigen::Vector3f& look, float spread_rad);
  // The nearest of `hit` (the scene's) and the aimed people's entry along origin + t dir, t >= t_min.
  void occlude(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float t_min, RayHit& hit) const;

  // The sensor's effects on laser `laser`'s return (called for every firing in order, hit or
  // not): false when the return is lost; `range` may become a mixed one.
  bool effects(int laser, const RayHit& hit, float& range);

 private:
  struct Cylinder {
    Eigen::Vector2f centre;
    float radius, z0, z1;
  };
  std::vector<const PersonTruth*> people_;
  std::vector<Cylinder> now_;
  std::vector<const Cylinder*> aimed_;
  SiteSensor sensor_;
  bool any_effect_ = false;
  FastRandom random_;
  std::vector<float> previous_range_;  // per laser, of its previous firing (+inf: no return)
};

}  // namespace bimloc::sim
