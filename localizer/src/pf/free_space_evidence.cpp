#include "free_space_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::pf::detail {
namespace {

// Within this of a face's end, a crossing is a corner: the plan's faces meet there only to
// within its drawing, and a ray may slip between two of them or stop on either.
constexpr double kFreeSpaceCornerM = 0.15;
// Within this of an opening's edge, a crossing is the opening's frame: the plan's openings are
// drawn to within centimetres, a ray is a few centimetres wide at range, and a door leaf stands
// in the frame. No verdict, as at a corner.
constexpr double kFreeSpaceOpeningMarginM = 0.1;
// Where along a face a ray crosses it is uncertain by the pose over |cos| of the incidence, up to
// this (the corner and frame margins).
constexpr double kFreeSpaceMinCos = 0.3;
constexpr double kFreeSpaceRegionM = 2.0;

}  // namespace

FreeSpaceParams FreeSpaceParams::of(const ParticleFilterConfig& c, double drift_m) {
  FreeSpaceParams p;
  p.sigma_m = std::sqrt(c.free_space_sigma_m * c.free_space_sigma_m + drift_m * drift_m);
  p.gate_sigmas = c.free_space_gate_sigmas;
  // A place's heading is fitted on the window's planes, each known to sigma_azimuth: a few
  // dozen of them pin it to about sigma_azimuth / 5 (5 deg -> 1 deg).
  // And the odometry's heading drift over half the window moves it as much again.
  const double fitted = c.sigma_azimuth_deg / 5.0 * M_PI / 180.0;
  const double drift = c.evidence_yaw_drift_rad_per_m * 0.5 * c.evidence_window_m;
  p.sigma_yaw_rad = std::hypot(fitted, drift);
  p.face_worth = 0.5 * (c.gate_mahalanobis2 - 3.0);
  p.support_rays = std::max(1, c.free_space_support_rays);
  p.open_m = c.free_space_open_m;
  p.open_wall_faces = c.free_space_open_wall_faces;
  p.open_faces = c.free_space_open_faces;
  p.explained = c.free_space_explained;
  // A surface seen in a doorway of X is X's leaf, shut, with the site's probability of a shut
  // door: that is the likelihood ratio against X of all the doorway's rays together (one leaf,
  // one event), never more than a face (a wall in its place would be worth no more).
  p.door_worth = std::min(p.face_worth, -std::log(std::max(1e-6, c.free_space_door_shut_probability)));
  return p;
}

double throughCost(double beyond_m, double sigma_m, double cap) {
  if (!(beyond_m > 0.0) || !(cap > 0.0)) return 0.0;
  const double z = beyond_m / sigma_m;
  // The better of the ray's two explanations at the place (a generalized likelihood ratio):
  // its wall stands and the ray overshot it by noise, exp(-z^2 / 2), or the wall is not there
  // for this ray (not built, clutter), w = exp(-cap). The mixture's sum of the two,
  // -log((1 - w) exp(-z^2 / 2) + w), only tends to cap: a wall whose every ray went far through
  // it was worth a hair under one face, and two such walls, the bar's two faces, never reached
  // it (school_25622 R009: 8.3398 against 8.34 for 15 s, the planes tied).
  return std::min(cap, 0.5 * z * z);
}

FreeSpaceMap::FreeSpaceMap(const bim::Storey& storey, double cell_m) : cell_m_(cell_m) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t w = 0; w < storey.walls.size(); ++w) {
    const bim::Wall& wall = storey.walls[w];
    for (const auto& f : wall.faces) {
      Face face;
      face.start = f.start.head<2>();
      const Eigen::Vector2d along = f.end.head<2>() - face.start;
      face.length_m = along.norm();
      if (!(face.length_m > 1e-6) || !along.allFinite()) continue;
      face.direction = along / face.length_m;
      face.normal = Eigen::Vector2d(-face.direction.y(), face.direction.x());
      const bool bounded = wall.height_m > 0.0 && std::isfinite(f.start.z());
      face.z_bottom = bounded ? f.start.z() : -std::numeric_limits<double>::infinity();
      face.z_top = bounded ? f.start.z() + wall.height_m : std::numeric_limits<double>::infinity();
      face.openings = &f.openings;
      face.wall = static_cast<int>(w);
      lo = lo.cwiseMin(face.start).cwiseMin(f.end.head<2>());
      hi = hi.cwiseMax(face.start).cwiseMax(f.end.head<2>());
      faces_.push_back(face);
    }
  }
  if (faces_.empty()) return;
  origin_ = lo - Eigen::Vector2d::Constant(cell_m_);
  nx_ = static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_m_)) + 2;
  ny_ = static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_m_)) + 2;
  cells_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), {});
  for (std::size_t i = 0; i < faces_.size(); ++i) {
    // Every cell the segment passes through, sampled at a quarter cell (and its ends' cells).
    const Face& f = faces_[i];
    const int steps = static_cast<int>(std::ceil(f.length_m / (0.25 * cell_m_))) + 1;
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector2d p = f.start + f.direction * (f.length_m * s / steps);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          // The neighbours too when the point is within a few centimetres of their edge.
          const Eigen::Vector2d q = p + 0.05 * Eigen::Vector2d(dx, dy);
          const int ix = static_cast<int>(std::floor((q.x() - origin_.x()) / cell_m_));
          const int iy = static_cast<int>(std::floor((q.y() - origin_.y()) / cell_m_));
          if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) continue;
          auto& cell = cells_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix)];
          if (cell.empty() || cell.back() != i) cell.push_back(static_cast<std::uint32_t>(i));
        }
    }
  }
  for (auto& cell : cells_) {
    std::sort(cell.begin(), cell.end());
    cell.erase(std::unique(cell.begin(), cell.end()), cell.end());
  }
}

int FreeSpaceMap::regionKey(const Eigen::Vector2d& p) const {
  const int ix = static_cast<int>(std::floor(p.x() / kFreeSpaceRegionM)) & 0x3fff;
  const int iy = static_cast<int>(std::floor(p.y() / kFreeSpaceRegionM)) & 0x3fff;
  return (iy << 14) | ix;
}

std::optional<FreeSpaceMap::Crossing> FreeSpaceMap::firstCrossing(const Eigen::Vector2d& o, const Eigen::Vector2d& u, double z0,
                                                                  double dz_per_m, double max_t, double lateral_per_m,
                                                                  double position_sigma_m, std::vector<std::uint32_t>* scratch) const {
  std::optional<Crossing> best;
  if (faces_.empty() || !(max_t > 0.0)) return best;
  // Amanatides-Woo traversal of the cells along the ray; a crossing found in a cell may lie in
  // a later one (faces span cells), so the walk stops once the cells begin beyond it.
  double gx = (o.x() - origin_.x()) / cell_m_, gy = (o.y() - origin_.y()) / cell_m_;
  int ix = static_cast<int>(std::floor(gx)), iy = static_cast<int>(std::floor(gy));
  const int sx = u.x() > 0 ? 1 : -1, sy = u.y() > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double ddx = u.x() != 0.0 ? cell_m_ / std::abs(u.x()) : inf, ddy = u.y() != 0.0 ? cell_m_ / std::abs(u.y()) : inf;
  double tx = u.x() != 0.0 ? ((sx > 0 ? (ix + 1 - gx) : (gx - ix)) * cell_m_) / std::abs(u.x()) : inf;
  double ty = u.y() != 0.0 ? ((sy > 0 ? (iy + 1 - gy) : (gy - iy)) * cell_m_) / std::abs(u.y()) : inf;
  double t_cell = 0.0;  // where the current cell begins along the ray
  std::vector<std::uint32_t> own;
  std::vector<std::uint32_t>& tried = scratch ? *scratch : own;
  tried.clear();
  while (t_cell <= max_t && (!best || t_cell <= best->t)) {
    if (ix >= 0 && iy >= 0 && ix < nx_ && iy < ny_) {
      for (const std::uint32_t i : cells_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix)]) {
        if (std::find(tried.begin(), tried.end(), i) != tried.end()) continue;
        tried.push_back(i);
        const Face& f = faces_[i];
        double t = 0, s = 0;
        if (!f.meets(o, u, t, s)) continue;  // parallel: the ray runs along it
        if (!(t > 1e-6) || t > max_t || (best && t >= best->t)) continue;
        // Where along the face the ray crosses is known to the place's pose: its heading moves
        // the ray t sigma_yaw sideways, which is that over cos(incidence) along the face; its
        // position moves the crossing by sigma_pos along the face and, across it, by sigma_pos
        // tan(incidence) along it (a ray at 17 deg to a wall, from a robot in its doorway,
        // crosses 3 cm off the plan 10 cm farther along). A crossing within 2 sigma of a face's
        // end or an opening's edge could as well have missed the face or passed through the
        // hole: no verdict.
        // Both over cos(incidence): sigma_pos sqrt(1 + tan^2) is sigma_pos / cos.
        const double cos_incidence = std::abs(u.dot(f.normal));
        const double along_sigma = std::hypot(lateral_per_m * t, position_sigma_m) / std::max(kFreeSpaceMinCos, cos_incidence);
        const double corner_m = std::max(kFreeSpaceCornerM, 2.0 * along_sigma);
        const double frame_m = std::max(kFreeSpaceOpeningMarginM, 2.0 * along_sigma);
        if (s < -corner_m || s > f.length_m + corner_m) continue;
        const double z = z0 + dz_per_m * t;
        if (z < f.z_bottom || z > f.z_top) continue;  // above or below the wall's body
        bool corner = s < corner_m || s > f.length_m - corner_m;
        // Through a door or a window: no wall there. (A rectangle of no width lies inside any
        // set of holes, even none: a centimetre.)
        if (!corner && f.openings && bim::insideOpening(*f.openings, s - 0.01, s + 0.01, z - 0.01, z + 0.01, 0.0)) continue;
        // Near a hole: within frame_m of it along the face (the heading's sideways slip),
        // within the drawing's margin in height.
        if (f.openings)
          for (const auto& hole : *f.openings)
            corner |= s >= hole.along_min_m - frame_m && s <= hole.along_max_m + frame_m && z >= hole.z_min_m - kFreeSpaceOpeningMarginM &&
                      z <= hole.z_max_m + kFreeSpaceOpeningMarginM;  // at its frame: a jamb or the hole, no verdict
        Crossing c;
        c.t = t, c.wall = f.wall, c.cos_incidence = cos_incidence, c.uncertain = corner;
        best = c;
      }
    }
    if (tx < ty) {
      t_cell = tx, tx += ddx, ix += sx;
    } else {
      t_cell = ty, ty += ddy, iy += sy;
    }
    if (!std::isfinite(t_cell)) break;
  }
  return best;
}

std::vector<FreeSpaceHit> freeSpaceHits(const FreeSpaceMap& map, const FreeSpaceParams& params, const Eigen::Vector3d& pose, double z_base,
                                        const RangeProfile& profile) {
  std::vector<FreeSpaceHit> hits;
  const double c = std::cos(pose.z()), s = std::sin(pose.z());
  const auto toMap = [&](double x, double y) { return Eigen::Vector2d(pose.x() + c * x - s * y, pose.y() + s * x + c * y); };
  const Eigen::Vector2d o = toMap(profile.origin_base.x(), profile.origin_base.y());
  const double z0 = z_base + profile.origin_base.z();
  // This turn's own skew (range_profile.hpp) adds to the place's uncertainty, as a sigma: a
  // bound taken for a sigma is the safe side of a uniform error's (bound / sqrt 3).
  const double sigma_yaw = std::hypot(params.sigma_yaw_rad, profile.skew_yaw_rad);
  const double sigma_m = std::hypot(params.sigma_m, profile.skew_m);
  std::vector<std::uint32_t> tried;  // firstCrossing's, reused ray after ray
  for (std::size_t ray = 0; ray < profile.ends_base.size(); ++ray) {
    const Eigen::Vector3f& e = profile.ends_base[ray];
    const auto index = static_cast<std::int32_t>(ray);
    const Eigen::Vector2d end = toMap(e.x(), e.y());
    const Eigen::Vector2d v = end - o;
    const double r = v.norm();
    if (!(r > 1e-3)) continue;
    const Eigen::Vector2d u = v / r;
    const double dz = (z_base + e.z() - z0) / r;
    const auto x = map.firstCrossing(o, u, z0, dz, r + params.open_m, sigma_yaw, sigma_m, &tried);
    if (!x) {
      // Nothing solid along the ray up to open_m past its end: it ended in the place's open ...
      const double reach = params.gate_sigmas * sigma_m / kFreeSpaceMinCos;
      const auto pass = map.openingPass(o, u, z0, dz, r, reach, &tried);
      const bool in_opening =
          pass && std::abs(r - pass->t) <= params.gate_sigmas * sigma_m / std::max(kFreeSpaceMinCos, pass->cos_incidence);
      // ... unless it ended in one of the place's own openings at its frame: within the gate of
      // the opening's face and, along it, within the margin of a jamb or of the head where a
      // crossing gets no verdict (firstCrossing). There the plan has the wall's body, the
      // opening's reveal and frame, which its two faces do not draw: no evidence. Counted as
      // open, the true place paid a quarter face for each doorway whose jamb its rays grazed, up
      // to the open term's whole face: on a corridor of doorways (random_residential_25546) the
      // truth paid that face at every weighing, and its margin over its 180-degree twin stayed a
      // hair under the bar. A ray that ended inside the hole (a leaf, a pane) stays open.
      if (in_opening && !params.explained) {
        const double along_sigma = std::hypot(sigma_yaw * pass->t, sigma_m) / std::max(kFreeSpaceMinCos, pass->cos_incidence);
        const double frame_m = std::max(kFreeSpaceOpeningMarginM, 2.0 * along_sigma);
        if (pass->edge_m <= frame_m || pass->head_m <= kFreeSpaceOpeningMarginM) continue;
      }
      hits.push_back({kOpenKeyBase + map.regionKey(end), static_cast<float>(params.open_wall_faces * params.face_worth), index});
      // With explained rays, a ray that ended in the place's opening is marked with it (within
      // the gate, as a ray on a wall): a pane or a door leaf stopped it there, which another
      // place's wall explains no better (freeSpaceCostGiven).
      if (in_opening && params.explained)
        hits.push_back({(pass->doorway ? kInDoorwayBase : kInWindowBase) + pass->wall, 0.0f, index});
      continue;
    }
    // Only the first solid wall counts, not every wall the ray went on through: walls in one
    // line of sight are taken to be missing together (a part of the site not built yet), one
    // deviation. Counting each (a ray through two walls as two missing walls) decided Jesse.1
    // and the construction sets sooner but made the truth pay for every missing wall behind a
    // missing wall: on the heavy site (20 % of the walls missing) it added false convergences
    // (docs/results/2026-11-30-session39.md).
    if (x->uncertain) continue;
    // The range along the ray is uncertain by the range noise over the incidence, and by the
    // place's heading: a candidate fitted on a few scans is known to sigma_yaw, which moves the
    // ray sideways by r sigma_yaw at the wall and so along it by that times tan(incidence). At
    // grazing incidence on a wall far away that is metres: a ray that ended on the hall's far
    // corner must not count as through the side wall beside it (random hall, 1 deg off).
    // Exactly, not to first order: the ray meets the face at the angle a (sin a = |cos| of the
    // incidence), from h = t sin a off the face's line; turned away from the face by the gate's
    // heading g sigma_yaw it crosses at h / sin(a - g sigma_yaw), and at a <= g sigma_yaw it may
    // run parallel to the face and never cross it: no verdict. Likewise the place's position
    // across the face moves the crossing by sigma_m / sin a, unbounded at grazing. (A floor of
    // |cos| 0.3 on both, as before, made the truth's rays down a 50 m school corridor, 3.6 deg
    // to its side walls, pay a wall each: 1.3 deg of heading moves a crossing from 10.7 to 16.7 m.)
    const double sin_a = x->cos_incidence, g = params.gate_sigmas;
    const double a = std::asin(std::min(1.0, sin_a)), tilt = g * sigma_yaw;
    if (!(a > tilt)) continue;
    const double lateral = x->t * (sin_a / std::sin(a - tilt) - 1.0) / g;  // one sigma's worth of the gate's slip
    const double sigma = std::hypot(sigma_m / sin_a, lateral);
    const double beyond = r - x->t;
    if (beyond > params.gate_sigmas * sigma)
      hits.push_back({x->wall, static_cast<float>(throughCost(beyond, sigma, params.face_worth)), index});
    else if (params.explained && beyond >= -params.gate_sigmas * sigma)
      hits.push_back({kOnWallBase + x->wall, 0.0f, index});
  }
  return hits;
}

namespace {

bool byKey(const FreeSpaceHit& a, const FreeSpaceHit& b) { return a.key < b.key; }

// Per ray of one scan's `hits`, the key of its mark in [lo, hi), less `offset` (-1: no mark).
void marksByRay(const std::vector<FreeSpaceHit>& hits, std::int32_t lo, std::int32_t hi, std::int32_t offset,
                std::vector<std::int32_t>& by_ray) {
  by_ray.clear();
  for (const auto& h : hits)
    if (h.key >= lo && h.key < hi && h.ray >= 0) {
      const auto ray = static_cast<std::size_t>(h.ray);
      if (by_ray.size() <= ray) by_ray.resize(ray + 1, -1);
      by_ray[ray] = h.key - offset;
    }
}

std::int32_t markOf(const std::vector<std::int32_t>& by_ray, std::int32_t ray) {
  return ray >= 0 && static_cast<std::size_t>(ray) < by_ray.size() ? by_ray[static_cast<std::size_t>(ray)] : -1;
}

// Per key of `all` (sorted by key) the mean cost of its rays times the support ramp; the open
// keys add up to at most open_faces faces, the others (through; on-wall marks cost nothing) add up.
double penaltyOf(const std::vector<FreeSpaceHit>& all, const FreeSpaceParams& params) {
  double through = 0, open = 0;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    double sum = 0;
    for (; j < all.size() && all[j].key == all[i].key; ++j) sum += all[j].cost;
    const double n = static_cast<double>(j - i);
    // At most one face, exactly: the costs are stored as floats, and float(4.17) is not 4.17.
    const double worth = std::min(params.face_worth, sum / n) * std::min(1.0, n / static_cast<double>(params.support_rays));
    (all[i].key >= kOpenKeyBase && all[i].key < kOnWallBase ? open : through) += worth;
    i = j;
  }
  return through + std::min(open, params.open_faces * params.face_worth);
}

}  // namespace

double freeSpacePenalty(const std::vector<const std::vector<FreeSpaceHit>*>& per_scan, const FreeSpaceParams& params) {
  std::vector<FreeSpaceHit> all;
  for (const auto* scan : per_scan)
    if (scan) all.insert(all.end(), scan->begin(), scan->end());
  std::sort(all.begin(), all.end(), byKey);
  return penaltyOf(all, params);
}

FreeSpaceCost freeSpaceCostGiven(const std::vector<const std::vector<FreeSpaceHit>*>& x, const std::vector<const std::vector<FreeSpaceHit>*>& y,
                                 const FreeSpaceParams& params, const std::vector<double>& counted) {
  std::vector<FreeSpaceHit> all;
  std::vector<std::int32_t> on_wall, in_opening;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!x[k]) continue;
    marksByRay(*x[k], kInDoorwayBase, kDoorExplainedBase, 0, in_opening);  // X's rays in its own openings
    if (k < y.size() && y[k])
      marksByRay(*y[k], kOnWallBase, kExplainedBase, kOnWallBase, on_wall);  // Y's wall each ray ended on
    else
      on_wall.clear();
    for (const auto& h : *x[k]) {
      if (h.key >= kInDoorwayBase && h.key < kDoorExplainedBase) continue;  // marks, read above
      const bool open = h.key >= kOpenKeyBase && h.key < kOnWallBase;
      std::int32_t wall = open ? markOf(on_wall, h.ray) : -1;
      const std::int32_t opening = wall >= 0 ? markOf(in_opening, h.ray) : -1;
      if (opening >= kInWindowBase) wall = -1;  // X's pane explains it as well: stays open
      if (opening >= kInDoorwayBase && opening < kInWindowBase) {
        all.push_back({kDoorExplainedBase + (opening - kInDoorwayBase), static_cast<float>(params.door_worth), h.ray});
        continue;
      }
      if (wall >= 0) all.push_back({kExplainedBase + wall, static_cast<float>(params.face_worth), h.ray});
      // A wall the planes counted keeps its rays in the open term too (bounded, as before).
      if (wall < 0 || (static_cast<std::size_t>(wall) < counted.size() && counted[static_cast<std::size_t>(wall)] > 0.0)) all.push_back(h);
    }
  }
  FreeSpaceCost cost;
  std::sort(all.begin(), all.end(), byKey);
  const auto first_explained =
      std::lower_bound(all.begin(), all.end(), kExplainedBase, [](const FreeSpaceHit& h, std::int32_t k) { return h.key < k; });
  for (auto i = first_explained; i != all.end();) {
    auto j = i;
    for (; j != all.end() && j->key == i->key; ++j) {}
    const double n = static_cast<double>(j - i);
    if (i->key >= kDoorExplainedBase) {  // X's doorway on wall key - base: one leaf, door_worth
      cost.doors += params.door_worth * std::min(1.0, n / static_cast<double>(params.support_rays));
      i = j;
      continue;
    }
    const auto wall = static_cast<std::size_t>(i->key - kExplainedBase);
    // One wall, one face's worth, whatever saw it: what the planes counted for it is taken off.
    const double planes = wall < counted.size() ? std::max(0.0, counted[wall]) : 0.0;
    const double worth = params.face_worth * std::min(1.0, n / static_cast<double>(params.support_rays));
    cost.explained.emplace_back(static_cast<std::int32_t>(wall), std::max(0.0, worth - planes));
    i = j;
  }
  all.erase(first_explained, all.end());
  cost.rest = penaltyOf(all, params);
  return cost;
}

double freeSpacePenaltyBound(const std::vector<const std::vector<FreeSpaceHit>*>& x, const FreeSpaceParams& params) {
  // Every open ray explained, each under a key of its own: at most face_worth / support_rays each.
  double open_rays = 0;
  for (const auto* scan : x)
    if (scan)
      for (const auto& h : *scan) open_rays += (h.key >= kOpenKeyBase && h.key < kOnWallBase) ? 1.0 : 0.0;
  const double extra = params.explained ? params.face_worth * open_rays / static_cast<double>(params.support_rays) : 0.0;
  return freeSpacePenalty(x, params) + extra;
}

}  // namespace bimloc::pf::detail
