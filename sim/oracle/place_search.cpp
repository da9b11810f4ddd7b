#include "sim/oracle/place_search.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::sim::oracle {
namespace {

constexpr int kRootCells = 32;   // a root node's side in lattice positions (3.2 m at 0.1 m)
constexpr int kRootAngles = 8;   // ... and its headings (16 deg at 2 deg)
constexpr int kRefineLevels = 4;  // local search steps: 1/4 of the cell, halved three times
constexpr int kCellBoundDepth = 2;  // a cell's bound tightened over its eighths and sixty-fourths

struct Node {
  int i0 = 0, j0 = 0, ni = 1, nj = 1, t0 = 0, nt = 1;
  float bound = 0;
  bool leaf() const { return ni == 1 && nj == 1 && nt == 1; }
};

// The least and the largest |heading - truth| over the node's lattice headings (an arc).
std::pair<double, double> angleRange(const Lattice& l, const Node& n, double truth) {
  const double two_pi = 2.0 * M_PI, first = n.t0 * l.step_rad, arc = (n.nt - 1) * l.step_rad;
  const auto mod = [&](double a) { return a - two_pi * std::floor(a / two_pi); };
  const double u = mod(truth - first);
  const double least = u <= arc ? 0.0 : std::min(u - arc, two_pi - u);
  const double v = mod(truth + M_PI - first);
  const double most = v <= arc ? M_PI : std::max(std::abs(wrapAngle(first - truth)), std::abs(wrapAngle(first + arc - truth)));
  return {least, most};
}

// The least and the largest distance from the truth's position to the node's lattice positions.
std::pair<double, double> distanceRange(const Lattice& l, const Node& n, const Eigen::Vector2d& truth) {
  const Eigen::Vector2d lo = l.origin + l.step_m * Eigen::Vector2d(n.i0, n.j0);
  const Eigen::Vector2d hi = l.origin + l.step_m * Eigen::Vector2d(n.i0 + n.ni - 1, n.j0 + n.nj - 1);
  const Eigen::Vector2d nearest = truth.cwiseMax(lo).cwiseMin(hi);
  const Eigen::Vector2d far((truth.x() - lo.x() > hi.x() - truth.x()) ? lo.x() : hi.x(),
                            (truth.y() - lo.y() > hi.y() - truth.y()) ? lo.y() : hi.y());
  return {(nearest - truth).norm(), (far - truth).norm()};
}

// Whether the region holds none of the node's poses (skip it), all of them, or some.
bool regionHoldsNone(const SearchContext& c, Region region, const Node& n) {
  const auto [d_least, d_most] = distanceRange(c.lattice, n, c.zone.start.head<2>());
  const auto [a_least, a_most] = angleRange(c.lattice, n, c.zone.start.z());
  const bool all_in_zone = d_most <= c.zone.radius_m && a_most <= c.zone.angle_rad;
  const bool none_in_zone = d_least > c.zone.radius_m || a_least > c.zone.angle_rad;
  if (region == Region::Truth) return none_in_zone;
  return all_in_zone || c.lattice.freeIn(n.i0, n.j0, n.ni, n.nj) == 0;
}

float nodeBound(const SearchContext& c, const Node& n, float stop_below) {
  const Lattice& l = c.lattice;
  const double cx = l.origin.x() + (n.i0 + 0.5 * (n.ni - 1)) * l.step_m, cy = l.origin.y() + (n.j0 + 0.5 * (n.nj - 1)) * l.step_m;
  const double yaw = (n.t0 + 0.5 * (n.nt - 1)) * l.step_rad;
  return boundOver(c, {cx, cy, yaw}, {0.5 * n.ni * l.step_m, 0.5 * n.nj * l.step_m, 0.5 * n.nt * l.step_rad}, stop_below);
}

std::vector<Node> children(const SearchContext& c, const Node& n) {
  const Lattice& l = c.lattice;
  // Split what spreads the points more: the translation or the turn (at the points' rms range).
  const double spread_turn = 2.0 * c.path.r_rms * std::sin(0.25 * n.nt * l.step_rad);
  const bool split_translation = (n.ni > 1 || n.nj > 1) && (n.nt == 1 || 0.5 * std::max(n.ni, n.nj) * l.step_m >= spread_turn);
  std::vector<Node> out;
  if (split_translation) {
    const int ni1 = (n.ni + 1) / 2, nj1 = (n.nj + 1) / 2;
    for (const auto& [i0, ni] : {std::pair{n.i0, ni1}, std::pair{n.i0 + ni1, n.ni - ni1}})
      for (const auto& [j0, nj] : {std::pair{n.j0, nj1}, std::pair{n.j0 + nj1, n.nj - nj1}})
        if (ni > 0 && nj > 0) out.push_back({i0, j0, ni, nj, n.t0, n.nt, 0});
  } else {
    const int nt1 = (n.nt + 1) / 2;
    out.push_back({n.i0, n.j0, n.ni, n.nj, n.t0, nt1, 0});
    out.push_back({n.i0, n.j0, n.ni, n.nj, n.t0 + nt1, n.nt - nt1, 0});
  }
  return out;
}

// Whether some start in the box (centre, half-widths) may score at least `bar`: its bound, and
// below the lattice the bounds of its eight halves, down to `depth` more halvings. A cell none of
// whose parts may reach the bar is skipped without its local search (the bound still holds).
bool mayReach(const SearchContext& c, const Eigen::Vector3d& centre, const Eigen::Vector3d& half, float bar, int depth) {
  if (boundOver(c, centre, half, bar) < bar) return false;
  if (depth == 0) return true;
  const Eigen::Vector3d quarter = 0.5 * half;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d part = centre + Eigen::Vector3d(k & 1 ? quarter.x() : -quarter.x(), k & 2 ? quarter.y() : -quarter.y(),
                                                          k & 4 ? quarter.z() : -quarter.z());
    if (mayReach(c, part, quarter, bar, depth - 1)) return true;
  }
  return false;
}

bool leafInRegion(const SearchContext& c, Region region, int i, int j, int t) {
  const Eigen::Vector3d p = c.lattice.pose(i, j, t);
  const bool in_zone = (p.head<2>() - c.zone.start.head<2>()).norm() <= c.zone.radius_m &&
                       std::abs(wrapAngle(p.z() - c.zone.start.z())) <= c.zone.angle_rad;
  if (region == Region::Truth) return in_zone;
  return !in_zone && c.lattice.free[static_cast<std::size_t>(j) * c.lattice.nx + i];
}

}  // namespace

Lattice::Lattice(const DistanceField& field, const OracleConfig& config)
    : origin(field.lower()), step_m(config.grid_m) {
  nx = static_cast<int>(std::floor((field.upper().x() - field.lower().x()) / step_m)) + 1;
  ny = static_cast<int>(std::floor((field.upper().y() - field.lower().y()) / step_m)) + 1;
  nt = static_cast<int>(std::lround(360.0 / config.grid_deg));
  step_rad = 2.0 * M_PI / nt;
  free.assign(static_cast<std::size_t>(nx) * ny, 0);
  free_sum.assign(static_cast<std::size_t>(nx + 1) * (ny + 1), 0);
  int count = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector3d p = pose(i, j, 0);
      const bool f = field.at(static_cast<float>(p.x()), static_cast<float>(p.y())) >= config.clearance_m;
      free[static_cast<std::size_t>(j) * nx + i] = f;
      count += f;
      free_sum[static_cast<std::size_t>(j + 1) * (nx + 1) + i + 1] = f + free_sum[static_cast<std::size_t>(j) * (nx + 1) + i + 1] +
                                                                    free_sum[static_cast<std::size_t>(j + 1) * (nx + 1) + i] -
                                                                    free_sum[static_cast<std::size_t>(j) * (nx + 1) + i];
    }
  free_area_m2 = count * step_m * step_m;
}

int Lattice::freeIn(int i0, int j0, int ni, int nj) const {
  const auto at = [&](int i, int j) { return free_sum[static_cast<std::size_t>(j) * (nx + 1) + i]; };
  return at(i0 + ni, j0 + nj) - at(i0, j0 + nj) - at(i0 + ni, j0) + at(i0, j0);
}

float valueAt(const SearchContext& c, double x, double y, double yaw, float stop_below) {
  if (c.discount) return robustScore(c.field, c.model, c.path, *c.discount, x, y, yaw, stop_below);
  return pathScore(c.field, c.model, c.path, x, y, yaw, stop_below);
}

float boundOver(const SearchContext& c, const Eigen::Vector3d& centre, const Eigen::Vector3d& half, float stop_below) {
  if (c.discount)
    return robustBound(c.field, c.model, c.path, *c.discount, centre.x(), centre.y(), centre.z(), half.x(), half.y(), half.z(),
                       stop_below);
  return pathBound(c.field, c.model, c.path, centre.x(), centre.y(), centre.z(), half.x(), half.y(), half.z(), stop_below);
}

float cellValue(const SearchContext& c, int i, int j, int t, Eigen::Vector3d* best_pose, float stop_at) {
  const Lattice& l = c.lattice;
  const Eigen::Vector3d centre = l.pose(i, j, t);
  const Eigen::Vector3d half(0.5 * l.step_m, 0.5 * l.step_m, 0.5 * l.step_rad);
  Eigen::Vector3d p = centre;
  float v = valueAt(c, p.x(), p.y(), p.z());
  Eigen::Vector3d step(0.25 * l.step_m, 0.25 * l.step_m, 0.25 * l.step_rad);
  for (int level = 0; level < kRefineLevels && v < stop_at; ++level, step *= 0.5) {
    for (bool improved = true; improved && v < stop_at;) {
      improved = false;
      for (int axis = 0; axis < 3 && v < stop_at; ++axis)
        for (const double sign : {1.0, -1.0}) {
          Eigen::Vector3d q = p;
          q[axis] += sign * step[axis];
          if (std::abs(q[axis] - centre[axis]) > half[axis] + 1e-12) continue;
          const float w = valueAt(c, q.x(), q.y(), q.z(), v);
          if (w > v) {
            v = w, p = q, improved = true;
            break;
          }
        }
    }
  }
  if (best_pose) *best_pose = p;
  return v;
}

SearchAnswer searchPlaces(const SearchContext& c, Region region, float bar, bool stop_at_bar) {
  const Lattice& l = c.lattice;
  SearchAnswer answer;
  const auto level = [&] { return stop_at_bar ? bar : std::max(bar, answer.best); };
  // Roots: blocks of the lattice, best bound first (the search finds good cells early).
  std::vector<Node> roots;
  for (int j = 0; j < l.ny; j += kRootCells)
    for (int i = 0; i < l.nx; i += kRootCells)
      for (int t = 0; t < l.nt; t += kRootAngles) {
        Node n{i, j, std::min(kRootCells, l.nx - i), std::min(kRootCells, l.ny - j), t, std::min(kRootAngles, l.nt - t), 0};
        if (regionHoldsNone(c, region, n)) continue;
        n.bound = nodeBound(c, n, bar);
        ++answer.nodes;
        if (n.bound >= bar) roots.push_back(n);
      }
  std::sort(roots.begin(), roots.end(), [](const Node& a, const Node& b) { return a.bound < b.bound; });
  std::vector<Node> stack = std::move(roots);  // the best on top
  while (!stack.empty()) {
    const Node n = stack.back();
    stack.pop_back();
    if (n.bound < level()) continue;
    if (n.leaf()) {
      if (!leafInRegion(c, region, n.i0, n.j0, n.t0)) continue;
      const Eigen::Vector3d half(0.5 * l.step_m, 0.5 * l.step_m, 0.5 * l.step_rad);
      if (!mayReach(c, l.pose(n.i0, n.j0, n.t0), half, level(), kCellBoundDepth)) continue;
      Eigen::Vector3d pose;
      const float v = cellValue(c, n.i0, n.j0, n.t0, &pose, stop_at_bar ? bar : std::numeric_limits<float>::infinity());
      ++answer.cells;
      if (v > answer.best) answer.best = v, answer.pose = pose;
      if (v >= bar) answer.reached = true;
      if (stop_at_bar && answer.reached) return answer;
      continue;
    }
    std::vector<Node> next;
    for (Node child : children(c, n)) {
      if (regionHoldsNone(c, region, child)) continue;
      child.bound = nodeBound(c, child, level());
      ++answer.nodes;
      if (child.bound >= level()) next.push_back(child);
    }
    std::sort(next.begin(), next.end(), [](const Node& a, const Node& b) { return a.bound < b.bound; });
    stack.insert(stack.end(), next.begin(), next.end());
  }
  return answer;
}

SearchAnswer searchEveryPlace(const SearchContext& c, Region region) {
  SearchAnswer answer;
  const Lattice& l = c.lattice;
  for (int j = 0; j < l.ny; ++j)
    for (int i = 0; i < l.nx; ++i)
      for (int t = 0; t < l.nt; ++t) {
        if (!leafInRegion(c, region, i, j, t)) continue;
        Eigen::Vector3d pose;
        const float v = cellValue(c, i, j, t, &pose);
        ++answer.cells;
        if (v > answer.best) answer.best = v, answer.pose = pose;
      }
  answer.reached = answer.cells > 0;
  return answer;
}

}  // namespace bimloc::sim::oracle
