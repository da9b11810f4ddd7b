// The paper's observations: planes from one scan by sequential RANSAC, as S-Graphs extracts
// them (voxel grid, then SACMODEL_PLANE by RANSAC, the inliers removed, again), with three
// additions for walls: a plane keeps only its largest connected run of inliers; it is refitted
// by trimmed least squares on the raw returns (voxel centroids that straddle two surfaces lie
// on neither); and planes are sorted into walls (vertical) and floor/ceiling (horizontal).
#include "plane_steps.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>

namespace bimloc::planes {
namespace {

// Gap along a wall that separates two walls: five voxels. A doorway (0.8 m and up) or a room
// between two coplanar walls is wider; the sparse returns of a wall seen through a doorway
// or far along a corridor are not.
constexpr double kSupportGapVoxels = 5.0;
// A plane passing this close to the sensor is seen edge-on: what lies in its band are the
// lidar's own scan lines (the +-1 degree rings on nearby walls make a "plane" at sensor
// height), not a surface.
constexpr double kMinPlaneDistance_m = 0.1;
// Two planes within this angle (and the RANSAC band in d) are one plane.
const double kSamePlaneCos = std::cos(2.0 * M_PI / 180.0);
// RANSAC attempts per accepted plane: rejected candidates (slanted, too short, fragments) cost
// an attempt each, and this bounds the work on scans full of them.
constexpr int kAttemptsPerPlane = 3;
// The standing stage's attempts draw from their own seeds (xor'ed into the user's).
constexpr std::uint64_t kStandingSeed = 0x5747414E44494E47ull;

// Every RANSAC attempt gets its own seed from the user's seed and the attempt's number
// (splitmix64), so that attempts do not repeat one another's samples and all is reproducible.
std::uint32_t attemptSeed(std::uint64_t seed, int attempt) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * std::uint64_t(attempt + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return static_cast<std::uint32_t>((z ^ (z >> 31)) >> 32);
}

// The voxels a surface needs at horizontal range `range_m` (PlaneExtractionConfig::
// ring_spacing_deg): min_inliers near the sensor, the same area farther.
double ringGap(const PlaneExtractionConfig& c, double range_m) {
  return c.ring_spacing_deg > 0 ? range_m * std::tan(c.ring_spacing_deg * M_PI / 180.0) : 0.0;
}
std::size_t requiredSupport(const PlaneExtractionConfig& c, double range_m) {
  const double n = std::max(c.min_inliers, 3);
  const double gap = ringGap(c, range_m);
  const double scale = gap > c.voxel_size_m && c.voxel_size_m > 0 ? c.voxel_size_m / gap : 1.0;
  return std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(n * scale)));
}
double horizontalRange(const detail::Cloud& cloud, const detail::Indices& voxels) {
  if (voxels.empty()) return 0.0;
  double x = 0, y = 0;
  for (const int i : voxels) x += cloud[i].x(), y += cloud[i].y();
  return std::hypot(x, y) / double(voxels.size());
}

detail::Indices without(const detail::Indices& pool, const detail::Indices& removed) {
  detail::Indices rest;
  rest.reserve(pool.size());
  std::set_difference(pool.begin(), pool.end(), removed.begin(), removed.end(), std::back_inserter(rest));
  return rest;
}

// The wall (or floor) behind one RANSAC candidate, and its plane:
// 1. the candidate's largest run along the wall;
// 2. trimmed least squares on it, and the run again from the pool's voxels in the band of that
//    plane: RANSAC's plane through three points may be a few degrees off, its band then cuts
//    across the wall and holds only a part of it;
// 3. trimmed least squares on the raw returns near that plane (for a wall, only those along the
//    run, not its coplanar neighbours'), where each return lies on one surface, unlike the
//    voxel centroids that straddle an edge.
// The raw returns give the plane; the voxels give the evidence (count, extents, covariance),
// as RANSAC counted it.
struct Support {
  detail::PlaneFit fit;
  detail::Indices run;     // pool voxels of the wall's stretch of the band
  detail::Indices voxels;  // those of them on the surface (in the band the returns ended in)
};
Support findSupport(const detail::Cloud& voxels, const detail::Cloud& raw, const detail::PackedCloud& raw_packed,
                    const detail::Indices& pool,
                    const detail::RansacPlane& candidate, bool wall, double threshold_m, double voxel_m) {
  const double gap_m = kSupportGapVoxels * voxel_m;
  Support s;
  if (wall) {
    const auto runs = detail::runsAlong(voxels, candidate.inliers, detail::planeHorizontal(candidate.normal), gap_m);
    s.run = *detail::largestRun(runs);  // the candidate has inliers, so at least one run
  } else {
    s.run = candidate.inliers;
  }
  detail::RefinedPlane coarse = detail::refinePlane(voxels, s.run, 0.5 * threshold_m);
  const detail::Indices band = detail::withinBand(voxels, pool, coarse.fit, threshold_m);
  if (!wall) {
    if (!band.empty()) s.run = band;
  } else {
    const auto runs = detail::runsAlong(voxels, band, detail::planeHorizontal(coarse.fit.normal), gap_m);
    if (const detail::Indices* same = detail::runOverlapping(runs, s.run)) s.run = *same;
  }
  coarse = detail::refinePlane(voxels, s.run, 0.5 * threshold_m);

  const Eigen::Vector3d along = detail::planeHorizontal(coarse.fit.normal);
  double lo = INFINITY, hi = -INFINITY;
  for (const int i : coarse.core) {
    const double u = along.dot(voxels[i].cast<double>());
    lo = std::min(lo, u), hi = std::max(hi, u);
  }
  const detail::Indices near =
      detail::pointsNearPlane(raw, raw_packed, coarse.fit, threshold_m, wall ? &along : nullptr, lo - voxel_m, hi + voxel_m);
  const detail::RefinedPlane fine = near.size() >= 3 ? detail::refinePlane(raw, near, 0.5 * threshold_m) : coarse;
  s.fit = fine.fit;
  // Voxel centroids are no noisier than the returns they average: the returns' band holds them.
  s.voxels = detail::withinBand(voxels, s.run, fine.fit, std::max(fine.band_m, coarse.band_m));
  return s;
}

}  // namespace

PlaneExtraction extractPlanes(const std::vector<Eigen::Vector3f>& points_sensor, const PlaneExtractionConfig& config) {
  PlaneExtraction result;
  result.input_points = points_sensor.size();
  const detail::Cloud raw = detail::validPoints(points_sensor, config.min_range_m, config.max_range_m);
  result.valid_points = raw.size();
  const detail::Cloud cloud = detail::voxelDownsample(raw, config.voxel_size_m);
  const detail::PackedCloud raw_packed(raw);  // every candidate's band test reads every return

  const std::size_t min_inliers = std::size_t(std::max(config.min_inliers, 3));
  const std::size_t fewest = requiredSupport(config, config.max_range_m);  // a plane's support at the farthest range
  const double sin_vertical = std::sin(config.vertical_tolerance_deg * M_PI / 180.0);
  const double cos_horizontal = std::cos(config.horizontal_tolerance_deg * M_PI / 180.0);
  const double voxel_m = std::max(config.voxel_size_m, config.distance_threshold_m);

  detail::Indices pool(cloud.size());
  std::iota(pool.begin(), pool.end(), 0);
  int accepted = 0;

  // One candidate of either stage: its support, the plane, accepted or not, and what leaves
  // which pool. `walls_pool`, while the standing stage runs, is that stage's pool, and `pool`
  // the whole scan's, from which an accepted wall's band is removed too.
  auto take = [&](const detail::RansacPlane& candidate, detail::Indices& search, detail::Indices* also,
                  bool walls_allowed) {
    // Walls: one run along the wall. Floor and ceiling are kept whole: a storey has one of
    // each, and a floor's scan rings are metres apart, so any gap would cut it up.
    const bool wall_band = std::abs(candidate.normal.z()) < sin_vertical;
    // The support comes from every voxel still free (`also`, the whole scan's pool, in the
    // standing stage), not only the standing ones the candidate was drawn from: the standing
    // test chooses where walls are searched, not what a wall's band holds, so a wall found
    // either way has the same support (its foot's strip of floor included, as RANSAC counts it).
    const Support support = findSupport(cloud, raw, raw_packed, also ? *also : search, candidate, wall_band,
                                        config.distance_threshold_m, voxel_m);
    ObservedPlane plane = detail::describePlane(cloud, support.voxels, support.fit);
    const double nz = std::abs(plane.normal.z());
    plane.vertical = nz < sin_vertical;
    const bool horizontal = nz > cos_horizontal;
    const bool surface = plane.d >= kMinPlaneDistance_m && ((plane.vertical && walls_allowed) || horizontal);
    // A wall's support judged by its area at its range: fewer voxels than min_inliers where
    // the rings are apart, spanning two of them (floors and ceilings keep the count).
    const bool by_area_only = support.voxels.size() < min_inliers;
    const auto byArea = [&] {  // its range only where the count is short of min_inliers
      const double range_m = horizontalRange(cloud, support.voxels);
      return support.voxels.size() >= requiredSupport(config, range_m) && plane.height_extent_m >= 0.5 * ringGap(config, range_m);
    };
    const bool enough = !by_area_only || (plane.vertical && byArea());
    const bool large = enough && plane.extent_m >= config.min_extent_m;
    // What the area rule is for: walls the scan shows that a count would drop. A small far
    // piece in the plane of a wall already found (a corridor's side wall beyond a doorway) is
    // not such a wall: it leaves the pool, as a too small run does, and costs the filter no
    // observation (each is matched by every particle, and paired for the seeds).
    const bool piece_of_found = by_area_only && plane.vertical &&
                                std::any_of(result.walls.begin(), result.walls.end(), [&](const ObservedPlane& w) {
                                  return w.normal.dot(plane.normal) > kSamePlaneCos &&
                                         std::abs(w.d - plane.d) < config.distance_threshold_m;
                                });
    if (surface && large && !piece_of_found) {
      (plane.vertical ? result.walls : result.horizontals).push_back(plane);
      ++accepted;
      // The run's voxels in the full band of the final plane are this plane's; the other
      // inliers may belong to other walls.
      const detail::Indices band = detail::withinBand(cloud, support.run, support.fit, config.distance_threshold_m);
      search = without(search, band);
      if (also) *also = without(*also, band);
    } else if (surface) {
      // Too small a run (or a piece of a wall found): the band's other runs may still be walls (a wall close by, of few
      // voxels, beside a farther piece of more), so only this run leaves the pool.
      search = without(search, support.run);
    } else {
      // Slanted, or scan lines: no run of this band is a wall or a floor.
      search = without(search, candidate.inliers);
    }
  };

  // Stage 1 (standing_height_m > 0): the walls, by vertical-plane RANSAC on the voxels of x-y
  // columns whose returns span standing_height_m (standing.cpp). Stage 2 then finds only the
  // horizontals, in what is left.
  const bool standing_stage = config.standing_height_m > 0;
  if (standing_stage) {
    detail::Indices standing = detail::standingVoxels(cloud, raw, voxel_m, config.standing_height_m);
    const double radius_m = std::max(config.min_extent_m, 2 * voxel_m);
    for (int attempt = 0; accepted < config.max_planes && attempt < kAttemptsPerPlane * config.max_planes &&
                          standing.size() >= fewest;
         ++attempt) {
      const auto candidate = detail::ransacVerticalPlane(cloud, standing, config.ransac_iterations,
                                                         config.distance_threshold_m, radius_m,
                                                         attemptSeed(config.seed ^ kStandingSeed, attempt));
      if (!candidate || candidate->inliers.size() < fewest) break;
      take(*candidate, standing, &pool, true);
    }
  }
  for (int attempt = 0; accepted < config.max_planes && attempt < kAttemptsPerPlane * config.max_planes &&
                        pool.size() >= fewest;
       ++attempt) {
    const auto candidate = detail::ransacPlane(cloud, pool, config.ransac_iterations, config.distance_threshold_m,
                                               attemptSeed(config.seed, attempt));
    // No plane left worth having: the largest RANSAC found is too small at any range. One too
    // small at its own range (near clutter) leaves the pool (take), and a far wall may follow.
    if (!candidate || candidate->inliers.size() < fewest) break;
    take(*candidate, pool, nullptr, !standing_stage);
  }
  return result;
}

}  // namespace bimloc::planes
