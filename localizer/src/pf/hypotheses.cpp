#include "hypotheses.hpp"
#include "pose_sets.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <tuple>

namespace bimloc::pf::detail {
namespace {

// The best log-likelihood of the hypotheses kept so far, and how far below it the caller
// still wants them (infinite: all).
struct Bound {
  double within = std::numeric_limits<double>::infinity();
  double best = -std::numeric_limits<double>::infinity();
  double floor() const { return best - within; }
};

// Three associations make a pose worth scoring; clutter (furniture, walls seen through doors)
// can outnumber a room's own walls, so the bar does not grow with the number of planes.
constexpr int kMinAssociated = 3;

// The pose at which observation i lies on landmark a and observation j on landmark b (the
// heading from a's normal, the position from the two planes' offsets), when it is inside
// `room` (or any room when room == -1, anywhere when room == kAnywhere) and each plane's
// centroid lies along its face to within along_m (none when negative). Without that rule,
// most poses solved over a storey put the planes beside their faces (two lines crossing
// anywhere), and their number grows with the building: on a 100-room floor the global
// search's and the seeds' scoring took half the time with it (docs/results/2026-11-26-h28speed2.md).

// The heading observation i on landmark a fixes, with its cosine and sine: one per (i, a),
// shared by every (j, b) paired with them.
struct Heading {
  double yaw, c, s;
};
Heading headingOf(const Observation& o, const Landmark& a) {
  const double yaw = wrapAngle(a.azimuth - o.azimuth_base);
  return {yaw, std::cos(yaw), std::sin(yaw)};
}

// solvePair with its first two tests (the turn between the faces, the heights) passed and
// the heading given.
std::optional<Particle> solveAt(const std::vector<Observation>& obs, std::size_t i, std::size_t j, const Landmark& a,
                                const Landmark& b, const Heading& h, double z, int room, const RoomIndex& rooms, double along_m) {
  // With the heading fixed, each plane is one line for (x, y): n·(x, y) = d_off - d - n_z z.
  Eigen::Matrix2d A;
  A << a.normal.x(), a.normal.y(), b.normal.x(), b.normal.y();
  if (std::abs(A.determinant()) < 0.3) return std::nullopt;
  const Eigen::Vector2d rhs(obs[i].d_offset - a.d - a.normal.z() * z, obs[j].d_offset - b.d - b.normal.z() * z);
  const Eigen::Vector2d xy = A.inverse() * rhs;
  // The room's box first: the cheapest test, and most poses solved from a room's faces fall
  // outside it (all the tests must pass, in any order).
  if (room >= 0 && !rooms.mayBeIn(room, xy.x(), xy.y())) return std::nullopt;  // roomAt would say so, slower
  if (along_m >= 0.0) {
    // Each plane's points along its face (matchObservations' rule): elsewhere the pair of
    // faces explains neither plane, and the pose is a coincidence of two lines.
    const double c = h.c, s = h.s;
    const auto along = [&](const Observation& o, const Landmark& l) {
      const Eigen::Vector2d m(xy.x() + c * o.centroid_base.x() - s * o.centroid_base.y(), xy.y() + s * o.centroid_base.x() + c * o.centroid_base.y());
      const double u = (m - l.start).dot(l.direction);
      return u >= -along_m && u <= l.length_m + along_m;
    };
    if (!along(obs[i], a) || !along(obs[j], b)) return std::nullopt;
  }
  Particle p;
  p.x = xy.x(), p.y = xy.y(), p.yaw = h.yaw, p.room = rooms.roomAt(xy.x(), xy.y());
  if ((p.room < 0 && room != kAnywhere) || (room >= 0 && p.room != room)) return std::nullopt;
  return p;
}

std::optional<Particle> solvePair(const std::vector<Observation>& obs, std::size_t i, std::size_t j, const Landmark& a,
                                  const Landmark& b, double z, int room, const RoomIndex& rooms, double along_m) {
  const double turn = wrapAngle(obs[j].azimuth_base - obs[i].azimuth_base);
  if (std::abs(wrapAngle(b.azimuth - a.azimuth - turn)) > kHypothesisAngleRad) return std::nullopt;
  if (!atFaceHeight(obs[i], a, z) || !atFaceHeight(obs[j], b, z)) return std::nullopt;
  return solveAt(obs, i, j, a, b, headingOf(obs[i], a), z, room, rooms, along_m);
}

// The pose scored; kept when it explains enough of the scan (and is not below the floor).
// A pose in no room, searched for as a rival (room == kAnywhere), is scored as the path
// evidence scores it: without the out-of-rooms penalty.
void scorePose(const Particle& p, const std::vector<Observation>& obs, double z, const RoomIndex& rooms,
               const ParticleFilterConfig& c, bool penalise_outside, Bound& bound, std::vector<Hypothesis>& out) {
  const MatchResult m = matchObservations(p, z, obs, rooms, c, nullptr, penalise_outside, bound.floor());
  if (m.below_floor || m.associated < kMinAssociated) return;
  out.push_back({p.x, p.y, p.yaw, p.room, m.log_likelihood, m.associated});
  bound.best = std::max(bound.best, m.log_likelihood);
}

bool pairable(const std::vector<Observation>& obs, std::size_t i, std::size_t j) { return i != j && atPairAngle(obs[i], obs[j]); }

// Each distinct pose scored, against the floor when there is one, the poses most pairs agree on
// first (pose_sets.hpp). The same pose solved from several pairs (collinear pieces of one wall
// fix the same lines) is scored once: a pose's score depends on the pose alone, and a repeat
// would add an entry equal to one already there, which the merge of near-duplicates drops.
// With a floor, the order poses are scored in decides how early the best is known, and so how
// much of every other pose's scan is matched before it falls below the floor; the result does
// not depend on it. The true pose and its look-alikes are what many pairs of faces agree on.
void scorePoses(std::vector<Particle>& poses, const std::vector<Observation>& obs, double z, const RoomIndex& rooms,
                const ParticleFilterConfig& c, bool penalise_outside, Bound& bound, std::vector<Hypothesis>& out) {
  if (std::isfinite(bound.within)) mostAgreedFirst(poses);
  dropRepeatedPoses(poses);
  for (const auto& p : poses) scorePose(p, obs, z, rooms, c, penalise_outside, bound, out);
}

// The poses from one room's landmarks: every pair of observations against every pair. The
// pairs solvePair turns down at its first two tests (the turn between the faces, the heights)
// are passed over here: those tests once per observation and face, not per pair of pairs
// (the seeds go over every room of the storey at every weighing); and the heading of each
// (observation, face) once, not per pair of pairs. The poses are the same, in the same order.
void fromLandmarks(const std::vector<Observation>& obs, double z, const std::vector<Landmark>& marks, int room,
                   const RoomIndex& rooms, double along_m, std::vector<Particle>& poses, std::vector<char>& at_height,
                   std::vector<Heading>& headings, std::vector<char>& known) {
  const std::size_t m = marks.size();
  at_height.resize(obs.size() * m);
  for (std::size_t i = 0; i < obs.size(); ++i)
    for (std::size_t a = 0; a < m; ++a) at_height[i * m + a] = atFaceHeight(obs[i], marks[a], z) ? 1 : 0;
  // The heading of (i, a), once it is first needed (most are never: no b turns with it).
  headings.resize(obs.size() * m);
  known.assign(obs.size() * m, 0);
  for (std::size_t i = 0; i < obs.size(); ++i)
    for (std::size_t j = 0; j < obs.size(); ++j) {
      if (!pairable(obs, i, j)) continue;
      const double turn = wrapAngle(obs[j].azimuth_base - obs[i].azimuth_base);
      for (std::size_t a = 0; a < m; ++a) {
        if (!at_height[i * m + a]) continue;
        for (std::size_t b = 0; b < m; ++b) {
          if (a == b || !at_height[j * m + b] || std::abs(wrapAngle(marks[b].azimuth - marks[a].azimuth - turn)) > kHypothesisAngleRad)
            continue;
          const std::size_t ia = i * m + a;
          if (!known[ia]) headings[ia] = headingOf(obs[i], marks[a]), known[ia] = 1;
          if (const auto p = solveAt(obs, i, j, marks[a], marks[b], headings[ia], z, room, rooms, along_m)) poses.push_back(*p);
        }
      }
    }
}

// Hypotheses over every face of the storey, through the face index: with observation i along
// face a (which fixes the heading), observation j's points lie where they are relative to i's,
// so face b can only be one that passes near there. Pairs of faces the robot could not see
// together are never tried: the cost is the faces times the faces near each, not its square.
void fromIndex(const std::vector<Observation>& obs, double z, const FaceIndex& index, const RoomIndex& rooms,
               const ParticleFilterConfig& c, int room, double along_m, std::vector<Particle>& poses) {
  const auto& faces = index.faces();
  const double angle = std::max(c.sigma_azimuth_deg, c.sigma_elevation_deg) * M_PI / 180.0;
  std::vector<double> reach(obs.size());
  for (std::size_t k = 0; k < obs.size(); ++k)
    reach[k] = matchRadius(obs[k].range_m, c.sigma_d_m, angle, c.gate_mahalanobis2, c.segment_margin_m);
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < obs.size(); ++i)
    for (std::size_t j = 0; j < obs.size(); ++j) {
      if (!pairable(obs, i, j)) continue;
      for (std::size_t a = 0; a < faces.size(); ++a) {
        const Landmark& fa = faces[a];
        const double yaw = wrapAngle(fa.azimuth - obs[i].azimuth_base);
        const double cy = std::cos(yaw), sy = std::sin(yaw);
        const Eigen::Vector2d step = obs[j].centroid_base - obs[i].centroid_base;
        const Eigen::Vector2d centre = fa.start + 0.5 * fa.length_m * fa.direction +
                                       Eigen::Vector2d(cy * step.x() - sy * step.y(), sy * step.x() + cy * step.y());
        near.clear();  // collected first: scoring queries the index too
        const double radius = 0.5 * fa.length_m + reach[i] + reach[j];
        if (std::isfinite(radius))
          index.forEachNear(centre, radius, [&](const Landmark& fb) { near.push_back(static_cast<std::size_t>(&fb - faces.data())); });
        else
          for (std::size_t b = 0; b < faces.size(); ++b) near.push_back(b);
        std::sort(near.begin(), near.end());  // the same order whatever the cells' order
        for (const std::size_t b : near)
          if (b != a)
            if (const auto p = solvePair(obs, i, j, fa, faces[b], z, room, rooms, along_m)) poses.push_back(*p);
      }
    }
}

}  // namespace

std::vector<Hypothesis> poseHypotheses(const std::vector<Observation>& observations, double z_base,
                                       const RoomIndex& rooms, const ParticleFilterConfig& config, std::size_t max_count,
                                       double wanted_within, bool outside_rooms, RoomShare* share) {
  std::vector<Hypothesis> all;
  if (observations.size() < 2 || rooms.roomCount() == 0) return all;
  Bound bound;
  bound.within = wanted_within;
  // Every pose solved first, scored after (see mostAgreedFirst): over every room, the poses of
  // all rooms in one order, so that the floor is high from the first rooms on.
  std::vector<Particle> poses;
  const int room = config.use_rooms ? 0 : outside_rooms ? kAnywhere : -1;
  const double along_m = config.segment_margin_m;
  std::vector<char> at_height, known;
  std::vector<Heading> headings;
  if (config.use_rooms) {
    // The rooms' order does not change the result (the poses are scored, then sorted by score
    // and pose), only which rooms a share reaches.
    const int count = static_cast<int>(rooms.roomCount());
    const int first = share ? ((share->next_room % count) + count) % count : 0;
    int searched = 0;
    while (searched < count) {
      const int r = (first + searched++) % count;
      fromLandmarks(observations, z_base, rooms.landmarks(r), r, rooms, along_m, poses, at_height, headings, known);
      if (share && share->poses > 0 && poses.size() >= share->poses) break;
    }
    if (share) share->next_room = (first + searched) % count, share->rooms_searched = searched;
  } else {
    // The ablation: every room holds every face; one pass over them is enough.
    if (const FaceIndex* index = rooms.fineIndex())
      fromIndex(observations, z_base, *index, rooms, config, room, along_m, poses);
    else
      fromLandmarks(observations, z_base, rooms.landmarks(0), room, rooms, along_m, poses, at_height, headings, known);
  }
  // The rival search (outside_rooms) also solves a scan whose planes all run one way from one
  // plane and its end: it must find every place such a scan fits. The filter's seeds do not:
  // down a corridor of look-alike flats, every end of every flat's walls fits such a scan about
  // as well, and the particles moved there pulled the cloud off the truth (random_residential
  // floors: 7 starts lost where 5 were gained).
  if (outside_rooms && config.match_wall_lines && config.match_wall_ends && !positionFixedByPlanes(observations))
    posesFromEnds(observations, z_base, rooms.landmarks(0), room, rooms, along_m, poses);
  scorePoses(poses, observations, z_base, rooms, config, room != kAnywhere, bound, all);
  // Those below the floor are out before they are sorted: the ones the caller wants, best
  // first, come before any of them whatever their number, so merging them changes nothing.
  if (std::isfinite(wanted_within))
    all.erase(std::remove_if(all.begin(), all.end(), [&](const Hypothesis& h) { return h.log_likelihood < bound.floor(); }),
              all.end());
  std::sort(all.begin(), all.end(), [](const Hypothesis& a, const Hypothesis& b) {
    return a.log_likelihood != b.log_likelihood ? a.log_likelihood > b.log_likelihood
                                                : std::tie(a.x, a.y, a.yaw) < std::tie(b.x, b.y, b.yaw);
  });
  // Best first, without near-duplicates (within 0.2 m and the angle tolerance of a better one).
  return distinctBest(all, max_count);
}

}  // namespace bimloc::pf::detail
