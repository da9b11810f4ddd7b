// bimloc bench bags [SCENARIO] [--repeat N] [--json]
// The cost of reading one run's recording as a ROS 1 bag, a ROS 2 MCAP bag (zstd chunks, as
// rosbag2 writes by default; and lz4 and uncompressed chunks, the same bag as the uncompressed
// ROS 1 one but for the container) and a ROS 2 SQLite3 bag: the input layer of `localize` (BagInput: topics, odometry, tf, every cloud
// decoded), best of N, each against the ROS 1 bag in the same run. The reads take turns (ROS 1,
// MCAP, SQLite3, then again), so that a load that comes and goes on a shared machine falls on
// each format alike; the ratio is of CPU seconds (the process's), since wall time also counts
// waiting for a core.
#include "sim/cli/commands.hpp"
#include "sim/cli/table.hpp"
#include "sim/dataset/bag_reader.hpp"
#include "sim/dataset/dataset_writer.hpp"
#include "sim/runner/run_scenario.hpp"
#include "sim/simulation/simulator.hpp"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include <unistd.h>

namespace {

using namespace bimloc::sim;
using Clock = std::chrono::steady_clock;

struct BagBenchArgs {
  std::string scenario = "scenarios/site_office_R101.yaml";
  int repeat = 3;
  bool json = false;
};

std::uintmax_t bytesOf(const std::filesystem::path& p) {
  if (std::filesystem::is_regular_file(p)) return std::filesystem::file_size(p);
  std::uintmax_t n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(p))
    if (e.is_regular_file()) n += e.file_size();
  return n;
}

void run(const BagBenchArgs& args) {
  const Scenario scenario = loadScenario(args.scenario);
  const World world = World::load(scenario.world);
  const Simulator sim(scenario, world);
  std::vector<LidarScan> scans;
  sim.castTurns(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())),
                [&](LidarScan&& scan) { scans.push_back(std::move(scan)); });
  const auto tmp = std::filesystem::temp_directory_path() / ("bimloc-bench-bags-" + std::to_string(::getpid()));
  struct Format {
    std::string name, bag_format, mcap_compression, input;
  };
  const std::vector<Format> formats = {{"ros1", "ros1", "", "dataset.bag"},
                                       {"mcap", "mcap", "zstd", "rosbag2"},
                                       {"mcap-lz4", "mcap", "lz4", "rosbag2"},
                                       {"mcap-none", "mcap", "", "rosbag2"},
                                       {"sqlite3", "sqlite3", "", "rosbag2"}};
  nlohmann::json rows = nlohmann::json::array();
  bimloc::cli::Table table({"format", "bag [MB]", "read [s]", "read CPU [s]", "x ROS 1 (CPU)", "points"});
  struct Measured {
    std::string input;
    double wall_s = 1e300, cpu_s = 1e300;
    std::size_t points = 0;
  };
  std::vector<Measured> measured(formats.size());
  try {
    for (std::size_t k = 0; k < formats.size(); ++k) {
      DatasetInfo info;
      info.T_base_lidar = scenario.sensor.T_base_lidar;
      info.bag_format = formats[k].bag_format;
      info.mcap_compression = formats[k].mcap_compression;
      const std::string dir = (tmp / formats[k].name).string();
      DatasetWriter writer(dir, info);
      for (const auto& o : sim.odometry()) writer.addOdometry(o);
      for (const auto& g : sim.groundTruth()) writer.addGroundTruth(g);
      for (const auto& s : scans) writer.addScan(s);
      writer.commit();
      measured[k].input = dir + "/" + formats[k].input;
    }
    for (int i = 0; i < std::max(1, args.repeat); ++i)
      for (Measured& m : measured) {
        const auto t0 = Clock::now();
        const double cpu0 = processCpuSeconds();
        const BagInput bag(m.input, BagInputOptions{});
        m.points = 0;
        bag.forEachTurn([&](const BagTurn& t) { m.points += t.points().size(); });
        m.cpu_s = std::min(m.cpu_s, processCpuSeconds() - cpu0);
        m.wall_s = std::min(m.wall_s, std::chrono::duration<double>(Clock::now() - t0).count());
      }
    for (std::size_t k = 0; k < formats.size(); ++k) {
      const Measured& m = measured[k];
      const double ratio = m.cpu_s / measured[0].cpu_s;
      const double mb = static_cast<double>(bytesOf(m.input)) / 1e6;
      rows.push_back({{"format", formats[k].name}, {"compression", formats[k].mcap_compression}, {"bag_bytes", bytesOf(m.input)}, {"read_seconds", m.wall_s},
                      {"read_cpu_seconds", m.cpu_s}, {"ratio_to_ros1", ratio}, {"points", m.points}, {"turns", scans.size()}});
      using bimloc::cli::fixed;
      table.add({formats[k].name, fixed(mb, 1), fixed(m.wall_s, 3), fixed(m.cpu_s, 3), fixed(ratio, 2), std::to_string(m.points)});
    }
  } catch (...) {
    std::filesystem::remove_all(tmp);
    throw;
  }
  std::filesystem::remove_all(tmp);
  if (args.json) {
    std::cout << nlohmann::json{{"scenario", args.scenario}, {"repeat", args.repeat}, {"formats", rows}}.dump() << "\n";
  } else {
    std::cout << args.scenario << ": " << scans.size() << " turns, best of " << args.repeat << "\n\n";
    table.print(std::cout);
  }
}

}  // namespace

void addBenchBagsCommand(CLI::App& bench) {
  auto args = std::make_shared<BagBenchArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "bags", "Reading one run as a ROS 1 bag, a ROS 2 MCAP bag (chunks zstd, rosbag2's default: mcap; lz4: mcap-lz4; "
              "uncompressed like the ROS 1 bag: mcap-none) and a ROS 2 SQLite3 bag (localize's input layer, every cloud decoded), "
              "the reads taking turns: seconds, CPU seconds and the ratio of CPU to the ROS 1 bag's, in the same run.");
  cmd->add_option("scenario", args->scenario, "scenario file")->capture_default_str();
  cmd->add_option("--repeat", args->repeat, "reads of each bag; the best is kept")->capture_default_str()->check(CLI::Range(1, 100));
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args] { run(*args); });
}
