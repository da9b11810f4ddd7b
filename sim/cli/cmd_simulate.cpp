// bimloc simulate SCENARIO --out DIR [--threads N] [--format ros1|mcap|sqlite3] [--compression C] [--packets]
#include "sim/cli/commands.hpp"
#include "sim/cli/progress.hpp"
#include "sim/dataset/dataset_metadata.hpp"
#include "sim/dataset/dataset_writer.hpp"
#include "sim/simulation/simulator.hpp"

#include <algorithm>
#include <iostream>
#include <map>
#include <thread>
#include <vector>

namespace {

using namespace bimloc::sim;

struct SimulateArgs {
  std::string scenario;
  std::string out;
  int threads = 0;
  bool quiet = false;
  bool packets = false;
  std::string format = "ros1";
  std::string compression;  // empty: the format's default
};

// The chunk compressions each format's own recorder offers, the default first: `rosbag record`
// (none, --lz4, --bz2) and rosbag2's MCAP storage (zstd, lz4, none); our SQLite3 bag stores
// messages as they are (rosbag2's file / message compression is refused by `localize`).
const std::map<std::string, std::vector<std::string>>& compressionsOf() {
  static const std::map<std::string, std::vector<std::string>> of = {
      {"ros1", {"none", "lz4", "bz2"}}, {"mcap", {"zstd", "lz4", "none"}}, {"sqlite3", {"none"}}};
  return of;
}

// A compression the format does not have: said, and exit 2 (a bad option, before anything runs).
std::string chosenCompression(const SimulateArgs& args) {
  const auto& offered = compressionsOf().at(args.format);
  if (args.compression.empty()) return offered.front();
  if (std::find(offered.begin(), offered.end(), args.compression) == offered.end()) {
    std::string list;
    for (const auto& c : offered) list += (list.empty() ? "" : ", ") + c;
    std::cerr << "bimloc simulate: error: --compression " << args.compression << ": a " << args.format
              << " bag has no such compression (it has: " << list << ")\n";
    throw bimloc::cli::ExitCode{bimloc::cli::kExitUnusableInput};
  }
  return args.compression;
}

nlohmann::json metadata(const Simulator& sim, const std::string& scenario_path) {
  const Scenario& s = sim.scenario();
  const Vlp16Config& c = s.sensor;
  return {{"scenario", {{"name", s.name}, {"file", scenario_path}}},
          {"seed", s.seed},
          {"world", s.world},
          {"storey", sim.world().building().storeyLabel(sim.storey())},
          {"start", {{"x", sim.start().x}, {"y", sim.start().y}, {"yaw_rad", sim.start().yaw}}},
          {"duration_s", s.duration_s},
          {"sensor", {{"model", "VLP-16"}, {"rpm", c.rpm}, {"min_range_m", c.min_range_m}, {"max_range_m", c.max_range_m},
                      {"range_noise_sigma_m", c.range_noise_sigma_m}, {"dropout_probability", c.dropout_probability},
                      {"motion_distortion", c.motion_distortion}, {"mount_T_base_lidar", poseJson(c.T_base_lidar)}}},
          {"odometry", {{"preset", s.odometry.preset}, {"rate_hz", s.odometry.rate_hz}}},
          {"T_map_odom_true", poseJson(sim.T_map_odom_true())},
          // The truth of how the simulated site differs from the plan the localizer gets.
          {"site", siteTruthJson(sim.world().siteTruth())}};
}

void run(const SimulateArgs& args) {
  const std::string compression = chosenCompression(args);
  const Scenario scenario = loadScenario(args.scenario);
  const World world = World::load(scenario.world);
  checkScenarioAgainstWorld(scenario, world);
  const Simulator sim(scenario, world);

  DatasetInfo info;
  info.metadata = metadata(sim, args.scenario);
  info.T_base_lidar = scenario.sensor.T_base_lidar;
  info.bag_format = args.format;
  const std::string stored = compression == "none" ? "" : compression;
  if (args.format == "ros1") info.ros1_compression = stored;
  if (args.format == "mcap") info.mcap_compression = stored;
  if (args.packets) info.packets_rpm = scenario.sensor.rpm;
  DatasetWriter writer(args.out, info);
  for (const auto& o : sim.odometry()) writer.addOdometry(o);
  for (const auto& g : sim.groundTruth()) writer.addGroundTruth(g);
  const int threads = args.threads > 0 ? args.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  {
    bimloc::cli::Progress progress("simulating " + scenario.name);
    sim.castTurns(threads, [&](LidarScan&& scan) { writer.addScan(scan); },
                  [&](std::size_t done, std::size_t total) { progress.update(done, total); });
  }
  const auto files = writer.commit();
  if (!args.quiet)
    std::cout << scenario.name << ": " << sim.turnCount() << " turns, " << scenario.duration_s << " s simulated, written to "
              << args.out << " (" << files.size() << " files)\n";
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Simulate a scenario (a Spot-like base with a VLP-16 walking through the plan's building) and write a\n"
      "synthetic dataset to DIR: dataset.bag (ROS1: /velodyne_points, /odom, /tf, /ground_truth; with --format\n"
      "mcap or sqlite3 a ROS 2 bag instead, the folder rosbag2/ as `ros2 bag record` writes it), one PCD per\n"
      "turn in clouds/, odometry.tum and ground_truth.tum, metadata.json. Same scenario and seed give\n"
      "bit-identical output whatever --threads. The folder appears only when everything is written.");
  cmd->add_option("scenario", args->scenario, "scenario file (YAML, see scenarios/README.md)")->required();
  cmd->add_option("--out", args->out, "output folder")->required();
  cmd->add_option("--threads", args->threads, "threads casting lidar turns (default: all cores)")->check(CLI::Range(1, 256));
  cmd->add_flag("--packets", args->packets,
                "also write the VLP-16's own data packets: velodyne_msgs/VelodyneScan on /velodyne_packets in the bag\n"
                "(one a turn) and velodyne.pcap, the sensor's UDP stream (port 2368), for a robot's own driver");
  cmd->add_flag("--quiet", args->quiet, "print nothing on success");
  cmd->add_option("--format", args->format,
                  "the bag: ros1 (dataset.bag), mcap (rosbag2/rosbag2_0.mcap) or sqlite3 (rosbag2/rosbag2_0.db3)")
      ->check(CLI::IsMember({"ros1", "mcap", "sqlite3"}))
      ->capture_default_str();
  cmd->add_option("--compression", args->compression,
                  "the bag's chunk compression, as the format's recorder offers it: ros1 none (the default), lz4 or bz2\n"
                  "(rosbag record --lz4 / --bz2); mcap zstd (the default), lz4 or none; sqlite3 none. Any other exits 2");
  cmd->callback([args] { run(*args); });
}
