// bimloc bench bags [SCENARIO] [--repeat N] [--json]
// The cost of reading one run's recording as a ROS 1 bag and as ROS 2 bags: the input layer of
// `localize` (BagInput: topics, odometry, tf, every cloud decoded and de-skewed), best of N,
// each against the ROS 1 bag in the same run, by wall time and by CPU time. The formats:
//   ros1          the ROS 1 bag of `simulate` (uncompressed): every ratio's reference
//   ros1-lz4, ros1-bz2  the same bag with chunks compressed by rosbag's own writer, as
//                 `rosbag record --lz4 / --bz2` writes them: the references of the compressed
//                 ROS 2 forms (MCAP lz4 against ROS 1 lz4; zstd, which ROS 1 has not, against both)
//   ros1-lz4-mixed  lz4, the topics interleaved in the order received, as `rosbag record --lz4`
//                 writes a robot's topics: the reference of mcap-rosbag2, rosbag2's own layout
//   mcap          MCAP, zstd chunks of 4 MiB (as `simulate --format mcap` writes it), read with
//                 its chunks decompressed ahead on a worker thread (chunk_prefetcher.hpp)
//   mcap-1thread  the same file read on one thread (BIMLOC_MCAP_PREFETCH=0)
//   mcap-rosbag2  MCAP as `ros2 bag record -s mcap` writes it by default: zstd chunks of
//                 768 KiB with their CRC, the topics interleaved in the order received
//   mcap-lz4, mcap-none  MCAP with lz4 / uncompressed chunks (4 MiB)
//   sqlite3       rosbag2's SQLite3 storage
// The reads take turns (every format, then again), so that a load that comes and goes on a
// shared machine falls on each format alike. Wall time is what a user waits; CPU time (the
// process's, every thread) is what the machine spends; the reading thread's CPU time is the
// read's critical path: its wall time where a core is free for the prefetch workers (on a
// machine whose cores are all busy, wall time follows the CPU time instead).
#include "sim/cli/commands.hpp"
#include "sim/cli/table.hpp"
#include "sim/dataset/bag_reader.hpp"
#include "sim/dataset/dataset_writer.hpp"
#include "sim/ros2/chunk_prefetcher.hpp"
#include "sim/runner/run_scenario.hpp"
#include "sim/simulation/simulator.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

#include <time.h>
#include <unistd.h>

namespace {

using namespace bimloc::sim;
using Clock = std::chrono::steady_clock;

struct BagBenchArgs {
  std::string scenario = "scenarios/site_office_R101.yaml";
  int repeat = 3;
  bool json = false;
};

// The streams written as a recorder receives them, merged by stamp (received_order), or one
// after the other: odometry, truth, then the clouds (an MCAP writer then puts the odometry in
// chunks of its own).
void writeStreams(const Simulator& sim, const std::vector<LidarScan>& scans, bool received_order, DatasetWriter& writer) {
  const auto& odometry = sim.odometry();
  const auto& truth = sim.groundTruth();
  if (!received_order) {
    for (const auto& o : odometry) writer.addOdometry(o);
    for (const auto& g : truth) writer.addGroundTruth(g);
    for (const auto& s : scans) writer.addScan(s);
    return;
  }
  std::size_t o = 0, g = 0, c = 0;
  while (o < odometry.size() || g < truth.size() || c < scans.size()) {
    const double to = o < odometry.size() ? odometry[o].stamp_s : 1e300;
    const double tg = g < truth.size() ? truth[g].stamp_s : 1e300;
    const double tc = c < scans.size() ? scans[c].stamp_s : 1e300;
    if (to <= tg && to <= tc) writer.addOdometry(odometry[o++]);
    else if (tg <= tc) writer.addGroundTruth(truth[g++]);
    else writer.addScan(scans[c++]);
  }
}

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// BIMLOC_MCAP_PREFETCH set for one read, and put back as it was.
class PrefetchSetting {
 public:
  explicit PrefetchSetting(std::optional<std::size_t> chunks) {
    if (!chunks) return;
    if (const char* v = std::getenv(kName)) previous_ = v;
    ::setenv(kName, std::to_string(*chunks).c_str(), 1);
    set_ = true;
  }
  ~PrefetchSetting() {
    if (!set_) return;
    if (previous_) ::setenv(kName, previous_->c_str(), 1);
    else ::unsetenv(kName);
  }
  PrefetchSetting(const PrefetchSetting&) = delete;
  PrefetchSetting& operator=(const PrefetchSetting&) = delete;

 private:
  static constexpr const char* kName = "BIMLOC_MCAP_PREFETCH";
  std::optional<std::string> previous_;
  bool set_ = false;
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
    std::string name, bag_format, compression, input;  // compression: the MCAP's, or the ROS 1 bag's
    std::size_t chunk_bytes = 4u << 20;
    bool received_order = false;
    std::optional<std::size_t> prefetch;  // chunks read ahead; unset: the default
    int same_bag_as = -1;                 // reads the bag of an earlier format
  };
  constexpr std::size_t kChunk = 4u << 20, kRosbag2Chunk = 768u << 10;  // ours; rosbag2's default
  const std::optional<std::size_t> kDefault;
  const std::vector<Format> formats = {{"ros1", "ros1", "", "dataset.bag", kChunk, false, kDefault, -1},
                                       {"ros1-lz4", "ros1", "lz4", "dataset.bag", kChunk, false, kDefault, -1},
                                       {"ros1-bz2", "ros1", "bz2", "dataset.bag", kChunk, false, kDefault, -1},
                                       {"ros1-lz4-mixed", "ros1", "lz4", "dataset.bag", kChunk, true, kDefault, -1},
                                       {"mcap", "mcap", "zstd", "rosbag2", kChunk, false, kDefault, -1},
                                       {"mcap-1thread", "mcap", "zstd", "rosbag2", kChunk, false, 0, 4},
                                       {"mcap-rosbag2", "mcap", "zstd", "rosbag2", kRosbag2Chunk, true, kDefault, -1},
                                       {"mcap-lz4", "mcap", "lz4", "rosbag2", kChunk, false, kDefault, -1},
                                       {"mcap-none", "mcap", "", "rosbag2", kChunk, false, kDefault, -1},
                                       {"sqlite3", "sqlite3", "", "rosbag2", kChunk, false, kDefault, -1}};
  nlohmann::json rows = nlohmann::json::array();
  bimloc::cli::Table table({"format", "bag [MB]", "chunks", "read [s]", "x ROS 1 (wall)", "CPU [s]", "x ROS 1 (CPU)",
                             "reading thread CPU [s]", "x ROS 1 (thread)", "x ROS 1 alike (CPU)", "x ROS 1 alike (thread)",
                             "points"});
  struct Measured {
    std::string input;
    double wall_s = 1e300, cpu_s = 1e300, thread_cpu_s = 1e300;
    std::size_t points = 0;
  };
  std::vector<Measured> measured(formats.size());
  try {
    for (std::size_t k = 0; k < formats.size(); ++k) {
      const std::string dir = (tmp / formats[k].name).string();
      if (formats[k].same_bag_as >= 0) {
        measured[k].input = measured[static_cast<std::size_t>(formats[k].same_bag_as)].input;
        continue;
      }
      DatasetInfo info;
      info.T_base_lidar = scenario.sensor.T_base_lidar;
      info.bag_format = formats[k].bag_format;
      (formats[k].bag_format == "ros1" ? info.ros1_compression : info.mcap_compression) = formats[k].compression;
      info.mcap_chunk_bytes = formats[k].chunk_bytes;
      DatasetWriter writer(dir, info);
      writeStreams(sim, scans, formats[k].received_order, writer);
      writer.commit();
      measured[k].input = dir + "/" + formats[k].input;
    }
    for (int i = 0; i < std::max(1, args.repeat); ++i)
      for (std::size_t k = 0; k < formats.size(); ++k) {
        Measured& m = measured[k];
        const PrefetchSetting prefetch(formats[k].prefetch);
        const auto t0 = Clock::now();
        const double cpu0 = processCpuSeconds(), thread0 = threadCpuSeconds();
        const BagInput bag(m.input, BagInputOptions{});
        m.points = 0;
        bag.forEachTurn([&](const BagTurn& t) { m.points += t.points().size(); });
        m.cpu_s = std::min(m.cpu_s, processCpuSeconds() - cpu0);
        m.thread_cpu_s = std::min(m.thread_cpu_s, threadCpuSeconds() - thread0);
        m.wall_s = std::min(m.wall_s, std::chrono::duration<double>(Clock::now() - t0).count());
      }
    for (std::size_t k = 0; k < formats.size(); ++k) {
      const Measured& m = measured[k];
      const double cpu_ratio = m.cpu_s / measured[0].cpu_s, wall_ratio = m.wall_s / measured[0].wall_s;
      const double thread_ratio = m.thread_cpu_s / measured[0].thread_cpu_s;
      const double mb = static_cast<double>(bytesOf(m.input)) / 1e6;
      const Format& f = formats[k];
      // rosbag closes a chunk at 768 KiB (its default threshold, which BagWriter keeps).
      const std::size_t chunk_bytes = f.bag_format == "ros1" ? kRosbag2Chunk : f.bag_format == "mcap" ? f.chunk_bytes : 0;
      const std::string chunks = chunk_bytes == 0 ? "" : (f.compression.empty() ? "none" : f.compression) + " " +
                                 std::to_string(chunk_bytes >> 10) + " KiB" + (f.received_order ? ", mixed" : "");
      const std::size_t prefetch = f.bag_format != "mcap" ? 0 : f.prefetch ? *f.prefetch : bimloc::sim::ros2::defaultPrefetchChunks();
      // A compressed ROS 2 form against the ROS 1 bags compressed alike: lz4 against ROS 1's
      // lz4; zstd, which rosbag has not, against both compressions a ROS 1 user can record with.
      nlohmann::json alike = nlohmann::json::array();
      std::string alike_cpu, alike_thread;
      for (std::size_t r = 0; r < formats.size(); ++r) {
        // A mixed ROS 1 bag is the reference of the mixed MCAP form only.
        const bool reference = formats[r].bag_format == "ros1" && !formats[r].compression.empty() &&
                               (!formats[r].received_order || f.received_order);
        if (!reference || f.bag_format != "mcap" || f.compression.empty()) continue;
        if (f.compression != "zstd" && f.compression != formats[r].compression) continue;
        const double cpu = m.cpu_s / measured[r].cpu_s, thread = m.thread_cpu_s / measured[r].thread_cpu_s;
        alike.push_back({{"against", formats[r].name}, {"ratio", cpu}, {"thread_ratio", thread},
                         {"wall_ratio", m.wall_s / measured[r].wall_s}});
        const std::string sep = alike_cpu.empty() ? "" : ", ";
        const std::string against = formats[r].name.substr(5);  // "lz4", "bz2", "lz4-mixed"
        alike_cpu += sep + against + " " + bimloc::cli::fixed(cpu, 2);
        alike_thread += sep + against + " " + bimloc::cli::fixed(thread, 2);
      }
      rows.push_back({{"format", f.name}, {"bag_format", f.bag_format}, {"compression", f.compression}, {"chunk_bytes", chunk_bytes},
                      {"topics_interleaved", f.received_order}, {"prefetch_chunks", prefetch}, {"bag_bytes", bytesOf(m.input)},
                      {"read_seconds", m.wall_s}, {"wall_ratio_to_ros1", wall_ratio}, {"read_cpu_seconds", m.cpu_s},
                      {"ratio_to_ros1", cpu_ratio}, {"reading_thread_cpu_seconds", m.thread_cpu_s},
                      {"thread_ratio_to_ros1", thread_ratio}, {"against_ros1_compressed_alike", alike}, {"points", m.points},
                      {"turns", scans.size()}});
      using bimloc::cli::fixed;
      table.add({f.name, fixed(mb, 1), chunks, fixed(m.wall_s, 3), fixed(wall_ratio, 2), fixed(m.cpu_s, 3), fixed(cpu_ratio, 2),
                 fixed(m.thread_cpu_s, 3), fixed(thread_ratio, 2), alike_cpu, alike_thread, std::to_string(m.points)});
    }
  } catch (...) {
    std::filesystem::remove_all(tmp);
    throw;
  }
  std::filesystem::remove_all(tmp);
  if (args.json) {
    std::cout << nlohmann::json{{"scenario", args.scenario}, {"repeat", args.repeat}, {"formats", rows}}.dump() << "\n";
  } else {
    std::cout << args.scenario << ": " << scans.size() << " turns, best of " << args.repeat << " (wall and CPU each)\n\n";
    table.print(std::cout);
  }
}

}  // namespace

void addBenchBagsCommand(CLI::App& bench) {
  auto args = std::make_shared<BagBenchArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "bags", "Reading one run as a ROS 1 bag and as ROS 2 bags (localize's input layer, every cloud decoded), the reads "
              "taking turns: wall seconds, CPU seconds and the reading thread's CPU seconds (the critical path, with "
              "the MCAP chunks decompressed on worker threads), each with its ratio to the ROS 1 bag's in the same run. MCAP: zstd "
              "chunks of 4 MiB as simulate writes them (mcap; mcap-1thread: the same file read with BIMLOC_MCAP_PREFETCH=0, "
              "no chunk decompressed ahead on a worker thread), as ros2 bag record writes them by default (mcap-rosbag2: zstd, "
              "768 KiB, the topics interleaved), lz4 (mcap-lz4) and uncompressed (mcap-none); and SQLite3. ROS 1 also with "
              "lz4 and bz2 chunks (ros1-lz4, ros1-bz2: rosbag record --lz4 / --bz2; ros1-lz4-mixed: the topics interleaved "
              "as recorded): each compressed MCAP form is also compared with the ROS 1 bags compressed alike (lz4 with lz4; "
              "zstd, which ROS 1 has not, with both; the mixed MCAP also with the mixed ROS 1 bag).");
  cmd->add_option("scenario", args->scenario, "scenario file")->capture_default_str();
  cmd->add_option("--repeat", args->repeat, "reads of each bag; the best is kept")->capture_default_str()->check(CLI::Range(1, 100));
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args] { run(*args); });
}
