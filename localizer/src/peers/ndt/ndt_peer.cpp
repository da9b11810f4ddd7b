// The HDL-style NDT peer: hdl_global_localization's branch-and-bound finds the pose, then
// hdl_localization's scan-to-map NDT tracks it with odometry as the prediction (its UKF left
// out: legged odometry predicts well enough between registrations). Convergence by its own
// criterion: the search's hit fraction and margin, then the NDT fitness from that pose; when
// the fitness stays bad for lost_after_bad_scans registrations, the search runs again.
#include "peers/ndt/branch_and_bound.hpp"
#include "peers/ndt/map_cloud.hpp"
#include "peers/ndt/ndt_tracker.hpp"
#include "peers/peer.hpp"
#include "planes/plane_steps.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <cmath>
#include <deque>
#include <optional>
#include <limits>
#include <sstream>

namespace bimloc::peers {
namespace {

// The slices of the registered turns while searching, stitched by odometry.
struct Keyframe {
  PlanarPose odom;  // the base in the odom frame
  Cloud2 slice;     // base frame (level)
  double travel_m;  // odometry distance travelled up to this turn
};

class NdtPeer : public PeerLocalizer {
 public:
  NdtPeer(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const NdtConfig& config)
      : c_(config), T_base_lidar_(T_base_lidar), floor_z_(storey.elevation_m),
        lidar_z_(T_base_lidar.translation().z()), map_(sampleMesh(storey.mesh, config.map_spacing_m)), tracker_(map_, config) {
    const double band_z = floor_z_ + c_.base_height_m + lidar_z_;
    const Cloud2 map_slice = sliceBand(map_, band_z + c_.scan_min_z_m, band_z + c_.scan_max_z_m);
    grid_ = OccupancyGrid::fromPoints(map_slice, c_.grid_resolution_m, c_.distinct_m + c_.grid_resolution_m);
    pyramid_ = std::make_unique<GridPyramid>(grid_, c_.pyramid_levels);
    std::ostringstream band;
    band << "z " << band_z + c_.scan_min_z_m << " to " << band_z + c_.scan_max_z_m << " m";
    if (!(c_.scan_min_z_m < c_.scan_max_z_m)) {
      warnings_.push_back("ndt: scan_min_z_m must be below scan_max_z_m (the slice is empty): it cannot localize");
    } else if (!tracker_.ready()) {
      warnings_.push_back("ndt: storey '" + storey.name + "' has no mesh to sample the map from: it cannot localize");
    } else if (grid_.occupiedCount() == 0) {
      warnings_.push_back("ndt: storey '" + storey.name + "' has no obstacle in the map slice (" + band.str() +
                          "): the global search has nothing to match; it cannot localize");
    }
    usable_ = warnings_.empty();
    search_.grid = &grid_;
    search_.pyramid = pyramid_.get();
  }

  bool wantsPoints(const Eigen::Isometry3d& T_odom_base) const override {
    if (!usable_) return false;
    if (!last_update_) return true;
    const PlanarPose d = between(*last_update_, planarPose(T_odom_base));
    return d.head<2>().norm() >= c_.update_min_d_m || std::abs(d.z()) >= c_.update_min_a_rad;
  }

  PeerStep step(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>* points_lidar) override {
    PeerStep s;
    s.report.method = "ndt";
    s.warnings = std::move(warnings_);
    warnings_.clear();
    const PlanarPose odom = planarPose(T_odom_base);
    if (last_odom_) travel_m_ += between(*last_odom_, odom).head<2>().norm();
    last_odom_ = odom;
    if (usable_ && points_lidar) {
      last_update_ = odom;
      s.report.updated = true;
      const Cloud3 scan = cleanScan(*points_lidar, s.warnings);
      if (converged_)
        track(T_odom_base, scan, s);
      else
        search(stamp_s, T_odom_base, *points_lidar, scan, s);
    }
    describe(T_odom_base, s);
    return s;
  }

 private:
  // Finite points within max_range_m, on hdl_localization's voxel grid, at most ndt_max_points.
  Cloud3 cleanScan(const std::vector<Eigen::Vector3f>& points, std::vector<std::string>& warnings) {
    const Cloud3 valid = planes::detail::validPoints(points, 0.0, c_.max_range_m);
    std::size_t nonfinite = 0;
    for (const auto& p : points) nonfinite += !p.allFinite();
    if (nonfinite && !warned_nonfinite_) {
      warnings.push_back("ndt: " + std::to_string(nonfinite) + " non-finite scan points dropped (warned once)");
      warned_nonfinite_ = true;
    }
    Cloud3 down = planes::detail::voxelDownsample(valid, c_.downsample_m);
    if (static_cast<int>(down.size()) <= c_.ndt_max_points) return down;
    const std::size_t stride = (down.size() + c_.ndt_max_points - 1) / c_.ndt_max_points;
    Cloud3 kept;
    for (std::size_t i = 0; i < down.size(); i += stride) kept.push_back(down[i]);
    return kept;
  }

  // The scan's slice: the points in the band about the lidar's height, in the level base frame
  // (the odometry's roll and pitch taken out), as xy.
  Cloud2 scanSlice(const std::vector<Eigen::Vector3f>& points, const Eigen::Isometry3d& T_odom_base) const {
    Eigen::Isometry3d T_level_lidar = Eigen::Isometry3d::Identity();
    T_level_lidar.linear() = tiltOf(T_odom_base.linear());
    T_level_lidar = T_level_lidar * T_base_lidar_;
    const Eigen::Isometry3f T = T_level_lidar.cast<float>();
    const float max2 = static_cast<float>(c_.max_range_m * c_.max_range_m);
    Cloud3 level;
    level.reserve(points.size() / 8);
    for (const auto& p : points) {
      if (!p.allFinite() || p.squaredNorm() > max2) continue;
      const Eigen::Vector3f q = T * p;
      level.emplace_back(q.x(), q.y(), q.z() - static_cast<float>(lidar_z_));
    }
    return sliceBand(level, c_.scan_min_z_m, c_.scan_max_z_m);
  }

  void search(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>& points, const Cloud3& scan,
              PeerStep& s) {
    const PlanarPose odom = planarPose(T_odom_base);
    Cloud2 slice = scanSlice(points, T_odom_base);
    if (slice.empty() && !warned_empty_band_) {
      std::ostringstream w;
      w << "ndt: a scan has no point in the band " << c_.scan_min_z_m << " to " << c_.scan_max_z_m
        << " m about the lidar: nothing for the global search (warned once)";
      s.warnings.push_back(w.str());
      warned_empty_band_ = true;
    }
    window_.push_back({odom, std::move(slice), travel_m_});
    while (window_.size() > 1 && travel_m_ - window_.front().travel_m > c_.global_window_m) window_.pop_front();
    if (stamp_s - last_search_s_ < c_.global_period_s) return;
    // The window's slices in the current base frame.
    Cloud2 stitched;
    double far = 0;
    for (const Keyframe& k : window_) {
      const PlanarPose rel = between(odom, k.odom);
      const double cr = std::cos(rel.z()), sr = std::sin(rel.z());
      for (const auto& p : k.slice) {
        const Eigen::Vector2f q(static_cast<float>(cr * p.x() - sr * p.y() + rel.x()), static_cast<float>(sr * p.x() + cr * p.y() + rel.y()));
        stitched.push_back(q);
        far = std::max(far, static_cast<double>(q.norm()));
      }
    }
    const Cloud2 cells = scanCells(stitched, c_.grid_resolution_m);
    if (static_cast<int>(cells.size()) < c_.min_scan_cells) return;
    last_search_s_ = stamp_s;
    search_.yaw_count = yawCount(c_.grid_resolution_m, std::min(far, c_.max_range_m));
    const SearchResult best = branchAndBound(search_, cells);
    if (best.best.score < 0) return;
    const Exclusion near{best.best, c_.distinct_m, c_.distinct_deg * M_PI / 180.0};
    const SearchResult second = branchAndBound(search_, cells, &near);
    const double n = static_cast<double>(cells.size());
    hit_fraction_ = best.best.score / n;
    margin_fraction_ = (best.best.score - std::max(0, second.best.score)) / n;
    // The best guess so far, carried by odometry until the next search.
    const Eigen::Vector3d p = search_.pose(best.best);
    const Eigen::Isometry3d T_map_base = levelPose({p.x(), p.y(), p.z()}, floor_z_ + c_.base_height_m, T_odom_base);
    guess_T_map_odom_ = T_map_base * T_odom_base.inverse();
    if (hit_fraction_ < c_.min_hit_fraction || margin_fraction_ < c_.min_margin_fraction) return;
    // Then NDT from the search's pose decides.
    const NdtAlignment a = tracker_.align(scan, T_map_base * T_base_lidar_);
    fitness_m2_ = a.fitness_m2;
    if (!a.good) return;
    T_map_odom_ = flatten(a.T_map_lidar * T_base_lidar_.inverse(), T_odom_base) * T_odom_base.inverse();
    converged_ = had_converged_ = true;
    bad_scans_ = 0;
    window_.clear();
  }

  void track(const Eigen::Isometry3d& T_odom_base, const Cloud3& scan, PeerStep& s) {
    (void)s;
    const Eigen::Isometry3d predicted = T_map_odom_ * T_odom_base;
    const NdtAlignment a = tracker_.align(scan, predicted * T_base_lidar_);
    fitness_m2_ = a.fitness_m2;
    if (a.good) {
      // Only a good registration moves the estimate; a bad one leaves odometry's prediction.
      T_map_odom_ = flatten(a.T_map_lidar * T_base_lidar_.inverse(), T_odom_base) * T_odom_base.inverse();
      bad_scans_ = 0;
      return;
    }
    if (++bad_scans_ < c_.lost_after_bad_scans) return;
    converged_ = false;  // relocalize: the global search runs again from the next turn
    guess_T_map_odom_ = T_map_odom_;
    bad_scans_ = 0;
    last_search_s_ = -std::numeric_limits<double>::infinity();
  }

  // The pose at (x, y, yaw) with base height z and the odometry's roll and pitch.
  static Eigen::Isometry3d levelPose(const PlanarPose& p, double z, const Eigen::Isometry3d& T_odom_base) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(p.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix() * tiltOf(T_odom_base.linear());
    T.translation() = Eigen::Vector3d(p.x(), p.y(), z);
    return T;
  }

  // NDT's x, y, yaw and height with the odometry's roll and pitch: map <- odom then corrects the
  // plane only (the bench and the localizer are planar).
  static Eigen::Isometry3d flatten(const Eigen::Isometry3d& T_map_base, const Eigen::Isometry3d& T_odom_base) {
    return levelPose(planarPose(T_map_base), T_map_base.translation().z(), T_odom_base);
  }

  void describe(const Eigen::Isometry3d& T_odom_base, PeerStep& s) const {
    s.report.converged = converged_;
    s.report.relocalizing = had_converged_ && !converged_;
    s.report.score = fitness_m2_;
    s.report.hit_fraction = hit_fraction_;
    s.report.margin_fraction = margin_fraction_;
    if (converged_) {
      s.T_map_base = T_map_odom_ * T_odom_base;
      // PCL's NDT gives no covariance: a stand-in from the fitness (its rms distance in x and y,
      // and that distance seen at 5 m for the heading), documented as such.
      const double v = std::max(fitness_m2_, 1e-4);
      s.covariance = Eigen::Vector3d(v, v, v / 25.0).asDiagonal();
    } else {
      s.T_map_base = guess_T_map_odom_ ? *guess_T_map_odom_ * T_odom_base : T_odom_base;
      // Not localized: as wide as the map, any heading.
      const double half = 0.5 * std::max(grid_.width, grid_.height) * grid_.resolution_m;
      s.covariance = Eigen::Vector3d(half * half, half * half, M_PI * M_PI).asDiagonal();
    }
  }

  NdtConfig c_;
  Eigen::Isometry3d T_base_lidar_;
  double floor_z_, lidar_z_;
  Cloud3 map_;
  NdtTracker tracker_;
  OccupancyGrid grid_;
  std::unique_ptr<GridPyramid> pyramid_;
  SearchGrid search_;
  bool usable_ = false;
  std::vector<std::string> warnings_;  // the construction's, given with the first step
  bool warned_nonfinite_ = false, warned_empty_band_ = false;

  std::optional<PlanarPose> last_update_, last_odom_;
  double travel_m_ = 0;
  std::deque<Keyframe> window_;
  double last_search_s_ = -std::numeric_limits<double>::infinity();
  double hit_fraction_ = 0, margin_fraction_ = 0, fitness_m2_ = 0;

  bool converged_ = false, had_converged_ = false;
  int bad_scans_ = 0;
  Eigen::Isometry3d T_map_odom_ = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Isometry3d> guess_T_map_odom_;
};

}  // namespace

std::unique_ptr<PeerLocalizer> makeNdt(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const NdtConfig& config,
                                       std::uint64_t seed) {
  (void)seed;  // nothing random: the map is a lattice, the search exhaustive in effect, NDT deterministic
  return std::make_unique<NdtPeer>(storey, T_base_lidar, config);
}

}  // namespace bimloc::peers
