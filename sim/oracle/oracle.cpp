#include "sim/oracle/oracle.hpp"

#include "sim/oracle/first_crossing.hpp"
#include "sim/oracle/place_search.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <unordered_set>

namespace bimloc::sim::oracle {
namespace {

// The points of keyframes [0, count) in the first keyframe's base frame, in a fixed shuffled
// order: a bound that stops early stops sooner when a few points of every keyframe come first.
PathCloud pathOf(const std::vector<Keyframe>& keyframes, std::size_t count) {
  PathCloud path;
  const Eigen::Vector3d o = keyframes.front().odom;
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Vector3d& p = keyframes[k].odom;
    // The keyframe's odometry relative to the first keyframe's.
    const double c0 = std::cos(o.z()), s0 = std::sin(o.z());
    const double dx = c0 * (p.x() - o.x()) + s0 * (p.y() - o.y()), dy = -s0 * (p.x() - o.x()) + c0 * (p.y() - o.y());
    const double yaw = p.z() - o.z(), c = std::cos(yaw), s = std::sin(yaw);
    for (const auto& q : keyframes[k].points)
      path.add(static_cast<float>(c * q.x() - s * q.y() + dx), static_cast<float>(s * q.x() + c * q.y() + dy));
  }
  std::uint64_t state = 0x9E3779B97F4A7C15ull;  // splitmix64: the same order on every platform
  const auto next = [&state] {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  for (std::size_t i = path.size(); i > 1; --i) {
    const std::size_t j = next() % i;
    std::swap(path.x[i - 1], path.x[j]), std::swap(path.y[i - 1], path.y[j]), std::swap(path.r[i - 1], path.r[j]);
  }
  path.finish();
  return path;
}

}  // namespace

std::vector<Eigen::Vector2f> bandPoints(const std::vector<Eigen::Vector3f>& lidar_points, const Eigen::Isometry3d& T_base_lidar,
                                        double z_low_base, double z_high_base, const OracleConfig& config) {
  const Eigen::Isometry3f T = T_base_lidar.cast<float>();
  std::unordered_set<std::uint64_t> taken;
  std::vector<Eigen::Vector2f> out;
  for (const auto& p : lidar_points) {
    if (!p.allFinite()) continue;
    const float range = p.norm();
    if (range < config.min_range_m || range > config.max_range_m) continue;
    const Eigen::Vector3f b = T * p;
    if (b.z() < z_low_base || b.z() > z_high_base) continue;
    const auto vx = static_cast<std::int64_t>(std::floor(b.x() / config.voxel_m)) + (1 << 20);
    const auto vy = static_cast<std::int64_t>(std::floor(b.y() / config.voxel_m)) + (1 << 20);
    if (taken.insert(static_cast<std::uint64_t>(vx) << 32 | static_cast<std::uint64_t>(vy)).second) out.emplace_back(b.x(), b.y());
  }
  const auto cap = static_cast<std::size_t>(config.max_points_per_scan);
  if (out.size() > cap) {  // every k-th, spread over the turn
    std::vector<Eigen::Vector2f> kept;
    for (std::size_t i = 0; i < cap; ++i) kept.push_back(out[i * out.size() / cap]);
    out = std::move(kept);
  }
  return out;
}

KeyframeRecorder::KeyframeRecorder(const OracleConfig& config, const Eigen::Isometry3d& T_base_lidar, double base_above_floor_m)
    : config_(config), T_base_lidar_(T_base_lidar), z_low_(config.band_low_m - base_above_floor_m),
      z_high_(config.band_high_m - base_above_floor_m) {}

void KeyframeRecorder::add(double time_s, const Eigen::Isometry3d& T_odom_base,
                           const std::function<std::vector<Eigen::Vector3f>()>& points) {
  const Eigen::Vector3d odom = planarPose(T_odom_base);
  if (!keyframes_.empty()) {
    const Eigen::Vector3d& last = keyframes_.back().odom;
    if ((odom.head<2>() - last.head<2>()).norm() < config_.keyframe_m &&
        std::abs(wrapAngle(odom.z() - last.z())) < config_.keyframe_deg * M_PI / 180.0)
      return;
  }
  keyframes_.push_back({time_s, odom, bandPoints(points(), T_base_lidar_, z_low_, z_high_, config_)});
}

double decisionThreshold(double free_area_m2, const OracleConfig& c, double* places) {
  // A place: a disc of the false-convergence radius and a heading span of twice its angle.
  const double per_place_m2 = M_PI * c.place_radius_m * c.place_radius_m;
  const double headings = 360.0 / (2.0 * c.place_deg);
  const double m = std::max(1.0, free_area_m2 / per_place_m2 * headings);
  if (places) *places = m;
  return std::log(m / c.alpha);
}

namespace {

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

bim::Storey withEveryWall(const bim::Building& building, std::size_t storey) {
  bim::Storey out;
  const bim::Storey& own = building.storeys.at(storey);
  out.id = own.id, out.name = own.name, out.elevation_m = own.elevation_m, out.rooms = own.rooms, out.walls = own.walls;
  for (std::size_t s = 0; s < building.storeys.size(); ++s)
    if (s != storey) out.walls.insert(out.walls.end(), building.storeys[s].walls.begin(), building.storeys[s].walls.end());
  return out;
}

OracleVerdict decideWhen(const bim::Storey& storey, double floor_z, const std::vector<Keyframe>& keyframes,
                         const Eigen::Vector3d& truth_start, const OracleConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = threadCpuSeconds();
  std::vector<int> wall_of;
  const std::vector<Segment2> walls = wallSegmentsInBand(storey, floor_z + config.band_low_m, floor_z + config.band_high_m, &wall_of);
  OracleVerdict verdict = decideOnWalls(walls, wall_of, keyframes, truth_start, config);
  // The walls' cut counts in the plain answer's cost, as it always did.
  verdict.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - verdict.robust_seconds;
  verdict.cpu_seconds = threadCpuSeconds() - cpu_start - verdict.robust_cpu_seconds;
  return verdict;
}

OracleVerdict decideOnWalls(const std::vector<Segment2>& walls, const std::vector<int>& wall_of, const std::vector<Keyframe>& keyframes,
                            const Eigen::Vector3d& truth_start, const OracleConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = threadCpuSeconds();
  OracleVerdict verdict;
  verdict.keyframes = static_cast<int>(keyframes.size());
  const DistanceField field(walls, config.raster_m, config.clamp_m, config.margin_m);
  const PointModel model(config, config.clamp_m);
  const Lattice lattice(field, config);
  verdict.threshold = decisionThreshold(lattice.free_area_m2, config, &verdict.rival_places);
  const TruthZone zone{truth_start, config.place_radius_m, config.place_deg * M_PI / 180.0};
  // The truth's place scored on the same grid: its best cell, or the true start itself; its
  // score Q and the start that gives it.
  struct Truth {
    float q;
    Eigen::Vector3d pose;
  };
  // Kept per keyframe: the robust answer's first check is at the plain answer's keyframe, the
  // run's last keyframe may be checked twice, and the truth's search is a pure function of the
  // path up to k (h28oracle3: searching it again was half of the oracle's time). Its nodes and
  // cells count where it is searched.
  std::map<std::size_t, Truth> truths;
  const auto truthOf = [&](std::size_t k, const SearchContext& context, std::size_t* nodes, std::size_t* cells) {
    if (const auto known = truths.find(k); known != truths.end()) return known->second;
    const SearchAnswer truth = searchPlaces(context, Region::Truth, -std::numeric_limits<float>::infinity(), false);
    const float at_start = pathScore(field, model, context.path, truth_start.x(), truth_start.y(), truth_start.z());
    *nodes += truth.nodes, *cells += truth.cells;
    return truths[k] = truth.best >= at_start ? Truth{truth.best, truth.pose} : Truth{at_start, truth_start};
  };
  // Whether the scans up to keyframe k rule every rival out.
  const auto ruledOut = [&](std::size_t k) {
    const PathCloud path = pathOf(keyframes, k + 1);
    const SearchContext context{field, model, path, lattice, zone};
    const float q = truthOf(k, context, &verdict.nodes, &verdict.cells).q;
    const SearchAnswer rival = searchPlaces(context, Region::Rivals, q - static_cast<float>(verdict.threshold), true);
    ++verdict.checks;
    verdict.nodes += rival.nodes, verdict.cells += rival.cells;
    return !rival.reached;
  };
  const auto stride = static_cast<std::size_t>(std::max(1, config.check_every));
  const std::optional<std::size_t> first = firstCrossing(keyframes.size(), 0, stride, ruledOut);
  // With every scan of the run, whether they rule the truth out: some rival above it by the
  // threshold (a rival that reaches it reaches the lower bar too, so no other search is needed).
  if (!keyframes.empty()) {
    const std::size_t last = keyframes.size() - 1;
    const PathCloud path = pathOf(keyframes, last + 1);
    const SearchContext context{field, model, path, lattice, zone};
    const float q = truthOf(last, context, &verdict.nodes, &verdict.cells).q;
    const SearchAnswer above = searchPlaces(context, Region::Rivals, q + static_cast<float>(verdict.threshold), true);
    verdict.nodes += above.nodes, verdict.cells += above.cells;
    verdict.truth_ruled_out = above.reached;
    verdict.points = path.size();
  }
  if (first) verdict.decidable_at_s = keyframes[*first].time_s;
  verdict.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  verdict.cpu_seconds = threadCpuSeconds() - cpu_start;
  if (!config.robust || !first) return verdict;

  // The robust answer: the same test with each rival's robust value (one wall's points dropped
  // from both sums, sim/oracle/deviation.hpp), whose groups follow the truth's best start.
  const auto robust_start = std::chrono::steady_clock::now();
  const double robust_cpu_start = threadCpuSeconds();
  const WallLabels labels(field, wall_of);
  const auto ruledOutRobustly = [&](std::size_t k) {
    const PathCloud path = pathOf(keyframes, k + 1);
    const SearchContext plain{field, model, path, lattice, zone};
    const Truth truth = truthOf(k, plain, &verdict.robust_nodes, &verdict.robust_cells);
    const Discount discount = discountOf(labels, field, model, path, truth.pose);
    const SearchContext context{field, model, path, lattice, zone, &discount};
    const SearchAnswer rival = searchPlaces(context, Region::Rivals, truth.q - static_cast<float>(verdict.threshold), true);
    ++verdict.robust_checks;
    verdict.robust_nodes += rival.nodes, verdict.robust_cells += rival.cells;
    return !rival.reached;
  };
  // A rival ruled out robustly is ruled out (its robust value is at least its score), so every
  // keyframe before decidable_at_s, where some rival was not, fails robustly too.
  const std::optional<std::size_t> robust = firstCrossing(keyframes.size(), *first, stride, ruledOutRobustly);
  if (robust) verdict.decidable_robust_at_s = keyframes[*robust].time_s;
  verdict.robust_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - robust_start).count();
  verdict.robust_cpu_seconds = threadCpuSeconds() - robust_cpu_start;
  return verdict;
}

}  // namespace bimloc::sim::oracle
