#include "extraction.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bimloc::bim::detail {
namespace {

// A footprint that fills less of its bounding rectangle than this is not a straight wall
// (curved, L-shaped, strongly mitred): its faces are a best fit and a warning says so.
constexpr double kMinBoxFill = 0.85;

WallFace makeFace(const Eigen::Vector2d& normal_xy, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double z) {
  WallFace face;
  face.plane.n = Eigen::Vector3d(normal_xy.x(), normal_xy.y(), 0.0);
  face.start = Eigen::Vector3d(a.x(), a.y(), z);
  face.end = Eigen::Vector3d(b.x(), b.y(), z);
  face.plane.d = -face.plane.n.dot(face.start);  // paper Eq. 1: d = -(a nx + b ny + c nz)
  face.axis = std::abs(normal_xy.x()) >= std::abs(normal_xy.y()) ? WallAxis::X : WallAxis::Y;
  return face;
}

}  // namespace

std::optional<Wall> wallFromGeometry(const RawProduct& product, std::string& problem) {
  std::vector<Eigen::Vector2d> xy;
  double z_min = std::numeric_limits<double>::infinity(), z_max = -z_min;
  Wall wall;
  if (!product.mesh.empty()) {
    wall.source = "mesh";
    for (const auto& v : product.mesh.vertices) {
      xy.emplace_back(v.x(), v.y());
      z_min = std::min(z_min, double(v.z())), z_max = std::max(z_max, double(v.z()));
    }
  } else if (product.extrusion) {
    wall.source = "profile";
    for (const auto& c : product.extrusion->corners) xy.emplace_back(c.x(), c.y());
    z_min = product.extrusion->z_min, z_max = product.extrusion->z_max;
  } else {
    problem = product.geometry_problem.empty() ? "no body geometry" : product.geometry_problem;
    return std::nullopt;
  }
  for (const auto& p : xy)
    if (!p.allFinite()) {
      problem = "non-finite coordinates in its geometry";
      return std::nullopt;
    }
  const Polygon2 hull = convexHull(xy);
  const Rectangle2 box = minAreaRectangle(hull);
  if (hull.size() < 3 || box.width < 1e-3 || box.length < 1e-3 || z_max - z_min < 1e-3) {
    problem = "degenerate geometry (no length, thickness or height)";
    return std::nullopt;
  }
  const double fill = std::abs(signedArea(hull)) / (box.length * box.width);
  wall.approximated = fill < kMinBoxFill || (product.extrusion && product.mesh.empty() && !product.extrusion->vertical);
  if (wall.approximated)
    problem = "not a straight vertical box (footprint fills " + std::to_string(int(std::round(100 * fill))) +
              "% of its rectangle): faces approximated";

  // A deterministic axis direction: the dominant component positive.
  Eigen::Vector2d u = box.axis;
  if (std::abs(u.x()) >= std::abs(u.y()) ? u.x() < 0 : u.y() < 0) u = -u;
  const Eigen::Vector2d left(-u.y(), u.x());
  const Eigen::Vector2d s = box.centre - 0.5 * box.length * u, e = box.centre + 0.5 * box.length * u;
  const double half = 0.5 * box.width;

  wall.id = product.global_id;
  wall.name = product.name;
  wall.ifc_type = product.ifc_class;
  wall.start = Eigen::Vector3d(s.x(), s.y(), z_min);
  wall.end = Eigen::Vector3d(e.x(), e.y(), z_min);
  wall.height_m = z_max - z_min;
  wall.thickness_m = box.width;
  // The double-sided wall (paper Eq. 2): the second face is the first flipped and moved by
  // the thickness. Both are stored explicitly, each with its own start point and d.
  wall.faces[0] = makeFace(left, s + half * left, e + half * left, z_min);
  wall.faces[1] = makeFace(-left, e - half * left, s - half * left, z_min);
  return wall;
}

Eigen::Vector2d planMiddle(std::vector<Eigen::Vector2d> points) {
  points.erase(std::remove_if(points.begin(), points.end(), [](const Eigen::Vector2d& p) { return !p.allFinite(); }), points.end());
  if (points.empty()) return Eigen::Vector2d::Zero();
  const auto median = [&](int axis) {
    std::vector<double> v;
    for (const auto& p : points) v.push_back(p[axis]);
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  return {median(0), median(1)};
}

namespace {

std::string farFromPlan(const std::vector<Eigen::Vector2d>& xy, double z_min, double z_max, const Eigen::Vector2d& middle) {
  double farthest = std::max(std::abs(z_min), std::abs(z_max));
  for (const auto& p : xy) farthest = std::max(farthest, (p - middle).cwiseAbs().maxCoeff());
  if (!std::isnan(farthest) && !(farthest > kFarthestElementM)) return "";
  char text[140];
  std::snprintf(text, sizeof text, "a coordinate %.3g m from the middle of the plan's walls (no building is %.0f km long: damage?)",
                farthest, kFarthestElementM / 1000.0);
  return text;
}

}  // namespace

std::string farFromPlan(const Wall& wall, const Eigen::Vector2d& middle) {
  return farFromPlan({wall.start.head<2>(), wall.end.head<2>()}, wall.start.z(), wall.start.z() + wall.height_m, middle);
}

std::string farFromPlan(const Room& room, const Eigen::Vector2d& middle) {
  return farFromPlan(room.footprint, room.floor_z, room.floor_z + room.height_m, middle);
}

}  // namespace bimloc::bim::detail
