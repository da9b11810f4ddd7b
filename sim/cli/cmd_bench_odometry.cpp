// bimloc bench odometry [--seeds N] [--json]
// Drift of each odometry preset: final position error over distance on a 100 m walk
// (a 25 m square, four 90 degree turns), over many seeds: mean, median and 95th percentile.
#include "sim/cli/commands.hpp"
#include "sim/cli/table.hpp"
#include "sim/odometry/odometry_model.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace {

using namespace bimloc::sim;

struct OdomBenchArgs {
  int seeds = 200;
  bool json = false;
};

Eigen::Isometry3d planar(double x, double y, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0.5);
  return T;
}

// Final position error / distance walked, for one seed.
double squareWalkDrift(const OdometryConfig& config, std::uint64_t seed) {
  NoisyOdometry odom(config, seed);
  const double dt = 1.0 / config.rate_hz, speed = 0.8, turn_rate = M_PI / 3;
  double t = 0, x = 0, y = 0, yaw = 0;
  OdometrySample s = odom.step(t, planar(x, y, yaw));
  for (int leg = 0; leg < 4; ++leg) {
    for (double walked = 0; walked < 25.0 - 1e-9; walked += speed * dt) {
      x += speed * dt * std::cos(yaw), y += speed * dt * std::sin(yaw), t += dt;
      s = odom.step(t, planar(x, y, yaw));
    }
    for (double turned = 0; turned < M_PI / 2 - 1e-9; turned += turn_rate * dt) {
      yaw += turn_rate * dt, t += dt;
      s = odom.step(t, planar(x, y, yaw));
    }
  }
  const Eigen::Isometry3d truth = odom.T_map_odom_true().inverse() * planar(x, y, yaw);
  return (s.T_odom_base.translation() - truth.translation()).head<2>().norm() / 100.0;
}

void run(const OdomBenchArgs& args) {
  nlohmann::json rows = nlohmann::json::array();
  bimloc::cli::Table table({"preset", "mean drift", "median", "95th pct"});
  for (const char* preset : {"legged", "lidar", "perfect"}) {
    std::vector<double> drift;
    for (int seed = 0; seed < args.seeds; ++seed)
      drift.push_back(squareWalkDrift(odometryPreset(preset), static_cast<std::uint64_t>(seed)));
    std::sort(drift.begin(), drift.end());
    double mean = 0;
    for (double d : drift) mean += d / double(drift.size());
    const double median = drift[drift.size() / 2], p95 = drift[drift.size() * 95 / 100];
    rows.push_back({{"preset", preset}, {"mean", mean}, {"median", median}, {"p95", p95}, {"seeds", args.seeds}});
    using bimloc::cli::fixed;
    table.add({preset, fixed(100 * mean, 2) + " %", fixed(100 * median, 2) + " %", fixed(100 * p95, 2) + " %"});
  }
  if (args.json) {
    std::cout << nlohmann::json{{"walk_m", 100.0}, {"presets", rows}}.dump() << "\n";
  } else {
    std::cout << "final position error / distance, 100 m square walk, " << args.seeds << " seeds\n\n";
    table.print(std::cout);
  }
}

}  // namespace

void addBenchOdometryCommand(CLI::App& bench) {
  auto args = std::make_shared<OdomBenchArgs>();
  CLI::App* cmd = bench.add_subcommand("odometry", "Drift of each odometry preset over a 100 m walk, over many seeds.");
  cmd->add_option("--seeds", args->seeds, "seeds per preset")->check(CLI::Range(10, 100000));
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args] { run(*args); });
}
