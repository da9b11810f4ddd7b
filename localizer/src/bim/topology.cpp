// The room <-> wall edges of the Situational Graph's top layers.
#include "extraction.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace bimloc::bim::detail {
namespace {

Eigen::Vector2d xy(const Eigen::Vector3d& p) { return p.head<2>(); }

constexpr double kMinVerticalOverlap_m = 0.1;

// The face of `wall` that looks into `room`, or -1: first a face lying on the footprint,
// else the face the room's centre is in front of, nearest first.
int faceTowards(const Wall& wall, const Room& room, const ExtractOptions& options) {
  const auto& poly = room.footprint;
  for (int f = 0; f < 2; ++f)
    for (std::size_t i = 0; i < poly.size(); ++i)
      if (faceBoundsEdge(wall.faces[f], poly[i], poly[(i + 1) % poly.size()], options)) return f;
  const Eigen::Vector3d c(room.centre.x(), room.centre.y(), wall.start.z());
  const double d0 = wall.faces[0].plane.signedDistance(c), d1 = wall.faces[1].plane.signedDistance(c);
  if (d0 > 0 && (d1 <= 0 || d0 < d1)) return 0;
  if (d1 > 0) return 1;
  return -1;
}

}  // namespace

bool faceBoundsEdge(const WallFace& face, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const ExtractOptions& options) {
  const Eigen::Vector2d edge = b - a;
  const double length = edge.norm();
  if (length < 1e-6) return false;
  const Eigen::Vector2d dir = edge / length;
  const Eigen::Vector2d inward(-dir.y(), dir.x());  // left of a counter-clockwise edge
  const Eigen::Vector2d n = xy(face.plane.n).normalized();
  // The face must look into the room: its outward normal is the room's inward normal.
  if (n.dot(inward) < std::cos(options.adjacency_angle_deg * M_PI / 180.0)) return false;
  const auto distance = [&](const Eigen::Vector2d& p) { return std::abs(n.dot(p) + face.plane.d); };
  if (distance(a) > options.adjacency_tolerance_m || distance(b) > options.adjacency_tolerance_m) {
    // The edge may be longer than the face (one room edge along several walls): accept when
    // the face's own segment lies on the edge's line.
    const double da = std::abs(inward.dot(xy(face.start) - a)), db = std::abs(inward.dot(xy(face.end) - a));
    if (da > options.adjacency_tolerance_m || db > options.adjacency_tolerance_m) return false;
  }
  const double s0 = dir.dot(xy(face.start) - a), s1 = dir.dot(xy(face.end) - a);
  const double overlap = std::min(length, std::max(s0, s1)) - std::max(0.0, std::min(s0, s1));
  return overlap >= options.adjacency_min_overlap_m;
}

bool edgeInWallBody(const Wall& wall, int f, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const ExtractOptions& options) {
  const WallFace& face = wall.faces[f];
  const Eigen::Vector2d edge = b - a;
  const double length = edge.norm();
  if (length < 1e-6) return false;
  const Eigen::Vector2d dir = edge / length;
  const Eigen::Vector2d inward(-dir.y(), dir.x());
  if (xy(face.plane.n).normalized().dot(inward) < std::cos(options.adjacency_angle_deg * M_PI / 180.0)) return false;
  // How far the face stands in front of the edge's line, into the room: 0 when the edge runs
  // along the face, the thickness when it runs along the wall's back.
  const auto in_body = [&](const Eigen::Vector3d& p) {
    const double h = inward.dot(xy(p) - a);
    return h >= -options.adjacency_tolerance_m && h <= wall.thickness_m + options.adjacency_tolerance_m;
  };
  if (!in_body(face.start) || !in_body(face.end)) return false;
  const double s0 = dir.dot(xy(face.start) - a), s1 = dir.dot(xy(face.end) - a);
  const double overlap = std::min(length, std::max(s0, s1)) - std::max(0.0, std::min(s0, s1));
  return overlap >= options.adjacency_min_overlap_m;
}

void linkRoomsToWalls(Storey& storey, const std::vector<SpaceBoundary>& boundaries,
                      const ExtractOptions& options) {
  for (auto& room : storey.rooms) {
    room.walls.clear();
    std::set<std::string> seen;
    for (const auto& b : boundaries) {
      if (b.space_id != room.id || seen.count(b.element_id)) continue;
      const Wall* wall = storey.findWall(b.element_id);
      if (!wall) continue;  // a slab, a door, or a wall of another storey
      seen.insert(b.element_id);
      room.walls.push_back({wall->id, faceTowards(*wall, room, options)});
    }
    if (!room.walls.empty()) {
      room.topology_source = "IfcRelSpaceBoundary";
      continue;
    }
    linkRoomByGeometry(room, storey.walls, options);
  }
}

void linkRoomByGeometry(Room& room, const std::vector<Wall>& walls, const ExtractOptions& options) {
  room.walls.clear();
  room.topology_source = "geometry";
  const auto& poly = room.footprint;
  for (const auto& wall : walls) {
    // One storey may hold rooms on two levels (example.ifc): a wall bounds the rooms it stands beside.
    const double overlap = std::min(wall.start.z() + wall.height_m, room.floor_z + room.height_m) -
                           std::max(wall.start.z(), room.floor_z);
    if (room.height_m > 0 && wall.height_m > 0 && overlap < kMinVerticalOverlap_m) continue;
    for (int f = 0; f < 2; ++f) {
      bool bounds = false;
      for (std::size_t i = 0; i < poly.size() && !bounds; ++i)
        bounds = faceBoundsEdge(wall.faces[f], poly[i], poly[(i + 1) % poly.size()], options) ||
                 edgeInWallBody(wall, f, poly[i], poly[(i + 1) % poly.size()], options);
      if (bounds) {
        room.walls.push_back({wall.id, f});
        break;
      }
    }
  }
}

}  // namespace bimloc::bim::detail
