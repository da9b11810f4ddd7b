// Pose hypotheses from a plane and its end, for scans whose planes all run one way
// (hypotheses.hpp: posesFromEnds; ParticleFilterConfig::match_wall_ends).
#include "hypotheses.hpp"

#include <cmath>

namespace bimloc::pf::detail {

// Where the scan's planes all run one way (no pair fixes a position), a plane seen to its end
// fixes it with its face: across by its offset, along by its standing span's end at the end of
// the face's wall line (match_wall_ends scores a run past it). Every observation with a span,
// on every face it may be at (the same heading and height tests as a pair's first plane), at
// either end of the face's line: the poses every fit of such a scan starts from. A span whose
// end is no wall's end (something hid the rest) gives poses the scoring turns down.
void posesFromEnds(const std::vector<Observation>& obs, double z, const std::vector<Landmark>& marks, int room,
                   const RoomIndex& rooms, double margin_m, std::vector<Particle>& poses) {
  for (const Observation& o : obs) {
    if (!(o.wall_span_m > 0.0) || !o.span_middle_base.allFinite()) continue;
    for (const Landmark& a : marks) {
      if (!std::isfinite(a.line_lo_m) || !std::isfinite(a.line_hi_m) || !atFaceHeight(o, a, z)) continue;
      // A span longer than the line and the wall-line margin fits at neither end (the match
      // would refuse it there, as solveAt's pairs refuse a plane beside its face).
      if (o.wall_span_m > a.line_hi_m - a.line_lo_m + margin_m) continue;
      const double yaw = wrapAngle(a.azimuth - o.azimuth_base), hc = std::cos(yaw), hs = std::sin(yaw);
      const Eigen::Vector2d n = a.normal.head<2>();
      if (!(n.norm() > 0.5)) continue;  // not a standing face
      // n . xy = d_off - d - n_z z across (solveAt's line), and along the face the span's middle
      // at (end -+ half the span) from the face's start.
      const double across = (o.d_offset - a.d - a.normal.z() * z) / n.squaredNorm();
      const Eigen::Vector2d middle(hc * o.span_middle_base.x() - hs * o.span_middle_base.y(),
                                   hs * o.span_middle_base.x() + hc * o.span_middle_base.y());
      for (const double end : {a.line_hi_m - 0.5 * o.wall_span_m, a.line_lo_m + 0.5 * o.wall_span_m}) {
        const double t = end + a.start.dot(a.direction) - middle.dot(a.direction);
        const Eigen::Vector2d xy = across * n + (t - across * n.dot(a.direction)) * a.direction;
        if (room >= 0 && !rooms.mayBeIn(room, xy.x(), xy.y())) continue;
        Particle p;
        p.x = xy.x(), p.y = xy.y(), p.yaw = yaw, p.room = rooms.roomAt(xy.x(), xy.y());
        if ((p.room < 0 && room != kAnywhere) || (room >= 0 && p.room != room)) continue;
        poses.push_back(p);
      }
    }
  }
}

}  // namespace bimloc::pf::detail
