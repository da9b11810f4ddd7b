#include "sim/simulation/simulator.hpp"

#include "sim/odometry/odometry_model.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace bimloc::sim {
namespace {

// Seeds of the independent random streams of a scenario, from its one seed.
std::uint64_t streamSeed(std::uint64_t seed, std::uint64_t stream) { return seed * 0x9E3779B97F4A7C15ull + stream; }
constexpr std::uint64_t kOdometryStream = 2;
constexpr std::uint64_t kLidarStream = 3;

// The scenario's site world, or none when the site is the plan.
std::unique_ptr<const World> siteWorld(const Scenario& scenario, const World& world) {
  if (scenario.site.exact()) return nullptr;
  try {
    return std::make_unique<const World>(world.withSite(scenario.site, scenario.seed));
  } catch (const std::invalid_argument& e) {
    const auto it = scenario.lines.find("site");
    throw ScenarioError(scenario.file + (it != scenario.lines.end() ? ":" + std::to_string(it->second) : std::string()) +
                        ": " + e.what());
  }
}

}  // namespace

Simulator::Simulator(const Scenario& scenario, const World& world)
    : scenario_(scenario),
      site_(siteWorld(scenario, world)),
      world_(site_ ? *site_ : world),
      storey_(scenarioStorey(scenario, world)),
      start_(startPose(scenario, world)),
      trajectory_(planTrajectory(scenario, world)),
      lidar_(scenario.sensor) {}

std::size_t Simulator::turnCount() const {
  return static_cast<std::size_t>(std::floor(scenario_.duration_s / lidar_.turnPeriod_s() + 1e-9));
}

double Simulator::turnStamp(std::size_t turn) const { return static_cast<double>(turn) * lidar_.turnPeriod_s(); }

LidarScan Simulator::turn(std::size_t turn) const {
  return cast(turn, lidarStorey(), [this](double t) { return trajectory_.T_map_base(t); });
}

LidarScan Simulator::turnOnItsStoreyAlone(std::size_t turn) const {
  return cast(turn, storey_, [this](double t) { return trajectory_.T_map_base(t); });
}

LidarScan Simulator::turnAlong(std::size_t turn, const std::function<Eigen::Isometry3d(double)>& T_map_base) const {
  return cast(turn, lidarStorey(), T_map_base);
}

LidarScan Simulator::cast(std::size_t turn, std::size_t storey, const std::function<Eigen::Isometry3d(double)>& T_map_base) const {
  // Every form of a turn draws the same noise: the lidar's stream, seeded by the turn.
  return lidar_.scan(world_, storey, T_map_base, turnStamp(turn), streamSeed(scenario_.seed, kLidarStream), turn);
}

NoisyOdometry Simulator::odometryModel(double floor_z) const {
  return NoisyOdometry(scenario_.odometry, streamSeed(scenario_.seed, kOdometryStream), floor_z);
}

void Simulator::castTurns(int threads, const std::function<void(LidarScan&&)>& sink,
                          const std::function<void(std::size_t, std::size_t)>& progress) const {
  const std::size_t total = turnCount();
  const std::size_t workers = static_cast<std::size_t>(std::max(1, threads));
  // Batches of turns cast in parallel, handed over in order: memory stays bounded and the
  // output does not depend on the thread count.
  const std::size_t batch = 4 * workers;
  for (std::size_t first = 0; first < total; first += batch) {
    const std::size_t count = std::min(batch, total - first);
    std::vector<LidarScan> scans(count);
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t i = next++; i < count; i = next++) scans[i] = turn(first + i);
    };
    std::vector<std::thread> pool;
    for (std::size_t w = 1; w < std::min(workers, count); ++w) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    for (auto& s : scans) sink(std::move(s));
    if (progress) progress(first + count, total);
  }
}

std::vector<OdometrySample> Simulator::odometry() const {
  NoisyOdometry model(scenario_.odometry, streamSeed(scenario_.seed, kOdometryStream), trajectory_.floor_z(0.0));
  std::vector<OdometrySample> out;
  const double dt = 1.0 / scenario_.odometry.rate_hz;
  for (std::size_t k = 0; k * dt <= scenario_.duration_s + 1e-9; ++k)
    out.push_back(model.step(k * dt, trajectory_.T_map_base(k * dt), trajectory_.onStairs(k * dt)));
  return out;
}

std::vector<GroundTruthSample> Simulator::groundTruth() const {
  std::vector<GroundTruthSample> out;
  const double dt = 1.0 / scenario_.odometry.rate_hz;
  for (std::size_t k = 0; k * dt <= scenario_.duration_s + 1e-9; ++k)
    out.push_back({k * dt, trajectory_.T_map_base(k * dt), trajectory_.storey(k * dt), trajectory_.onStairs(k * dt)});
  return out;
}

Eigen::Isometry3d Simulator::T_map_odom_true() const {
  NoisyOdometry model(scenario_.odometry, 0, trajectory_.floor_z(0.0));
  model.step(0.0, trajectory_.T_map_base(0.0));
  return model.T_map_odom_true();
}

}  // namespace bimloc::sim
