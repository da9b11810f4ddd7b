#include "plan_layers.hpp"

#include "bim/buried_faces.hpp"

#include <cmath>
#include <map>

namespace bimloc::sgraph::detail {
namespace {

constexpr double kMinWallLength_m = 0.05;
constexpr double kMaxNormalZ = 0.1;
constexpr double kRectangleTolerance = 0.15;  // room area vs the rectangle of its wall pairs  // a face whose normal leaves the floor plane more than this is not a wall

std::string wallName(const bim::Wall& wall, std::size_t index) {
  return "wall " + std::to_string(index) + " '" + (wall.name.empty() ? wall.id : wall.name) + "' (" + wall.id + ")";
}

// A node for a plan wall, or why it cannot be one.
bool makePlanNode(const bim::Wall& wall, WallNode& node, std::string& problem) {
  const Eigen::Vector2d a = wall.start.head<2>(), b = wall.end.head<2>();
  if (!a.allFinite() || !b.allFinite() || !std::isfinite(wall.thickness_m)) {
    problem = "its geometry is not finite";
    return false;
  }
  if ((b - a).norm() < kMinWallLength_m) {
    problem = "it has zero length";
    return false;
  }
  for (const auto& f : wall.faces) {
    if (!f.plane.n.allFinite() || !std::isfinite(f.plane.d) || std::abs(f.plane.n.z()) > kMaxNormalZ || f.plane.n.head<2>().norm() < 0.5) {
      problem = "a face is not a vertical plane";
      return false;
    }
  }
  const Eigen::Vector2d e = wall.faces[0].plane.n.head<2>().normalized();
  const Eigen::Vector2d e1 = wall.faces[1].plane.n.head<2>().normalized();
  if (e.dot(e1) > -0.999) {
    problem = "its faces are not opposite";
    return false;
  }
  node.kind = WallNode::Kind::Plan;
  const Eigen::Vector2d c = 0.5 * (a + b);
  for (int k = 0; k < 2; ++k) {
    const auto& f = wall.faces[static_cast<std::size_t>(k)];
    node.face[k].centre = c;
    node.face[k].e = e;
    node.face[k].side = k == 0 ? 1.0 : -1.0;
    // Plane of the face at zero parameters: d_k = -side (e·c + h_k), with the plan's d (the
    // normal taken as exactly +-e, its horizontal part).
    const double d = f.plane.d / f.plane.n.head<2>().norm();
    node.face[k].h = -node.face[k].side * d - e.dot(c);
    node.start[k] = f.start.head<2>();
    node.end[k] = f.end.head<2>();
    node.openings[k] = f.openings;
  }
  return true;
}

struct Side {
  FaceRef ref;
  double length = -1;
};

}  // namespace

void buildPlanLayers(const bim::Storey& storey, Graph& g, std::vector<std::string>& warnings) {
  std::map<std::string, int> index_of;
  g.nodes.resize(storey.walls.size());
  const std::vector<bool> buried = bim::buriedFaces(storey);
  for (std::size_t i = 0; i < storey.walls.size(); ++i) {
    const bim::Wall& wall = storey.walls[i];
    WallNode& node = g.nodes[i];
    node.wall = static_cast<int>(i);
    std::string problem;
    node.active = makePlanNode(wall, node, problem);
    for (int k = 0; k < 2; ++k) node.buried[static_cast<std::size_t>(k)] = buried[2 * i + static_cast<std::size_t>(k)];
    if (!node.active) warnings.push_back(wallName(wall, i) + " is not a landmark: " + problem);
    else index_of.emplace(wall.id, static_cast<int>(i));
  }

  for (std::size_t r = 0; r < storey.rooms.size(); ++r) {
    const bim::Room& room = storey.rooms[r];
    RoomData data;
    data.room = static_cast<int>(r);
    data.name = room.name.empty() ? room.id : room.name;
    data.footprint = room.footprint;
    // The faces looking into the room: as linked, or the one the room's centre is in front of.
    for (const bim::RoomWall& link : room.walls) {
      const auto it = index_of.find(link.wall_id);
      if (it == index_of.end()) continue;
      const WallNode& node = g.nodes[static_cast<std::size_t>(it->second)];
      int face = link.face;
      if (face < 0 || face > 1) face = node.face[0].distance(node.params.data(), room.centre.x(), room.centre.y()) > 0 ? 0 : 1;
      data.faces.push_back({it->second, face});
    }
    // For each side (x walls looking +x or -x, y walls looking +y or -y) its longest face.
    std::array<Side, 4> sides;
    for (const FaceRef& f : data.faces) {
      const WallNode& node = g.nodes[static_cast<std::size_t>(f.node)];
      const Eigen::Vector2d n = node.normal(f.face);
      const int axis = node.axis(f.face) == bim::WallAxis::X ? 0 : 1;
      const int slot = 2 * axis + (n[axis] > 0 ? 0 : 1);
      if (node.length(f.face) > sides[slot].length) sides[slot] = {f, node.length(f.face)};
    }
    const bool x_pair = sides[0].length > 0 && sides[1].length > 0, y_pair = sides[2].length > 0 && sides[3].length > 0;
    if (!x_pair && !y_pair) {
      warnings.push_back("room '" + data.name + "' has no pair of opposite walls: not in the topological layer");
      continue;
    }
    data.corridor = !(x_pair && y_pair);
    if (x_pair) data.pairs.insert(data.pairs.end(), {sides[0].ref, sides[1].ref});
    if (y_pair) data.pairs.insert(data.pairs.end(), {sides[2].ref, sides[3].ref});
    // Where the factor is zero on the plan: on the mid-line of each pair, (n_a - n_b)·p = d_b - d_a.
    Eigen::Matrix2d M;
    Eigen::Vector2d v;
    for (std::size_t p = 0; p < data.pairs.size() / 2; ++p) {
      const WallNode& a = g.nodes[static_cast<std::size_t>(data.pairs[2 * p].node)];
      const WallNode& b = g.nodes[static_cast<std::size_t>(data.pairs[2 * p + 1].node)];
      M.row(static_cast<Eigen::Index>(p)) = (a.normal(data.pairs[2 * p].face) - b.normal(data.pairs[2 * p + 1].face)).transpose();
      v[static_cast<Eigen::Index>(p)] = b.d(data.pairs[2 * p + 1].face) - a.d(data.pairs[2 * p].face);
    }
    if (data.corridor) {
      const Eigen::Vector2d m = M.row(0).transpose();
      data.plan_centre = room.centre - (m.dot(room.centre) - v[0]) / m.squaredNorm() * m;
    } else {
      if (std::abs(M.determinant()) < 1e-6) {
        warnings.push_back("room '" + data.name + "': its walls do not cross: not in the topological layer");
        continue;
      }
      data.plan_centre = M.inverse() * v;
      // S-Graphs' room is a rectangle between its two pairs; an open space of another shape
      // (an L-shaped corridor with its lobby) would tie far walls to a centre outside it.
      auto distance = [&](const FaceRef& f) {
        const WallNode& node = g.nodes[static_cast<std::size_t>(f.node)];
        return std::abs(node.face[f.face].distance(node.params.data(), data.plan_centre.x(), data.plan_centre.y()));
      };
      const double width = distance(data.pairs[0]), depth = distance(data.pairs[2]);
      if (room.area_m2 > 0 && std::abs(4 * width * depth - room.area_m2) > kRectangleTolerance * room.area_m2) {
        warnings.push_back("room '" + data.name + "' is not a rectangle between its walls: not in the topological layer");
        continue;
      }
    }
    data.centre = {data.plan_centre.x(), data.plan_centre.y()};
    const int room_index = static_cast<int>(g.rooms.size());
    for (const FaceRef& f : data.pairs) g.nodes[static_cast<std::size_t>(f.node)].rooms.push_back(room_index);
    g.rooms.push_back(std::move(data));
  }
}

}  // namespace bimloc::sgraph::detail
