#include "sgraph_fixtures.hpp"

#include "sim/worldgen/worlds.hpp"

#include <cmath>

namespace bimloc::test {
namespace {

bim::WallFace face(const Eigen::Vector2d& n, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  bim::WallFace f;
  f.plane.n = Eigen::Vector3d(n.x(), n.y(), 0.0);
  f.start = Eigen::Vector3d(a.x(), a.y(), 0.0);
  f.end = Eigen::Vector3d(b.x(), b.y(), 0.0);
  f.plane.d = -f.plane.n.dot(f.start);
  f.axis = std::abs(n.x()) >= std::abs(n.y()) ? bim::WallAxis::X : bim::WallAxis::Y;
  return f;
}

// Parameter along p -> q where it crosses segment a -> b, or a negative value.
double crossing(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d r = q - p, s = b - a;
  const double den = r.x() * s.y() - r.y() * s.x();
  if (std::abs(den) < 1e-12) return -1;
  const Eigen::Vector2d w = a - p;
  const double t = (w.x() * s.y() - w.y() * s.x()) / den, u = (w.x() * r.y() - w.y() * r.x()) / den;
  return (u >= 0 && u <= 1) ? t : -1;
}

bool inOpening(const std::vector<Opening>& openings, std::size_t wall, const bim::Wall& w, const Eigen::Vector2d& p) {
  const Eigen::Vector2d a = w.start.head<2>(), u = (w.end - w.start).head<2>().normalized();
  const double s = (p - a).dot(u);
  for (const Opening& o : openings) {
    if (o.wall != wall) continue;
    const double s0 = (o.a - a).dot(u), s1 = (o.b - a).dot(u);
    if (s > std::min(s0, s1) && s < std::max(s0, s1)) return true;
  }
  return false;
}

bool blocked(const bim::Storey& storey, const std::vector<Opening>& openings, std::size_t self, const Eigen::Vector2d& p,
             const Eigen::Vector2d& q) {
  for (std::size_t j = 0; j < storey.walls.size(); ++j) {
    if (j == self) continue;
    for (const auto& f : storey.walls[j].faces) {
      const double t = crossing(p, q, f.start.head<2>(), f.end.head<2>());
      if (t <= 1e-9 || t >= 1 - 1e-9) continue;
      if (!inOpening(openings, j, storey.walls[j], p + t * (q - p))) return true;
    }
  }
  return false;
}

}  // namespace

bim::Wall boxWall(const std::string& id, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness_m) {
  bim::Wall w;
  w.id = w.name = id;
  w.ifc_type = "IfcWall";
  w.start = Eigen::Vector3d(a.x(), a.y(), 0.0);
  w.end = Eigen::Vector3d(b.x(), b.y(), 0.0);
  w.height_m = 2.8;
  w.thickness_m = thickness_m;
  const Eigen::Vector2d u = (b - a).normalized(), left(-u.y(), u.x());
  const double h = thickness_m / 2;
  w.faces[0] = face(left, a + h * left, b + h * left);
  w.faces[1] = face(-left, b - h * left, a - h * left);
  w.source = "mesh";
  return w;
}

bim::Wall liftedWall(bim::Wall w, double z0_m, double height_m) {
  for (Eigen::Vector3d* p : {&w.start, &w.end, &w.faces[0].start, &w.faces[0].end, &w.faces[1].start, &w.faces[1].end})
    p->z() = z0_m;
  w.height_m = height_m;
  return w;
}

bim::Room boxRoom(const std::string& name, double x0, double y0, double x1, double y1, const std::vector<bim::RoomWall>& walls) {
  bim::Room r;
  r.id = r.name = name;
  r.footprint = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  r.area_m2 = (x1 - x0) * (y1 - y0);
  r.centre = {(x0 + x1) / 2, (y0 + y1) / 2};
  r.height_m = 2.8;
  r.walls = walls;
  r.topology_source = "geometry";
  return r;
}

bim::Storey shiftedWall(const bim::Storey& storey, std::size_t index, double offset_m) {
  bim::Storey s = storey;
  bim::Wall& w = s.walls.at(index);
  const Eigen::Vector3d shift = offset_m * w.faces[0].plane.n;
  w.start += shift, w.end += shift;
  for (auto& f : w.faces) {
    f.start += shift, f.end += shift;
    f.plane.d = -f.plane.n.dot(f.start);
  }
  return s;
}

std::vector<Opening> worldOpenings(const std::string& world, const bim::Storey& storey) {
  const auto spec = worldgen::makeWorld(world).storeys.at(0);
  std::vector<Opening> out;
  for (const auto& door : spec.doors) {
    const auto& ws = spec.walls.at(static_cast<std::size_t>(door.wall));
    for (std::size_t i = 0; i < storey.walls.size(); ++i) {
      if (storey.walls[i].name != ws.name) continue;
      const Eigen::Vector2d u = (ws.end - ws.start).normalized(), c = ws.start + door.offset_m * u;
      out.push_back({i, c - door.width_m / 2 * u, c + door.width_m / 2 * u});
    }
  }
  return out;
}

std::vector<planes::ObservedPlane> syntheticWalls(const bim::Storey& truth, const std::vector<Opening>& openings,
                                                  const Eigen::Isometry3d& T_map_lidar, const SyntheticLidar& lidar,
                                                  std::mt19937_64& rng) {
  std::vector<planes::ObservedPlane> out;
  const Eigen::Vector3d t = T_map_lidar.translation();
  const Eigen::Vector2d p = t.head<2>();
  const Eigen::Matrix3d R = T_map_lidar.linear();
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (std::size_t i = 0; i < truth.walls.size(); ++i) {
    const bim::Wall& wall = truth.walls[i];
    for (const auto& f : wall.faces) {
      const Eigen::Vector2d n = f.plane.n.head<2>(), a = f.start.head<2>(), b = f.end.head<2>();
      if (n.dot(p) + f.plane.d < 0.2) continue;  // behind it, or too close
      const int samples = static_cast<int>(std::ceil((b - a).norm() / lidar.step_m));
      std::vector<Eigen::Vector2d> seen;
      for (int k = 0; k <= samples; ++k) {
        const Eigen::Vector2d q = a + (b - a) * (static_cast<double>(k) / samples);
        if ((q - p).norm() > lidar.range_m || inOpening(openings, i, wall, q) || blocked(truth, openings, i, p, q)) continue;
        seen.push_back(q);
      }
      // The longest run of consecutive visible samples: what the plane extraction keeps.
      std::size_t best_from = 0, best_to = 0;
      for (std::size_t from = 0; from < seen.size();) {
        std::size_t to = from + 1;
        while (to < seen.size() && (seen[to] - seen[to - 1]).norm() < 1.5 * lidar.step_m) ++to;
        if (to - from > best_to - best_from) best_from = from, best_to = to;
        from = to;
      }
      if (best_to - best_from < 2) continue;
      const double extent = (seen[best_to - 1] - seen[best_from]).norm();
      if (extent < lidar.min_extent_m) continue;
      Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
      for (std::size_t k = best_from; k < best_to; ++k) centroid += seen[k];
      centroid /= static_cast<double>(best_to - best_from);
      // The face in the lidar frame (a plane moves with a pose: n' = R^T n, d' = d + n·t), plus noise.
      const Eigen::Vector3d n_map(n.x(), n.y(), 0.0);
      const Eigen::Vector3d n_s = R.transpose() * n_map;
      Eigen::Vector3d minimal = planes::minimalPlane(n_s, f.plane.d + n_map.dot(t));
      const double deg = M_PI / 180.0;
      minimal += Eigen::Vector3d(lidar.sigma_azimuth_deg * deg * gauss(rng), lidar.sigma_elevation_deg * deg * gauss(rng),
                                 lidar.sigma_d_m * gauss(rng));
      planes::ObservedPlane o;
      o.normal = Eigen::Vector3d(std::cos(minimal[1]) * std::cos(minimal[0]), std::cos(minimal[1]) * std::sin(minimal[0]), std::sin(minimal[1]));
      o.d = minimal[2];
      o.covariance = Eigen::Vector3d(std::pow(lidar.sigma_azimuth_deg * deg, 2), std::pow(lidar.sigma_elevation_deg * deg, 2),
                                     std::pow(lidar.sigma_d_m, 2)).asDiagonal();
      o.inliers = 200;
      o.extent_m = extent;
      o.height_extent_m = 2.0;
      o.centroid = R.transpose() * (Eigen::Vector3d(centroid.x(), centroid.y(), t.z()) - t);
      o.rms_m = lidar.sigma_d_m;
      o.vertical = true;
      if (lidar.spans) {
        const Eigen::Vector2d middle = 0.5 * (seen[best_from] + seen[best_to - 1]);
        o.wall_span_m = extent;
        o.wall_span_middle = R.transpose() * (Eigen::Vector3d(middle.x(), middle.y(), t.z()) - t);
      }
      out.push_back(o);
    }
  }
  return out;
}

}  // namespace bimloc::test
