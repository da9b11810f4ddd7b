#include "hypotheses.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::pf::detail {
namespace {

constexpr double kAngleTolerance = 5.0 * M_PI / 180.0;
constexpr double kMinPairAngle = 30.0 * M_PI / 180.0;  // nearly parallel planes fix no position

// Hypotheses from one landmark set, kept when inside `room` (or any room when room < 0).
void fromLandmarks(const std::vector<Observation>& obs, double z, const std::vector<Landmark>& marks, int room,
                   const RoomIndex& rooms, const ParticleFilterConfig& c, std::vector<Hypothesis>& out) {
  // Three associations make a pose worth scoring; clutter (furniture, walls seen through doors)
  // can outnumber a room's own walls, so the bar does not grow with the number of planes.
  const int min_associated = 3;
  for (std::size_t i = 0; i < obs.size(); ++i)
    for (std::size_t j = 0; j < obs.size(); ++j) {
      if (i == j) continue;
      const double turn = wrapAngle(obs[j].azimuth_base - obs[i].azimuth_base);
      if (std::abs(turn) < kMinPairAngle || std::abs(turn) > M_PI - kMinPairAngle) continue;
      for (std::size_t a = 0; a < marks.size(); ++a)
        for (std::size_t b = 0; b < marks.size(); ++b) {
          if (a == b || std::abs(wrapAngle(marks[b].azimuth - marks[a].azimuth - turn)) > kAngleTolerance) continue;
          const double yaw = wrapAngle(marks[a].azimuth - obs[i].azimuth_base);
          // With the heading fixed, each plane is one line for (x, y): n·(x, y) = d_off - d - n_z z.
          Eigen::Matrix2d A;
          A << marks[a].normal.x(), marks[a].normal.y(), marks[b].normal.x(), marks[b].normal.y();
          const Eigen::Vector2d rhs(obs[i].d_offset - marks[a].d - marks[a].normal.z() * z,
                                    obs[j].d_offset - marks[b].d - marks[b].normal.z() * z);
          if (std::abs(A.determinant()) < 0.3) continue;
          const Eigen::Vector2d xy = A.inverse() * rhs;
          Particle p;
          p.x = xy.x(), p.y = xy.y(), p.yaw = yaw, p.room = rooms.roomAt(xy.x(), xy.y());
          if (p.room < 0 || (room >= 0 && p.room != room)) continue;
          const MatchResult m = matchObservations(p, z, obs, rooms, c);
          if (m.associated >= min_associated) out.push_back({p.x, p.y, p.yaw, p.room, m.log_likelihood, m.associated});
        }
    }
}

}  // namespace

std::vector<Hypothesis> poseHypotheses(const std::vector<Observation>& observations, double z_base,
                                       const RoomIndex& rooms, const ParticleFilterConfig& config, std::size_t max_count) {
  std::vector<Hypothesis> all;
  if (observations.size() < 2 || rooms.roomCount() == 0) return all;
  if (config.use_rooms) {
    for (int r = 0; r < static_cast<int>(rooms.roomCount()); ++r)
      fromLandmarks(observations, z_base, rooms.landmarks(r), r, rooms, config, all);
  } else {
    // The ablation: every room holds every face; one pass over them is enough.
    fromLandmarks(observations, z_base, rooms.landmarks(0), -1, rooms, config, all);
  }
  std::sort(all.begin(), all.end(), [](const Hypothesis& a, const Hypothesis& b) {
    return a.log_likelihood != b.log_likelihood ? a.log_likelihood > b.log_likelihood
                                                : std::tie(a.x, a.y, a.yaw) < std::tie(b.x, b.y, b.yaw);
  });
  std::vector<Hypothesis> kept;  // best first, without near-duplicates
  for (const auto& h : all) {
    bool duplicate = false;
    for (const auto& k : kept)
      duplicate |= std::hypot(h.x - k.x, h.y - k.y) < 0.2 && std::abs(wrapAngle(h.yaw - k.yaw)) < kAngleTolerance;
    if (!duplicate) kept.push_back(h);
    if (kept.size() >= max_count) break;
  }
  return kept;
}

}  // namespace bimloc::pf::detail
