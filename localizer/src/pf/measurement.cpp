#include "measurement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace bimloc::pf::detail {
namespace {

// Wider than this (the annealed sigmas at the start), a query would visit most of a floor's
// cells: brute force over the faces is cheaper then.
constexpr double kIndexedRadiusM = 12.0;

// Whether the plane `o` (its normal at map azimuth `azimuth`; where it stands along its line:
// `middle`, map x y, and half its span) lies behind the solid part of face `l`, seen from
// `sensor` (map x y): parallel to the face, farther behind it than the gate reaches, the face
// facing the sensor and as high as the plane, and every ray to the plane's support crossing
// the face where it has no opening (grown by opening_margin_m). A lidar cannot see through a
// wall; a counter or cabinet stands before one, and a plan has no furniture: a plane before a
// face is clutter, behind it a contradiction (the beam model's asymmetry, as AMCL's: a short
// return is an unmapped obstacle, a long one through a mapped wall is not).
bool behindSolidFace(const Observation& o, const Landmark& l, const Eigen::Vector2d& sensor, double z_base, double azimuth,
                     const Eigen::Vector2d& middle, double half, double gate_reach_rad, double gate_reach_m, double opening_margin_m) {
  if (std::abs(wrapAngle(azimuth - l.azimuth)) > gate_reach_rad) return false;  // not parallel: not behind it
  // Hidden from top to bottom: a plane seen over a parapet or under a bulkhead is not behind it.
  if (z_base + o.z_low < l.z_bottom - kVerticalMarginM || z_base + o.z_high > l.z_top + kVerticalMarginM) return false;
  const Eigen::Vector2d n = l.normal.head<2>();
  const double sensor_front = n.dot(sensor - l.start);  // > 0: the sensor before the face
  const double plane_behind = -n.dot(middle - l.start);   // > 0: the plane behind the face's plane
  if (sensor_front <= 0.0 || plane_behind <= gate_reach_m) return false;
  // Where the rays to the plane's two ends cross the face's line (similar triangles).
  const double ratio = sensor_front / (sensor_front + plane_behind);
  const double u_sensor = (sensor - l.start).dot(l.direction), u_middle = (middle - l.start).dot(l.direction);
  const double a = u_sensor + (u_middle - half - u_sensor) * ratio, b = u_sensor + (u_middle + half - u_sensor) * ratio;
  const double lo = std::min(a, b), hi = std::max(a, b);
  if (lo < 0.0 || hi > l.length_m) return false;  // past the face's end: seen round it, perhaps
  if (l.openings)
    for (const auto& hole : *l.openings)
      if (hole.along_max_m + opening_margin_m > lo && hole.along_min_m - opening_margin_m < hi) return false;  // through a door, a window
  return true;
}

}  // namespace

MatchResult matchObservations(const Particle& p, double z_base, const std::vector<Observation>& observations,
                              const RoomIndex& rooms, const ParticleFilterConfig& c, std::vector<ObservationMatch>* per_observation,
                              bool out_of_rooms_penalised, double floor, double opening_margin_m, const FaceShortlist* shortlist) {
  MatchResult result;
  const double gate = c.gate_mahalanobis2;
  if (per_observation) per_observation->clear(), per_observation->reserve(observations.size());  // grown once, not by doubling
  const FaceIndex* index = rooms.faceIndex();
  const bool outside = p.room < 0;
  if (outside && !index && !rooms.seesEveryFace()) {
    // Outside every room, and no faces to match it with: the lowest weight there is.
    result.log_likelihood = -0.5 * gate * (static_cast<double>(observations.size()) + 1.0) - 10.0;
    return result;
  }
  // Outside every room (a corridor or hall the plan has no space for, a doorway, the street),
  // there is no room to restrict the association: every face near the observations counts,
  // and the pose pays one clutter plane for standing where the plan has no room. A room is
  // a prior on where the robot is, not a measurement: penalised, not ruled out.
  if (outside && out_of_rooms_penalised) result.log_likelihood -= c.outside_rooms_penalty;
  const bool via_index = index && (rooms.seesEveryFace() || outside);
  const std::vector<Landmark>& landmarks = via_index ? index->faces() : rooms.landmarks(outside ? 0 : p.room);
  const double cy = std::cos(p.yaw), sy = std::sin(p.yaw);
  const double inv_az = 1.0 / (c.sigma_azimuth_deg * M_PI / 180.0), inv_el = 1.0 / (c.sigma_elevation_deg * M_PI / 180.0);
  const double inv_d = 1.0 / c.sigma_d_m;
  const double margin_m = c.segment_margin_m;
  const double max_angle_rad = std::max(c.sigma_azimuth_deg, c.sigma_elevation_deg) * M_PI / 180.0;
  const FaceIndex* fine = rooms.fineIndex();
  // The local search also matches a plane behind a face, in its openings (below): as far as
  // the deepest wall with openings.
  const double behind_m = opening_margin_m >= 0.0 ? rooms.fillingDepth() : 0.0;
  // Opposite sides of one axis are at least 90 deg apart (wallSide, landmark.hpp). Where the
  // gate's angle is under 45 deg, a face of the other side has e_az^2 > 4 gate, and m2_fill >=
  // e_az^2 (sums of non-negative terms, rounded upwards-monotone): it can never pass `best`
  // (<= gate), so leaving it out changes nothing; the lists keep the rest in their order.
  const bool by_axis = !via_index && !rooms.seesEveryFace();  // the faces from a room's lists of one axis
  const bool by_side = std::sqrt(gate) * (c.sigma_azimuth_deg * M_PI / 180.0) < 0.25 * M_PI;
  // A point of the yaw-free base frame, in the map at the particle's pose.
  const auto inMap = [&](const Eigen::Vector2d& b) { return Eigen::Vector2d(p.x + cy * b.x() - sy * b.y(), p.y + sy * b.x() + cy * b.y()); };
  // The local search's pieces (see below): azimuth and d in the scan's frame, cost, support.
  struct Piece {
    double azimuth, d, cost, support;
  };
  std::vector<Piece> pieces;
  if (opening_margin_m >= 0.0) pieces.reserve(observations.size());  // one allocation, not one per doubling
  // The shortlist stands for the index only where the index would be asked: every face a candidate.
  if (shortlist && !(index && rooms.seesEveryFace() && shortlist->match.size() == observations.size())) shortlist = nullptr;
  // How far from a plane its match can lie: only where the index is asked (a room's faces are
  // all considered): its sine and square root were paid at every particle of every weighing.
  std::optional<MatchReach> reach_of;
  if (via_index && !shortlist) reach_of.emplace(c.sigma_d_m, max_angle_rad, gate, margin_m, behind_m);
  for (std::size_t k = 0; k < observations.size(); ++k) {
    const Observation& o = observations[k];
    // The observed normal in the map (a plane moves with a pose: n' = R n).
    const double nx = cy * o.normal_base.x() - sy * o.normal_base.y(), ny = sy * o.normal_base.x() + cy * o.normal_base.y();
    const double azimuth = o.azimuth_base + p.yaw, elevation = o.elevation;
    const bim::WallAxis axis = std::abs(nx) >= std::abs(ny) ? bim::WallAxis::X : bim::WallAxis::Y;
    const int side = by_side ? wallSide(nx, ny) : -1;
    // The index asked: one side's faces where the side is known (the same positions in faces()).
    const FaceIndex* query = side >= 0 && index && rooms.sideIndex(side) && !shortlist ? rooms.sideIndex(side) : index;
    const auto faceAt = [&](const Landmark& l) { return static_cast<std::uint32_t>(&l - query->faces().data()); };
    const Eigen::Vector2d centroid = inMap(o.centroid_base);
    // Where the plane stands (its standing span, else centroid -+ half its extent): for the
    // wall-line rule (when on), the openings rule and the through-wall check.
    const bool span_known = o.wall_span_m > 0.0 && o.span_middle_base.allFinite();
    const bool check_line = c.match_wall_lines && span_known;
    const bool end_term = c.match_wall_ends && o.end_scored;
    const Eigen::Vector2d span_middle = span_known ? inMap(o.span_middle_base) : centroid;
    const double span_half = 0.5 * (span_known ? o.wall_span_m : o.extent_m);
    // Without the room factor, only the faces that pass near the plane's points can match it
    // (face_index.hpp): the same best match as over every face, at the cost of what is near.
    const double radius = shortlist ? shortlist->radius_m[k] : via_index ? reach_of->at(o.range_m) : 0.0;
    const bool indexed = via_index && radius < kIndexedRadiusM;
    const bool cell_ordered = indexed && fine;
    double best = gate;
    int best_face = -1;
    bool best_filling = false;
    const Landmark* best_landmark = nullptr;
    const auto consider = [&](const Landmark& l) __attribute__((always_inline)) {
      // The paper's semantic classes: x walls with x walls (a room's lists hold one axis already).
      if (!by_axis && l.axis != axis) return;
      if (!atFaceHeight(o, l, z_base)) return;  // a wall above (or below) what the scan saw of it
      // Paper Eq. (plane error): the squared Mahalanobis distance of the minimal planes, with
      // d taken at the particle (the landmark moved to a frame centred on it, axes of the map):
      // compared at the map's origin instead, a heading error of 1 degree would cost 0.17 m of
      // d per 10 m from the origin, and the same view would score worse far from it.
      const double d_landmark = l.d + l.normal.x() * p.x + l.normal.y() * p.y + l.normal.z() * z_base;
      const double behind = o.d_offset - d_landmark;  // > 0: the plane stands behind the face
      const double e_d = behind * inv_d;
      const bool check_openings = opening_margin_m >= 0.0 && l.openings && !l.openings->empty();
      // A face farther in d alone than the best so far is passed over before its angles: m2
      // below adds e_d^2 to a sum of squares, and a float sum of non-negative terms is no
      // smaller than any of them (rounding is monotonic), so m2 would exceed `best` too: the
      // same faces pass. Not where a filling may be scored instead (nearer in d: below).
      if (!check_openings && e_d * e_d > best) return;
      const double e_az = wrapAngle(azimuth - l.azimuth) * inv_az, e_el = (elevation - l.elevation) * inv_el;
      const double m2 = e_az * e_az + e_el * e_el + e_d * e_d;
      // In the face's openings, a plane is what fills them (a pane, a frame, a shut door's
      // leaf), which stands anywhere within the wall's body: its d is off by how far it lies
      // outside the face-to-depth span (why: below). Anywhere, not only within the gate of the
      // face: a filling that counted only near the face would pull the pose towards it.
      double m2_fill = m2;
      if (check_openings && behind > 0.0) {
        const double e_fill = std::max(0.0, behind - l.depth_m) * inv_d;
        m2_fill = e_az * e_az + e_el * e_el + e_fill * e_fill;
      }
      if (m2_fill > best) return;  // m2_fill <= m2: the least this face can score
      // The observed wall's points must lie along the face, not beside its end.
      const double u = (centroid - l.start).dot(l.direction);
      if (u < -margin_m || u > l.length_m + margin_m) return;
      double m2_end = 0.0;
      bool filling = false;
      if (check_line || check_openings) {
        const double m = (span_middle - l.start).dot(l.direction);  // where the plane stands along the face
        // And all of its points must lie along its wall line (wall_lines.hpp): a plane that runs
        // on past the end of the line is another wall, whatever face its centroid falls on.
        if (check_line) {
          const double overrun = std::max(l.line_lo_m - (m - span_half), (m + span_half) - l.line_hi_m);
          if (overrun > margin_m) return;
          // Short of the gate, a plane that runs past where its wall line ends is scored for it,
          // in the plane's own noise (as its d): a wall's seen end fixes the pose along the wall
          // as its plane does across it. Without, a pose 0.5 m along a wall whose end the scans
          // saw fitted it as well as the truth (IFC 4.3 sample house: its walls all run along y).
          if (end_term && overrun > 0.0) m2_end = overrun * inv_d * overrun * inv_d;
        }
        // Not the face where it stands in the face's openings (by where the plane stands, not
        // its centroid -+ half its extent: the centroid sits near the sensor, and a pane filling
        // its window "overflowed" it by 0.1 m, the Duplex), but what fills them. A pane seen
        // where the plan has its window is what the plan predicts: scored as unexplained, it
        // counted against the true pose and for a pose 0.3 m aside that puts the pane on the
        // solid wall (AC20-FZK-Haus, room 5: the settled pose waited 7 s for it).
        if (check_openings &&
            bim::insideOpening(*l.openings, m - span_half, m + span_half, z_base + o.z_low, z_base + o.z_high, opening_margin_m))
          filling = true;
      }
      const double m2_here = (filling ? m2_fill : m2) + m2_end;
      // Of faces that fit exactly alike (collinear pieces of one wall), the one the search
      // reaches first: in the list, or in the 1 m cells' order (see RoomIndex::fineIndex).
      if (m2_here > best) return;
      if (m2_here == best && (best_face < 0 || !cell_ordered ||
                              !fine->visitsBefore(centroid, radius, faceAt(l), faceAt(*best_landmark))))
        return;
      best = m2_here;
      best_filling = filling;
      best_face = l.id;
      best_landmark = &l;
    };
    if (indexed && shortlist)
      for (const Landmark* l : shortlist->match[k]) consider(*l);
    else if (indexed)
      query->forEachNear(centroid, radius, consider);
    else if (!via_index)  // a room's faces: those of the plane's axis and side, the others would be passed over
      for (const auto& l : rooms.landmarks(outside ? 0 : p.room, axis, side)) consider(l);
    else
      for (const auto& l : landmarks) consider(l);
    // The local search (the converged pose's refinement) also knows what no face can explain:
    // a plane seen through a solid face costs the clutter it is and the face that should have
    // hidden it.
    if (opening_margin_m >= 0.0) {
      const double reach = std::sqrt(gate);
      const Eigen::Vector2d sensor(p.x, p.y);
      bool hidden = false;
      const auto hides = [&](const Landmark& l) {
        hidden = hidden || behindSolidFace(o, l, sensor, z_base, azimuth, span_middle, span_half, reach / inv_az, reach * c.sigma_d_m,
                                           opening_margin_m);
      };
      // A face that hides the plane crosses the rays from the sensor to its support, all of
      // which lie within half the distance plus half the span of their middle: what the robot
      // sees, not the building.
      if (shortlist)
        for (const Landmark* l : shortlist->hide[k]) hides(*l);
      else if (index)
        index->forEachNear(0.5 * (sensor + span_middle), 0.5 * (span_middle - sensor).norm() + span_half, hides);
      else
        for (const auto& l : landmarks) hides(l);
      if (hidden) best = 2.0 * gate, best_face = -1, best_filling = false;
    }
    // An observation that matches nothing is clutter (the site does not look like the plan
    // yet): it costs what a match at the gate would, so it cannot destroy a good particle.
    if (best < gate) ++result.associated;
    // In the local search, the pieces of one surface are weighed together, below.
    if (opening_margin_m >= 0.0) pieces.push_back({o.azimuth_base, o.d_offset, best, o.support});
    else result.log_likelihood += -0.5 * best;
    if (per_observation) per_observation->push_back({best_face, static_cast<float>(best), best_filling});
    if (result.log_likelihood < floor) {
      result.below_floor = true;
      return result;
    }
  }
  // In the local search, the pieces of one surface (coplanar within the gate's reach: a
  // shelving's front cut into pieces by what stands on it, a wall seen between them, a wall and
  // the cabinet fronts along it) are one observation, not several independent ones: the surface
  // costs the mean of its pieces' costs, each weighed by its support. Counted per piece, a
  // surface weighed by how many pieces the extractor cut it into: a shelf front in five pieces
  // outvoted the wall behind it seen in two (docs/realdata_room.md). And counted per piece
  // while matched but once while unexplained (session 15's rule), matching a wall cost more
  // than leaving it and the cabinets along it unexplained, and a piece just inside the gate cost
  // a gate of its own while one just outside joined its neighbours: the PandarXT32's frame was
  // fitted 0.29 m off (docs/results/2026-11-27-h29close.md). The mean is continuous in the
  // pose, is a lone piece's own cost, a clutter's (the gate) when no piece is explained, and
  // lets no small piece stand for the whole surface.
  if (opening_margin_m >= 0.0) {
    const double reach = std::sqrt(gate);
    struct Surface {
      double azimuth, d, weighted_cost, support;
    };
    std::vector<Surface> surfaces;
    surfaces.reserve(pieces.size());
    for (const Piece& piece : pieces) {
      const auto same = std::find_if(surfaces.begin(), surfaces.end(), [&](const Surface& u) {
        return std::abs(wrapAngle(piece.azimuth - u.azimuth)) <= reach / inv_az && std::abs(piece.d - u.d) <= reach * c.sigma_d_m;
      });
      if (same == surfaces.end()) surfaces.push_back({piece.azimuth, piece.d, piece.cost * piece.support, piece.support});
      else same->weighted_cost += piece.cost * piece.support, same->support += piece.support;
    }
    for (const Surface& u : surfaces) result.log_likelihood += -0.5 * u.weighted_cost / u.support;
    if (result.log_likelihood < floor) result.below_floor = true;
  }
  return result;
}

FaceShortlist shortlistFaces(const Eigen::Vector3d& centre, double xy_radius_m, double yaw_radius, double z_base,
                             const std::vector<Observation>& observations, const RoomIndex& every_face, const ParticleFilterConfig& c,
                             double opening_margin_m) {
  FaceShortlist s;
  s.centre = centre, s.xy_radius_m = xy_radius_m, s.yaw_radius = yaw_radius;
  const FaceIndex* index = every_face.faceIndex();
  if (!index || !every_face.seesEveryFace()) return s;  // not a local search's faces: no shortlist
  s.match.resize(observations.size()), s.hide.resize(observations.size()), s.radius_m.resize(observations.size());
  const double gate = c.gate_mahalanobis2, reach = std::sqrt(gate);
  const double sigma_az = c.sigma_azimuth_deg * M_PI / 180.0;
  const double max_angle_rad = std::max(c.sigma_azimuth_deg, c.sigma_elevation_deg) * M_PI / 180.0;
  const double cy = std::cos(centre.z()), sy = std::sin(centre.z());
  const auto inMap = [&](const Eigen::Vector2d& b) {
    return Eigen::Vector2d(centre.x() + cy * b.x() - sy * b.y(), centre.y() + sy * b.x() + cy * b.y());
  };
  // How far a point of the base frame moves over the region (a turn by yaw_radius moves it at
  // most |b| yaw_radius), with a centimetre for rounding: the shortlist may hold more, never less.
  const auto moves = [&](const Eigen::Vector2d& b) { return xy_radius_m + b.norm() * yaw_radius + 0.01; };
  // The angle between the plane and a face at the region's best yaw for it, less a hair.
  const auto leastAngle = [&](double azimuth, const Landmark& l) {
    return std::max(0.0, std::abs(wrapAngle(azimuth - l.azimuth)) - yaw_radius - 1e-9);
  };
  for (std::size_t k = 0; k < observations.size(); ++k) {
    const Observation& o = observations[k];
    const double azimuth = o.azimuth_base + centre.z();
    // matchObservations' candidates: the faces within the match radius of the centroid, of
    // the wall's heights, whose angle alone does not put them beyond the gate at every yaw.
    const double radius = s.radius_m[k] = matchRadius(o.range_m, c.sigma_d_m, max_angle_rad, gate, c.segment_margin_m,
                                                      opening_margin_m >= 0.0 ? every_face.fillingDepth() : 0.0);
    if (radius < kIndexedRadiusM)
      index->forEachNear(inMap(o.centroid_base), radius + moves(o.centroid_base), [&](const Landmark& l) {
        const double e_az = leastAngle(azimuth, l) / sigma_az;
        if (atFaceHeight(o, l, z_base) && e_az * e_az <= gate + 1e-9) s.match[k].push_back(&l);
      });
    if (opening_margin_m < 0.0) continue;
    // The faces that may hide it (behindSolidFace): near the rays from the sensor to its
    // support, parallel to it within the gate and as high as it.
    const bool span_known = o.wall_span_m > 0.0 && o.span_middle_base.allFinite();
    const Eigen::Vector2d middle = span_known ? o.span_middle_base : o.centroid_base;
    const double half = 0.5 * (span_known ? o.wall_span_m : o.extent_m);
    const Eigen::Vector2d sensor(centre.x(), centre.y());
    index->forEachNear(0.5 * (sensor + inMap(middle)), 0.5 * middle.norm() + half + moves(middle), [&](const Landmark& l) {
      if (z_base + o.z_low < l.z_bottom - kVerticalMarginM || z_base + o.z_high > l.z_top + kVerticalMarginM) return;
      if (leastAngle(azimuth, l) > reach * sigma_az) return;
      s.hide[k].push_back(&l);
    });
  }
  return s;
}

bool atPairAngle(const Observation& a, const Observation& b) {
  constexpr double kMinPairAngle = 30.0 * M_PI / 180.0;
  const double turn = std::abs(wrapAngle(b.azimuth_base - a.azimuth_base));
  return turn >= kMinPairAngle && turn <= M_PI - kMinPairAngle;
}

bool positionFixedByPlanes(const std::vector<Observation>& observations) {
  for (std::size_t i = 0; i < observations.size(); ++i)
    for (std::size_t j = i + 1; j < observations.size(); ++j)
      if (atPairAngle(observations[i], observations[j])) return true;
  return false;
}

}  // namespace bimloc::pf::detail
