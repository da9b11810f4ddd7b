#include "sim/lidar/lidar_site.hpp"

#include "sim/world/site_people.hpp"

#include <cmath>
#include <limits>

namespace bimloc::sim {

LidarSite::LidarSite(const World& world, std::size_t storey, std::uint64_t turn_seed, int lasers)
    : sensor_(world.siteTruth().sensor),
      random_(turn_seed ^ 0x51735E75E7ull),
      previous_range_(static_cast<std::size_t>(lasers), std::numeric_limits<float>::infinity()) {
  for (const PersonTruth& p : world.siteTruth().people)
    if (p.storey == storey || storey == World::kAllStoreys) people_.push_back(&p);
  now_.resize(people_.size());
  any_effect_ = sensor_.any();
}

void LidarSite::moveTo(double t_s) {
  for (std::size_t i = 0; i < people_.size(); ++i) {
    const PersonTruth& p = *people_[i];
    now_[i] = {personCentreAt(p, t_s).cast<float>(), static_cast<float>(p.radius_m), static_cast<float>(p.floor_z),
               static_cast<float>(p.floor_z + p.height_m)};
  }
}

void LidarSite::aim(const Eigen::Vector3f& origin, const Eigen::Vector3f& look, float spread_rad) {
  aimed_.clear();
  const Eigen::Vector2f h = look.head<2>().normalized();
  // The rays' origins differ by the lasers' vertical offsets (about 2 cm, tilted): a margin.
  constexpr float kOriginMargin_m = 0.05f;
  for (const Cylinder& c : now_) {
    const Eigen::Vector2f v = c.centre - origin.head<2>();
    const float along = h.dot(v), across = std::abs(h.x() * v.y() - h.y() * v.x());
    if (along < -(c.radius + kOriginMargin_m)) continue;  // behind the cycle's rays
    if (across > c.radius + kOriginMargin_m + spread_rad * v.norm()) continue;  // beside them
    aimed_.push_back(&c);
  }
}

void LidarSite::occlude(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float t_min, RayHit& hit) const {
  for (const Cylinder* cylinder : aimed_) {
    const Cylinder& c = *cylinder;
    float t = 0.0f;
    Eigen::Vector3f normal;
    if (!rayEntersCylinder(origin, dir, c.centre, c.radius, c.z0, c.z1, t_min, t, normal) || !(t < hit.range_m)) continue;
    hit.range_m = t;
    hit.normal = normal;
    hit.dropout = 0.0f;  // clothes: a matte, bright enough target
  }
}

bool LidarSite::effects(int laser, const RayHit& hit, float& range) {
  float& previous = previous_range_[static_cast<std::size_t>(laser)];
  const float here = hit.range_m, before = previous;
  previous = here;
  if (!hit.hit()) return false;
  // Draws only where an effect can happen (a lossy surface, an edge): the sequence is a
  // function of the scene and the turn, and a plain wall costs no draw.
  if (hit.dropout > 0.0f && random_.uniform() < hit.dropout) return false;
  if (sensor_.mixed_probability > 0.0 && std::isfinite(before) && std::abs(here - before) > sensor_.mixed_jump_m &&
      random_.uniform() < sensor_.mixed_probability)
    range += static_cast<float>(random_.uniform()) * (before - here);  // between this surface and the previous firing's
  return true;
}

}  // namespace bimloc::sim
