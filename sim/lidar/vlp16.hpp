// The Velodyne VLP-16, ray cast in the simulated world: 16 lasers with the manual's vertical
// angles, firing order and per-laser vertical offsets, 2.304 us between firings, 55.296 us per
// firing cycle, clockwise spin; range limits, Gaussian range noise, dropout, intensity from
// the incidence angle; and motion distortion: every cycle is cast from the sensor pose at its
// own instant, so a turning, walking robot gets the skewed turns a real one gets.
#pragma once

#include "sim/lidar/lidar_scan.hpp"
#include "sim/lidar/vlp16_config.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace bimloc::sim {

class World;

constexpr int kVlp16Lasers = 16;
constexpr double kVlp16FiringPeriod_s = 2.304e-6;  // one laser fires every 2.304 us
constexpr double kVlp16CyclePeriod_s = 55.296e-6;  // 16 firings + 18.432 us idle

// Laser id (firing order) -> vertical angle and vertical offset (VLP-16 manual, rev. A).
double vlp16ElevationDeg(int laser);
double vlp16VerticalOffsetM(int laser);
// Ring: 0 for the lowest beam (-15 deg) up to 15 for the highest (+15 deg).
std::uint16_t vlp16Ring(int laser);

// Rays of a turn, recorded for the benchmark's plain loop (same rays, same scene).
struct RayRecord {
  std::vector<Eigen::Vector3f> origins;
  std::vector<Eigen::Vector3f> directions;
};

class Vlp16 {
 public:
  explicit Vlp16(const Vlp16Config& config);

  const Vlp16Config& config() const { return config_; }
  double turnPeriod_s() const { return 60.0 / config_.rpm; }
  double azimuthStepDeg() const { return 360.0 * config_.rpm / 60.0 * kVlp16CyclePeriod_s; }
  int cyclesPerTurn() const { return cycles_; }

  // One turn starting at t0_s (the turn's stamp) on `storey`. T_map_base(t) is the base's
  // true pose. `seed` and `turn_index` fix the noise, so turns can be cast in any order or
  // in parallel with the same result.
  LidarScan scan(const World& world, std::size_t storey, const std::function<Eigen::Isometry3d(double)>& T_map_base,
                 double t0_s, std::uint64_t seed, std::uint64_t turn_index, RayRecord* rays = nullptr) const;

 private:
  Vlp16Config config_;
  int cycles_ = 0;
  std::array<Eigen::Vector3d, kVlp16Lasers> offsets_;  // laser origin in the sensor frame
  // The head's yaw at each cycle of a turn (cos, sin of -omega t_cycle): the same every turn,
  // computed once instead of once a cycle of every turn.
  std::vector<double> cos_cycle_, sin_cycle_;
};

}  // namespace bimloc::sim
