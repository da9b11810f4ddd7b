// bimloc localize INPUT --plan PLAN [--storey S|auto] [--method ...] [--config FILE.yaml] [--json] [--out DIR]
//   INPUT: a dataset folder of `bimloc simulate`, or a ROS 1 bag (recorded on a robot, or the
//   dataset.bag of `simulate`), or a ROS 2 bag (a rosbag2 folder, an .mcap or .db3 file; the
//   rosbag2/ of `simulate --format mcap|sqlite3`): [--cloud-topic T] [--odom-topic T] [--odom-frame F]
//   [--base-frame F] [--mount x,y,z,roll,pitch,yaw] [--truth-topic T] [--no-deskew]
// The same localizer as `bimloc run`, offline, on a recording; one loop for both kinds
// (sim/runner/localize_recording.hpp).
#include "sim/cli/commands.hpp"
#include "sim/common/printable.hpp"
#include "sim/cli/localize_output.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/cli/table.hpp"
#include "sim/dataset/bag_reader.hpp"
#include "sim/dataset/deskew.hpp"
#include "sim/ros2/rosbag2_reader.hpp"
#include "sim/runner/localize_recording.hpp"
#include "sim/world/world.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace {

using namespace bimloc::sim;

struct LocalizeArgs {
  std::string input;
  std::string plan;
  std::string storey;
  std::string method = "sgraph";
  std::string config;
  std::string out;
  std::uint64_t seed = 0;
  bool json = false;
  BagInputOptions bag;
  std::string mount;
  bool no_deskew = false;
  // The VLP-16's 100 m, and 0.3 m: its ROS driver drops ranges below 0.4 m, but a range is
  // measured from each laser's own origin, a few cm off the sensor's centre (sim/lidar/vlp16.cpp
  // places them so too), so real points lie down to ~0.36 m from the centre; none nearer than 0.3 m.
  SensorRange range{0.3, 100.0};
};

// "x,y,z,roll,pitch,yaw" (metres, radians; R = Rz(yaw) Ry(pitch) Rx(roll), as ROS's RPY).
Eigen::Isometry3d parseMount(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(x))
      throw std::runtime_error("--mount: '" + item + "' is not a number (expected x,y,z,roll,pitch,yaw in m and rad)");
    v.push_back(x);
  }
  if (v.size() != 6) throw std::runtime_error("--mount: expected 6 numbers x,y,z,roll,pitch,yaw (m, rad), got " + std::to_string(v.size()));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return T;
}

// What the loop needs of a recording, whichever its kind.
struct Recording {
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();
  std::string storey;  // as recorded, may be empty
  std::vector<StampedPose> ground_truth;
  double start_s = 0;
  TurnSource turns;
  std::string input_bag;  // the bag, for localized.bag
  std::vector<std::string> notes;  // where the odometry and mount came from
  RecordingChecks checks;          // the odometry's and the truth's (the scans' are counted by the loop)
  // Keeps what `turns` reads from alive.
  std::shared_ptr<RecordedDataset> dataset;
  std::shared_ptr<BagInput> bag;
  std::size_t bag_warnings_said = 0;  // at open; more may come as the messages are read
  bool deskewed = false;  // the turns are de-skewed (a per-point time field, no --no-deskew)
};

Recording openDataset(const std::string& dir, const SensorRange& range) {
  Recording rec;
  rec.dataset = std::make_shared<RecordedDataset>(readDataset(dir));
  const RecordedDataset& data = *rec.dataset;
  rec.T_base_lidar = data.T_base_lidar;
  rec.storey = data.storey;
  rec.ground_truth = data.ground_truth;
  rec.start_s = data.scans.front().stamp_s;
  // The TUM reader drops (and counts) the samples that are no pose, as the bag readers do.
  rec.checks.odometry = data.odometry_drops;
  rec.checks.ground_truth = data.ground_truth_drops;
  rec.checks.odometry_jumps = findJumps(data.odometry);
  rec.turns = [d = rec.dataset, range](const std::function<void(const RecordedTurn&)>& visit) {
    for (const auto& scan : d->scans) {
      RecordedTurn turn;
      turn.stamp_s = scan.stamp_s + 0.5 * d->turn_period_s;  // mid-turn, as the runner
      turn.T_odom_base = interpolatePose(d->odometry, turn.stamp_s);  // as the bag path: samples straddle the middle
      // Read and checked now, as the bag's scans: one with no usable point is skipped.
      auto points = std::make_shared<std::vector<Eigen::Vector3f>>(readPcdPoints(scan.file));
      turn.drops = keepUsablePoints(*points, nullptr, range);
      turn.points = [points] { return *points; };
      turn.name = scan.file;
      visit(turn);
    }
  };
  return rec;
}

// Said once a run: whether the turns are de-skewed, and from which per-point time.
std::string deskewNote(const BagInput& bag, const BagInputOptions& options) {
  if (!bag.timed())
    return "de-skew: off (the clouds on " + options.cloud_topic +
           " have no per-point time field: time, t, offset_time, time_stamp or timestamp)";
  if (!options.deskew) return "de-skew: off (--no-deskew)";
  if (bag.packets()) return "de-skew: on (per-point time from the VLP-16's packets on " + options.cloud_topic + ")";
  return "de-skew: on (per-point time from the field '" + bag.timeField() + "')";
}

Recording openBag(const std::string& path, const BagInputOptions& options) {
  Recording rec;
  rec.bag = std::make_shared<BagInput>(path, options);
  const BagInput& bag = *rec.bag;
  rec.T_base_lidar = bag.T_base_lidar();
  rec.ground_truth = bag.groundTruth();
  rec.checks.odometry = bag.odometryDrops();
  rec.checks.odometry_jumps = findJumps(bag.odometry());
  rec.checks.ground_truth = bag.groundTruthDrops();
  rec.input_bag = path;
  rec.deskewed = bag.timed() && options.deskew;
  const auto warnings = bag.warnings();
  for (const auto& w : warnings) std::cerr << "warning: " << printable(w) << "\n";  // names read from the bag: any bytes
  rec.bag_warnings_said = warnings.size();
  rec.notes = {"odometry: " + bag.odometrySource(), "mount: " + bag.mountSource(),
               deskewNote(bag, options)};
  rec.turns = [b = rec.bag](const std::function<void(const RecordedTurn&)>& visit) {
    b->forEachTurn([&](const BagTurn& t) {
      RecordedTurn turn;
      turn.stamp_s = t.stamp_s;
      // Interpolated at the turn's middle, the instant its points are de-skewed to.
      turn.T_odom_base = interpolatePose(b->odometry(), t.stamp_s);
      turn.points = t.points;
      turn.name = b->path() + ": message " + std::to_string(t.index);
      turn.drops = t.drops;
      turn.warnings = t.warnings;
      visit(turn);
    });
  };
  rec.start_s = bag.firstTurnStamp() - 0.5 * bag.turnPeriod();
  return rec;
}

void run(const LocalizeArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  // A dataset folder has metadata.json; a rosbag2 folder metadata.yaml and its storage files.
  const bool is_dataset = std::filesystem::is_directory(args.input) && std::filesystem::exists(args.input + "/metadata.json");
  const bool is_ros2 = !is_dataset && bimloc::sim::ros2::isRosbag2(args.input);
  const bool is_bag = is_ros2 || (!std::filesystem::is_directory(args.input) && isRosBag(args.input));
  if (!is_bag && !std::filesystem::is_directory(args.input) && std::filesystem::exists(args.input) &&
      args.input.size() > 4 && args.input.substr(args.input.size() - 4) == ".bag")
    throw std::runtime_error(args.input + ": not a ROS1 bag (no '#ROSBAG V2.0' at its start)");
  BagInputOptions bag_options = args.bag;
  if (!args.mount.empty()) bag_options.mount = parseMount(args.mount);
  bag_options.deskew = !args.no_deskew;
  bag_options.range = args.range;
  if (!(args.range.min_m >= 0 && args.range.max_m > args.range.min_m))
    throw std::runtime_error("--min-range and --max-range: expected 0 <= min < max, got " + std::to_string(args.range.min_m) +
                             " and " + std::to_string(args.range.max_m));
  Recording rec = is_bag ? openBag(args.input, bag_options) : openDataset(args.input, args.range);
  const bimloc::bim::Building building = bimloc::bim::readIfc(args.plan, {});
  const bool storey_auto = args.storey == "auto";
  // The true storey, for scoring: as recorded (with auto, the localizer is not told it).
  const std::string storey_name =
      !args.storey.empty() && !storey_auto ? args.storey : (rec.storey.empty() ? "0" : rec.storey);
  const bimloc::bim::Storey* storey = building.findStorey(storey_name);
  if (!storey) throw std::runtime_error(building.storeyLookupError(storey_name));  // it names the plan
  const auto truth_storey = static_cast<std::size_t>(storey - building.storeys.data());

  LocalizerSettings settings = args.config.empty() ? LocalizerSettings{} : loadLocalizerConfig(args.config);
  bimloc::LocalizerConfig config = settings.config;
  if (!args.method.empty()) config.method = *bimloc::methodFromString(args.method);
  config.seed = args.seed;
  config.points_deskewed = rec.deskewed;  // the free space then leaves the turns' skew out
  config.storey = storey_auto || settings.storey_auto ? std::string() : storeyKey(building, truth_storey);
  bimloc::Localizer localizer(building, rec.T_base_lidar, config);
  ScenarioResult r;
  r.name = args.input, r.plan = args.plan, r.storey = storey->name, r.method = bimloc::toString(config.method), r.seed = args.seed;
  r.storey_auto = config.storey.empty();
  r.start_room = "(unknown)";

  std::unique_ptr<bimloc::cli::LocalizeOutput> output;
  if (!args.out.empty()) {
    bimloc::cli::LocalizeOutputFrames frames;
    frames.odom = args.bag.odom_frame, frames.base = args.bag.base_frame, frames.tf_topic = args.bag.tf_topic;
    output = std::make_unique<bimloc::cli::LocalizeOutput>(args.out, rec.input_bag, frames, building, localizer);
  }
  TurnObserver observe;
  if (output)
    observe = [&](const RecordedTurn& turn, const bimloc::LocalizationResult& step) {
      std::optional<Eigen::Isometry3d> truth;
      if (!rec.ground_truth.empty()) truth = interpolatePose(rec.ground_truth, turn.stamp_s);  // as the scorer
      output->step(turn, step, truth);
    };
  RecordingRun recording =
      localizeRecording(building, truth_storey, localizer, rec.T_base_lidar, rec.turns, rec.start_s, rec.ground_truth, r, observe);
  r = std::move(recording.result);
  // The loop counted the scans; the odometry's and the truth's counts are the reader's.
  r.recording->odometry = rec.checks.odometry;
  r.recording->odometry_jumps = rec.checks.odometry_jumps;
  r.recording->ground_truth = rec.checks.ground_truth;
  std::vector<std::string> dropped = r.recording->warnings();
  // What the bag's reader found only as it read the messages (a compressed ROS 1 chunk's size field).
  if (rec.bag) {
    const auto found = rec.bag->warnings();
    dropped.insert(dropped.end(), found.begin() + static_cast<std::ptrdiff_t>(std::min(rec.bag_warnings_said, found.size())), found.end());
  }
  for (auto& w : dropped) w = printable(w);  // for the JSON too: names read from the recording may be any bytes
  r.warnings.insert(r.warnings.begin(), dropped.begin(), dropped.end());
  for (const auto& w : dropped) std::cerr << "bimloc localize: warning: " << args.input << ": " << w << "\n";
  const auto& last = recording.last;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto report = bimloc::cli::runReport({r}, r.wall_seconds);
  if (output) output->commit(report, r);
  if (args.json) {
    std::cout << report.dump() << "\n";
  } else {
    bimloc::cli::printRunTable({r}, report, std::cout);
    for (const auto& note : rec.notes) std::cout << note << "\n";
    // Not localized: the places the recording still fits (a symmetric room has more than one).
    if (!r.hypotheses.empty()) {
      std::cout << "places still possible (best first):\n";
      for (const auto& p : r.hypotheses)
        std::cout << "  x " << p.x << " y " << p.y << " yaw " << p.yaw_deg << " deg, room " << p.room << ", relative weight "
                  << p.relative_weight << "\n";
    }
    if (last && last->T_map_odom) {
      const Eigen::Isometry3d& T = *last->T_map_odom;
      const Eigen::Quaterniond q(T.linear());
      // Fixed decimals (1 mm, 1e-5 of the quaternion: the TUM file has them all), no "-0" for a
      // rounding error's sign, within the tables' width.
      const auto at = [](double v, int decimals) {
        const double unit = std::pow(10.0, -decimals);
        return bimloc::cli::fixed(std::abs(v) < 0.5 * unit ? 0.0 : v, decimals);
      };
      const Eigen::Vector3d t = T.translation();
      std::cout << bimloc::cli::wrapText("map <- odom (" + std::string(bimloc::toString(last->state)) + "): xyz " + at(t.x(), 3) + " " +
                                             at(t.y(), 3) + " " + at(t.z(), 3) + ", quaternion xyzw " + at(q.x(), 5) + " " +
                                             at(q.y(), 5) + " " + at(q.z(), 5) + " " + at(q.w(), 5),
                                         bimloc::cli::kTableColumns);
    }
    if (rec.ground_truth.empty())
      std::cout << (is_bag ? "(no " + args.bag.truth_topic + " in the bag: errors not evaluated)\n"
                           : std::string("(no ground_truth.tum: errors not evaluated)\n"));
    if (output)
      std::cout << "wrote " << args.out << "/ (trajectory.tum" << (is_ros2 ? ", localized.mcap" : is_bag ? ", localized.bag" : "")
                << ", report.json, snapshots/)\n";
  }
  // As `run`: a run that did not localize, or localized falsely, fails (docs/exit_codes.md).
  if (!r.passed) throw bimloc::cli::ExitCode{bimloc::cli::kExitNotLocalized};
}

}  // namespace

void addLocalizeCommand(CLI::App& app) {
  auto args = std::make_shared<LocalizeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "localize",
      "Run the localizer offline on a recording against a plan: global localization, then map <- odom. The\n"
      "recording is a dataset folder in the form `bimloc simulate` writes (clouds/*.pcd with clouds/index.csv,\n"
      "odometry.tum, metadata.json with the mount; ground_truth.tum if known) or a ROS 1 or ROS 2 bag (a rosbag2\n"
      "folder, an .mcap or a .db3 file; sensor_msgs/PointCloud2 of a Velodyne driver; nav_msgs/Odometry or /tf\n"
      "odom -> base_link; the mount on /tf_static or --mount).\n"
      "Scored like `bimloc run` when ground truth is present. Points no lidar can have measured (not finite, at the\n"
      "origin, outside --min-range..--max-range), scans with none left, odometry samples that are no pose and\n"
      "odometry jumps are dropped or flagged, and counted in warnings and the summary (docs/recording_checks.md).\n"
      "Exit status (docs/exit_codes.md): 0 localized; 1 ran and did not localize (or localized falsely);\n"
      "2 the input cannot be used (a damaged or unusable recording, bad options): an error names it, nothing is written.");
  cmd->add_option("input", args->input, "dataset folder, ROS 1 .bag, or ROS 2 bag (rosbag2 folder, .mcap, .db3)")->required();
  cmd->add_option("--plan", args->plan, "IFC plan")->required();
  cmd->add_option("--storey", args->storey,
                  std::string(bimloc::cli::kStoreyHelp) + " (default: as recorded, else 0); auto: not told, every storey with walls and rooms "
                  "is a candidate (scored against the recorded storey)");
  cmd->add_option("--method", args->method,
                  bimloc::cli::kMethodHelp)
      ->check(bimloc::cli::methodCheck())
      ->capture_default_str();
  cmd->add_option("--config", args->config, "YAML file of localizer settings (the keys of a scenario's `localizer:`)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--seed", args->seed, "seed of the filter")->capture_default_str();
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->add_option("--out", args->out,
                  "write trajectory.tum (map <- base_link), localized.bag (ROS 1 input: + /tf map -> odom, /localization) or "
                  "localized.mcap (ROS 2 input: the same + the plan on /bimloc/plan), "
                  "report.json and snapshots/ into this folder, all or nothing");
  auto* bag = cmd->add_option_group("bag input", "for a ROS 1 or ROS 2 bag");
  bag->add_option("--cloud-topic", args->bag.cloud_topic,
                  "sensor_msgs/PointCloud2 with fields x, y, z (a per-point time field: de-skew; see docs/sensors.md), "
                  "or velodyne_msgs/VelodyneScan, the VLP-16's raw packets (decoded, de-skewed per firing)")
      ->capture_default_str();
  bag->add_option("--odom-topic", args->bag.odom_topic,
                  "nav_msgs/Odometry; when absent (and not given), /tf ODOM_FRAME -> BASE_FRAME is the odometry")
      ->capture_default_str()
      ->each([args](const std::string&) { args->bag.odom_topic_given = true; });
  bag->add_option("--odom-frame", args->bag.odom_frame, "odometry frame (REP 105)")->capture_default_str();
  bag->add_option("--base-frame", args->bag.base_frame, "robot frame: the localized pose is of it")->capture_default_str();
  bag->add_option("--mount", args->mount,
                  "lidar mount base_frame -> cloud frame as x,y,z,roll,pitch,yaw (m, rad); default: from /tf_static or /tf");
  bag->add_option("--truth-topic", args->bag.truth_topic, "nav_msgs/Odometry or geometry_msgs/PoseStamped ground truth in map, scored when present")
      ->capture_default_str();
  bag->add_flag("--no-deskew", args->no_deskew, "use the clouds as they are, even with a per-point time field");
  cmd->add_option("--min-range", args->range.min_m, "metres from the sensor's centre: nearer points are no measurement (dropped, counted); a VLP-16's")
      ->capture_default_str();
  cmd->add_option("--max-range", args->range.max_m, "metres from the sensor's centre: farther points are no measurement (dropped, counted); a VLP-16's")
      ->capture_default_str();
  cmd->callback([args] { run(*args); });
}
