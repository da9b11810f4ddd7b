#include "sim/lidar/vlp16.hpp"

#include "sim/lidar/fast_random.hpp"
#include "sim/lidar/lidar_site.hpp"
#include "sim/world/world.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim {
namespace {

// Reference: VLP-16 User Manual rev. A (../shared/reference.md), in firing order.
constexpr double kElevationDeg[kVlp16Lasers] = {-15, 1, -13, 3, -11, 5, -9, 7, -7, 9, -5, 11, -3, 13, -1, 15};
constexpr double kOffsetMm[kVlp16Lasers] = {11.2, -0.7, 9.7, -2.2, 8.1, -3.7, 6.6, -5.1,
                                            5.1,  -6.6, 3.7, -8.1, 2.2, -9.7, 0.7, -11.2};

// splitmix64: a well-mixed per-turn seed from (scenario seed, turn index).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Intensity from the incidence angle (Lambertian), on the driver's 0..255 scale; a matte
// wall seen head-on returns about 100, as painted plaster does on a real VLP-16.
float intensity(const Eigen::Vector3f& dir, const Eigen::Vector3f& normal) {
  return 100.0f * std::max(0.0f, -dir.dot(normal));
}

}  // namespace

double vlp16ElevationDeg(int laser) { return kElevationDeg[laser]; }
double vlp16VerticalOffsetM(int laser) { return 1e-3 * kOffsetMm[laser]; }
std::uint16_t vlp16Ring(int laser) { return static_cast<std::uint16_t>((kElevationDeg[laser] + 15) / 2); }

Vlp16::Vlp16(const Vlp16Config& config) : config_(config) {
  cycles_ = static_cast<int>(std::floor(turnPeriod_s() / kVlp16CyclePeriod_s));
  for (int k = 0; k < kVlp16Lasers; ++k) offsets_[k] = Eigen::Vector3d(0, 0, vlp16VerticalOffsetM(k));
  const double omega = 2.0 * M_PI * config_.rpm / 60.0;  // as scan() computes it
  for (int c = 0; c < std::max(0, cycles_); ++c) {
    const double t_cycle = c * kVlp16CyclePeriod_s;
    cos_cycle_.push_back(std::cos(-omega * t_cycle)), sin_cycle_.push_back(std::sin(-omega * t_cycle));
  }
}

LidarScan Vlp16::scan(const World& world, std::size_t storey, const std::function<Eigen::Isometry3d(double)>& T_map_base,
                      double t0_s, std::uint64_t seed, std::uint64_t turn_index, RayRecord* rays) const {
  LidarScan out;
  out.stamp_s = t0_s;
  out.points.reserve(static_cast<std::size_t>(cycles_) * kVlp16Lasers);
  FastRandom rng(mix(seed ^ mix(turn_index)));
  LidarSite site(world, storey, mix(seed ^ mix(turn_index)), kVlp16Lasers);
  const float sigma = static_cast<float>(config_.range_noise_sigma_m);
  const bool dropout = config_.dropout_probability > 0.0;
  const double omega = 2.0 * M_PI * config_.rpm / 60.0;  // rad/s, clockwise seen from above
  const float t_min = 0.05f, t_max = static_cast<float>(config_.max_range_m + 1.0);
  std::array<double, kVlp16Lasers> cos_el, sin_el;
  for (int k = 0; k < kVlp16Lasers; ++k) {
    cos_el[k] = std::cos(kElevationDeg[k] * M_PI / 180.0);
    sin_el[k] = std::sin(kElevationDeg[k] * M_PI / 180.0);
  }
  const Eigen::Isometry3d T_static = T_map_base(t0_s) * config_.T_base_lidar;

  // Cycles are cast in blocks of 16: for each laser, one packet of its 16 consecutive firings
  // (adjacent azimuths, nearly one origin: coherent rays). Points are emitted cycle by cycle,
  // laser by laser, so packets or single rays give the same scan, noise draws included.
  constexpr int kBlock = 16;
  RayHit hits[kBlock][kVlp16Lasers];
  Eigen::Vector3f origins[kBlock][kVlp16Lasers], local_dirs[kBlock][kVlp16Lasers], world_dirs[kBlock][kVlp16Lasers];
  float times[kBlock][kVlp16Lasers];
  // The head turns by a fixed angle between the 16 firings of a cycle: rotate instead of
  // calling sin and cos for every ray.
  std::array<double, kVlp16Lasers> cos_fire, sin_fire;
  for (int k = 0; k < kVlp16Lasers; ++k)
    cos_fire[k] = std::cos(-omega * k * kVlp16FiringPeriod_s), sin_fire[k] = std::sin(-omega * k * kVlp16FiringPeriod_s);
  for (int c0 = 0; c0 < cycles_; c0 += kBlock) {
    const int n = std::min(kBlock, cycles_ - c0);
    for (int j = 0; j < n; ++j) {
      const double t_cycle = (c0 + j) * kVlp16CyclePeriod_s;
      // Each cycle is cast from the sensor's pose at its own instant (motion distortion).
      const Eigen::Isometry3d T = config_.motion_distortion ? T_map_base(t0_s + t_cycle) * config_.T_base_lidar : T_static;
      const Eigen::Matrix3f R = T.linear().cast<float>();
      const Eigen::Vector3f t_lidar = T.translation().cast<float>(), up = R.col(2);
      const double c_yaw = cos_cycle_[static_cast<std::size_t>(c0 + j)], s_yaw = sin_cycle_[static_cast<std::size_t>(c0 + j)];
      for (int k = 0; k < kVlp16Lasers; ++k) {
        times[j][k] = static_cast<float>(t_cycle + k * kVlp16FiringPeriod_s);
        const double c = c_yaw * cos_fire[k] - s_yaw * sin_fire[k], s_ = s_yaw * cos_fire[k] + c_yaw * sin_fire[k];
        local_dirs[j][k] = Eigen::Vector3f(float(cos_el[k] * c), float(cos_el[k] * s_), float(sin_el[k]));
        world_dirs[j][k] = R * local_dirs[j][k];
        origins[j][k] = t_lidar + static_cast<float>(offsets_[k].z()) * up;  // the laser's vertical offset
      }
      if (rays) {  // in firing order: what a one-ray-per-firing caster would cast
        rays->origins.insert(rays->origins.end(), origins[j], origins[j] + kVlp16Lasers);
        rays->directions.insert(rays->directions.end(), world_dirs[j], world_dirs[j] + kVlp16Lasers);
      }
    }
    for (int k = 0; k < kVlp16Lasers; ++k) {
      if (config_.use_packets) {
        Eigen::Vector3f o[kBlock], d[kBlock];
        RayHit packet[kBlock];
        for (int j = 0; j < n; ++j) o[j] = origins[j][k], d[j] = world_dirs[j][k];
        world.castRays16(storey, o, d, t_min, t_max, packet, n);
        for (int j = 0; j < n; ++j) hits[j][k] = packet[j];
      } else {
        for (int j = 0; j < n; ++j) hits[j][k] = world.castRay(storey, origins[j][k], world_dirs[j][k], t_min, t_max);
      }
    }
    // People move between firing blocks: a block (16 cycles, 0.9 ms: a walker moves 1 mm)
    // meets them where they are at its first cycle's instant.
    const bool people = site.hasPeople(), effects = site.hasEffects();
    if (people) site.moveTo(t0_s + c0 * kVlp16CyclePeriod_s);
    for (int j = 0; j < n; ++j) {
      if (people) {
        // A cycle's rays share one azimuth in the sensor frame; in the map their horizontal
        // directions part by the spin over its 16 firings and, tilted, by up to
        // tan(15 deg) sin(tilt) / cos(tilt) either side of the level one.
        const Eigen::Vector3f up = (world_dirs[j][kVlp16Lasers - 1] - world_dirs[j][0]).normalized();  // +-15 deg pair
        const float tilt = std::sqrt(std::max(0.0f, 1.0f - up.z() * up.z()));
        const float spread = 0.6f * tilt / std::max(0.5f, std::abs(up.z())) + 0.01f;
        site.aim(origins[j][0], world_dirs[j][0], spread);
      }
      for (int k = 0; k < kVlp16Lasers; ++k) {
        RayHit& hit = hits[j][k];
        if (people) site.occlude(origins[j][k], world_dirs[j][k], t_min, hit);
        float true_range = hit.range_m;
        const bool kept = !effects || site.effects(k, hit, true_range);
        if (!hit.hit()) continue;
        // Noise and dropout are drawn for every return, kept or not, so that the random
        // sequence depends on the configuration only, never on the range limits.
        const float range = true_range + (sigma > 0.0f ? sigma * static_cast<float>(rng.normal()) : 0.0f);
        const bool dropped = dropout && rng.uniform() < config_.dropout_probability;
        if (!kept || dropped || range < config_.min_range_m || range > config_.max_range_m) continue;
        const Eigen::Vector3f p = offsets_[k].cast<float>() + range * local_dirs[j][k];
        out.points.push_back({p.x(), p.y(), p.z(), intensity(world_dirs[j][k], hit.normal), vlp16Ring(k), times[j][k]});
      }
    }
  }
  return out;
}

}  // namespace bimloc::sim
