#include "sim/world/site_clutter.hpp"

#include "sim/common/seeded_random.hpp"
#include "sim/world/site_partitions.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <array>
#include <cmath>

namespace bimloc::sim {
namespace {

constexpr int kDrawsPerBox = 100;        // per box; a full room is found out quickly
constexpr double kBoxDoorSwing_m = 1.0;  // doors: kept this much further than anything else
constexpr double kWallGap_m = 0.01;   // between a box and the edge it stands against
// A wall whose axis is this close to a box's back (beyond half its thickness) is the one it stands against.
constexpr double kHostWall_m = 0.06;

using Box = std::array<Eigen::Vector2d, 4>;

double boxToSegment(const Box& box, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  double d = 1e30;
  for (int i = 0; i < 4; ++i) d = std::min(d, segmentDistance(box[i], box[(i + 1) % 4], a, b));
  return d;
}

double boxToBox(const Box& p, const Box& q) {
  double d = 1e30;
  for (int i = 0; i < 4; ++i) d = std::min(d, boxToSegment(p, q[i], q[(i + 1) % 4]));
  return d;
}

Box boxCorners(const Eigen::Vector2d& centre, const Eigen::Vector2d& u, double along, double across) {
  const Eigen::Vector2d n(-u.y(), u.x());
  const Eigen::Vector2d x = 0.5 * along * u, y = 0.5 * across * n;
  return {centre - x - y, centre + x - y, centre + x + y, centre - x + y};
}

}  // namespace

void placeClutter(const bim::Storey& storey, std::size_t storey_index, const SiteClutter& config,
                  const std::vector<Eigen::Affine3d>& wall_motions, const std::vector<Eigen::Vector2d>& door_centres,
                  std::uint64_t seed, ComposedStorey& out, SiteTruth& truth) {
  if (config.density_per_m2 <= 0.0) return;
  SeededRandom random(seed ^ (0xC1077E5ull * (storey_index + 1)), RandomStream::SiteClutter);
  std::vector<Box> placed;
  for (const bim::Room& room : storey.rooms) {
    const auto& fp = room.footprint;
    const double count_draw = random.uniform();
    if (fp.size() < 3) continue;
    const int wanted = static_cast<int>(std::floor(config.density_per_m2 * room.area_m2 + count_draw));
    double perimeter = 0.0;
    for (std::size_t i = 0; i < fp.size(); ++i) perimeter += (fp[(i + 1) % fp.size()] - fp[i]).norm();
    Eigen::Vector2d lo = fp.front(), hi = lo;
    for (const auto& q : fp) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    int made = 0;
    for (int k = 0; k < wanted; ++k) {
      for (int draw = 0; draw < kDrawsPerBox; ++draw) {
        // Every draw takes the same numbers, so a rejection does not shift the ones after it.
        double r[9];
        for (double& v : r) v = random.uniform();
        Eigen::Vector3d size;
        for (int a = 0; a < 3; ++a) size[a] = config.min_size_m[a] + r[6 + a] * (config.max_size_m[a] - config.min_size_m[a]);
        const bool against = r[0] < config.against_walls;
        Eigen::Vector2d centre, u, back(0, 0);
        int host_edge = -1;
        if (against) {  // the edge by length, then a spot along it; the box's back to the edge
          double s = r[1] * perimeter;
          std::size_t i = 0;
          for (; i + 1 < fp.size() && s > (fp[(i + 1) % fp.size()] - fp[i]).norm(); ++i) s -= (fp[(i + 1) % fp.size()] - fp[i]).norm();
          const Eigen::Vector2d a = fp[i], b = fp[(i + 1) % fp.size()];
          u = (b - a).normalized();
          back = a + r[2] * (b - a);
          centre = back + (0.5 * size.y() + kWallGap_m) * Eigen::Vector2d(-u.y(), u.x());  // inward: left of a CCW edge
          host_edge = static_cast<int>(i);
        } else {
          centre = Eigen::Vector2d(lo.x() + r[3] * (hi.x() - lo.x()), lo.y() + r[4] * (hi.y() - lo.y()));
          u = Eigen::Vector2d(std::cos(M_PI * r[5]), std::sin(M_PI * r[5]));
        }
        const Box box = boxCorners(centre, u, size.x(), size.y());
        bool clear = true;
        for (const auto& c : box) clear = clear && bim::pointInPolygon(fp, c);
        for (std::size_t i = 0; clear && i < fp.size(); ++i)
          if (static_cast<int>(i) != host_edge) clear = boxToSegment(box, fp[i], fp[(i + 1) % fp.size()]) >= config.clearance_m;
        for (std::size_t i = 0; clear && i < storey.walls.size(); ++i) {
          const bim::Wall& w = storey.walls[i];
          const Eigen::Vector2d ws = w.start.head<2>(), we = w.end.head<2>();
          if (against && segmentDistance(back, back, ws, we) <= 0.5 * w.thickness_m + kHostWall_m) continue;
          const Eigen::Vector2d s = (wall_motions[i] * Eigen::Vector3d(ws.x(), ws.y(), 0)).head<2>();
          const Eigen::Vector2d e = (wall_motions[i] * Eigen::Vector3d(we.x(), we.y(), 0)).head<2>();
          clear = boxToSegment(box, s, e) >= config.clearance_m + 0.5 * w.thickness_m;
        }
        for (std::size_t i = 0; clear && i < door_centres.size(); ++i)
          clear = boxToSegment(box, door_centres[i], door_centres[i]) >= config.clearance_m + kBoxDoorSwing_m;
        for (const auto& p : truth.partitions)
          if (clear && p.storey == storey_index) clear = boxToSegment(box, p.start, p.end) >= config.clearance_m + 0.5 * p.thickness_m;
        for (std::size_t i = 0; clear && i < placed.size(); ++i) clear = boxToBox(box, placed[i]) >= config.clearance_m;
        if (!clear) continue;
        const double z0 = room.floor_z, z1 = z0 + (room.height_m > 0 ? std::min(size.z(), room.height_m) : size.z());
        const std::string id = "clutter-" + std::to_string(storey_index) + "-" + std::to_string(truth.clutter.size());
        appendBox(out, id, "Clutter", centre - 0.5 * size.x() * u, centre + 0.5 * size.x() * u, size.y(), z0, z1);
        truth.clutter.push_back({storey_index, room.name, Eigen::Vector3d(centre.x(), centre.y(), z0),
                                 std::atan2(u.y(), u.x()) * 180.0 / M_PI, Eigen::Vector3d(size.x(), size.y(), z1 - z0), against});
        placed.push_back(box);
        ++made;
        break;
      }
    }
    if (made < wanted)
      truth.warnings.push_back("storey '" + storey.name + "', room " + room.name + ": " + std::to_string(wanted - made) +
                               " of " + std::to_string(wanted) + " clutter boxes left out (no place " +
                               std::to_string(config.clearance_m).substr(0, 4) + " m clear of the rest)");
  }
}

}  // namespace bimloc::sim
