#include "room_association.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace bimloc::sgraph::detail {
namespace {

constexpr double kParallelCos = 0.985;  // 10 degrees
constexpr double kMinRoomWidth_m = 0.8, kMaxRoomWidth_m = 40.0;

struct Seen {
  int node = -1, face = 0;
  Eigen::Vector2d n = Eigen::Vector2d::UnitX();
  double d = 0, distance = 0;  // the plane, and the robot's distance to it
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
};

// A pair of opposite walls around the robot: the nearest facing each way along one axis.
struct Pair {
  Seen a, b;
  Eigen::Vector2d m = Eigen::Vector2d::Zero();  // mid-line (n_a - n_b)·p = v
  double v = 0;
};

std::optional<Pair> pairAround(const std::vector<Seen>& seen, int axis) {
  const Seen* side[2] = {nullptr, nullptr};
  for (const Seen& s : seen) {
    const bool x_wall = std::abs(s.n.x()) >= std::abs(s.n.y());
    if (x_wall != (axis == 0)) continue;
    const int slot = s.n[axis] > 0 ? 0 : 1;
    if (!side[slot] || s.distance < side[slot]->distance) side[slot] = &s;
  }
  if (!side[0] || !side[1] || side[0]->n.dot(side[1]->n) > -kParallelCos) return std::nullopt;
  const double width = side[0]->distance + side[1]->distance;
  if (width < kMinRoomWidth_m || width > kMaxRoomWidth_m) return std::nullopt;
  Pair p{*side[0], *side[1], side[0]->n - side[1]->n, side[1]->d - side[0]->d};
  return p;
}

// The room node the pairs match, or -1.
int matchRoom(const Graph& g, const std::vector<Pair>& pairs, const Eigen::Vector2d& robot, const SGraphConfig& c) {
  int best = -1;
  double best_distance = c.room_match_distance_m;
  for (std::size_t r = 0; r < g.rooms.size(); ++r) {
    const RoomData& room = g.rooms[r];
    const Eigen::Vector2d centre(room.centre[0], room.centre[1]);
    double distance = 0;
    if (pairs.size() == 2) {
      if (room.corridor) continue;
      Eigen::Matrix2d M;
      M << pairs[0].m.transpose(), pairs[1].m.transpose();
      if (std::abs(M.determinant()) < 1e-6) return -1;
      distance = (M.inverse() * Eigen::Vector2d(pairs[0].v, pairs[1].v) - centre).norm();
    } else {
      // One pair: how far the room's centre is from its mid-line, and the robot must be in the room.
      if (!bim::pointInPolygon(room.footprint, robot)) continue;
      distance = std::abs(pairs[0].m.dot(centre) - pairs[0].v) / pairs[0].m.norm();
    }
    if (distance < best_distance) best_distance = distance, best = static_cast<int>(r);
  }
  return best;
}

}  // namespace

void mergeInto(Graph& g, int from, int to, int k, SGraphResult& result) {
  WallNode& source = g.nodes[static_cast<std::size_t>(from)];
  WallNode& target = g.nodes[static_cast<std::size_t>(to)];
  // Turn, then shift the plan wall so that its face k is the new plane.
  const Eigen::Vector2d n_new = source.normal(0), n_plan = target.normal(k);
  target.params[1] += wrapAngle(std::atan2(n_new.y(), n_new.x()) - std::atan2(n_plan.y(), n_plan.x()));
  const FaceGeometry& f = target.face[k];
  const double ca = std::cos(target.params[1]), sa = std::sin(target.params[1]);
  const double rc = (ca * f.e.x() - sa * f.e.y()) * f.centre.x() + (sa * f.e.x() + ca * f.e.y()) * f.centre.y();
  // d_k = -side (R e·c + h + s) - tau/2  =>  s = -side (d + tau/2) - R e·c - h
  target.params[0] = -f.side * (source.d(0) + 0.5 * target.params[2]) - rc - f.h;
  for (Keyframe& kf : g.window)
    for (PlaneMeasurement& m : kf.planes)
      if (m.node == from) m.node = to, m.face = k;
  target.observations += source.observations;
  target.last_keyframe = std::max(target.last_keyframe, source.last_keyframe);
  source.active = false;
  for (PlaneAssociation& a : result.associations) {
    if (a.kind != PlaneAssociation::Kind::NewPlane || a.new_plane != source.new_id) continue;
    a.kind = PlaneAssociation::Kind::PlanWall, a.wall = target.wall, a.face = k, a.new_plane = -1;
    --result.new_planes_matched;
    ++result.plan_walls_matched;
  }
  ++result.planes_merged;
}

int associateRooms(Graph& g, const Keyframe& kf, const SGraphConfig& c, SGraphResult& result) {
  const Eigen::Vector2d robot(kf.pose[0], kf.pose[1]);
  std::vector<Seen> seen;
  bool any_new = false;
  for (const PlaneMeasurement& m : kf.planes) {
    const WallNode& node = g.nodes[static_cast<std::size_t>(m.node)];
    if (!node.active) continue;
    Seen s{m.node, m.face, node.normal(m.face), node.d(m.face), 0.0, m.centroid_map};
    s.distance = s.n.dot(robot) + s.d;
    if (s.distance <= 0) continue;
    seen.push_back(s);
    any_new = any_new || node.kind == WallNode::Kind::New;
  }
  if (!any_new) return 0;  // only a new plane can be a duplicate
  std::vector<Pair> pairs;
  for (int axis = 0; axis < 2; ++axis)
    if (auto p = pairAround(seen, axis)) pairs.push_back(*p);
  if (pairs.empty()) return 0;
  const int r = matchRoom(g, pairs, robot, c);
  if (r < 0) return 0;
  const RoomData& room = g.rooms[static_cast<std::size_t>(r)];
  int merged = 0;
  for (const Pair& p : pairs) {
    // A pair of two new planes says where two unknown planes are, not where the room's walls
    // are: its merges would rest on nothing the map knows (Duplex B202: a counter front 0.49 m
    // before one wall and a plane 0.34 m behind the opposite one, merged together, moved the
    // robot 0.32 m). Only a pair with a wall already matched to the plan anchors the room.
    if (g.nodes[static_cast<std::size_t>(p.a.node)].kind == WallNode::Kind::New &&
        g.nodes[static_cast<std::size_t>(p.b.node)].kind == WallNode::Kind::New)
      continue;
    for (const Seen* s : {&p.a, &p.b}) {
      if (g.nodes[static_cast<std::size_t>(s->node)].kind != WallNode::Kind::New) continue;
      // The room's face on that side, along which the new plane's points lie, not seen directly.
      int best_node = -1, best_face = 0;
      double best = c.merge_max_offset_m;
      for (const FaceRef& f : room.faces) {
        const WallNode& plan = g.nodes[static_cast<std::size_t>(f.node)];
        if (!plan.active || plan.normal(f.face).dot(s->n) < kParallelCos) continue;
        const double u = plan.along(f.face, s->centroid);
        if (u < -c.segment_margin_m || u > plan.length(f.face) + c.segment_margin_m) continue;
        bool seen_directly = false;
        for (const PlaneMeasurement& m : kf.planes) seen_directly = seen_directly || m.node == f.node;
        if (seen_directly) continue;
        const double gap = std::abs(plan.face[f.face].distance(plan.params.data(), robot.x(), robot.y()) - s->distance);
        if (gap < best) best = gap, best_node = f.node, best_face = f.face;
      }
      if (best_node < 0) continue;
      mergeInto(g, s->node, best_node, best_face, result);
      ++merged;
    }
  }
  return merged;
}

}  // namespace bimloc::sgraph::detail
