// A spatial index of wall faces: which faces pass near a point of the floor. Matching an
// observed plane against every face of a storey costs what the building costs; matching it
// against the faces that pass near where its points lie costs what the robot can see. The
// index answers conservatively: every face within the radius is visited (once), some farther
// ones may be, so a match made through it is the match brute force would make.
#pragma once

#include "cell_scale.hpp"
#include "landmark.hpp"

#include <algorithm>
#include <cmath>

#include <cstdint>
#include <limits>
#include <vector>

namespace bimloc::pf::detail {

class FaceIndex {
 public:
  explicit FaceIndex(std::vector<Landmark> faces, double cell_m = 1.0);
  // The same faces() (the same positions), but only those with keep[i] in the cells: a query
  // visits the kept faces forEachNear of the whole index would visit, in the same order.
  FaceIndex(std::vector<Landmark> faces, double cell_m, const std::vector<bool>& keep);

  const std::vector<Landmark>& faces() const { return faces_; }
  bool empty() const { return faces_.empty(); }

  // Calls visit(face) once for every face whose base segment comes within radius_m of
  // `centre` (and possibly for a few a little farther), in an order that depends on the cells
  // (see visitsBefore). Not thread-safe: the visited marks are the index's own scratch (one
  // index per filter, and a filter runs on one thread).
  template <class Visit>
  void forEachNear(const Eigen::Vector2d& centre, double radius_m, Visit&& visit) const {
    if (faces_.empty()) return;
    if (++stamp_ == 0) std::fill(seen_.begin(), seen_.end(), 0u), stamp_ = 1;
    forEachCellRun(centre, radius_m, [&](const std::uint32_t* f, const std::uint32_t* end) {
      for (; f != end; ++f) {
        if (seen_[*f] == stamp_) continue;
        seen_[*f] = stamp_;
        visit(faces_[*f]);
      }
      return true;
    });
  }

  // Whether forEachNear(centre, radius_m) would visit faces()[a] before faces()[b] (either may
  // be missing). Leaves the visited marks alone: callable from inside forEachNear.
  bool visitsBefore(const Eigen::Vector2d& centre, double radius_m, std::uint32_t a, std::uint32_t b) const {
    bool first_a = false;
    forEachCellRun(centre, radius_m, [&](const std::uint32_t* f, const std::uint32_t* end) {
      for (; f != end; ++f)
        if (*f == a || *f == b) return first_a = *f == a, false;
      return true;
    });
    return first_a;
  }

 private:
  // Calls run(first, end) with the face ids of each run of cells whose centre is within the
  // radius plus half a cell diagonal, rows upwards, cells left to right, until run says stop.
  template <class Run>
  void forEachCellRun(const Eigen::Vector2d& centre, double radius_m, Run&& run) const {
    const double r = radius_m + 0.7072 * cell_m_;  // cells whose centre is this close may touch the disc
    const int x0 = std::max(0, cellX(centre.x() - r)), x1 = std::min(nx_ - 1, cellX(centre.x() + r));
    const int y0 = std::max(0, cellY(centre.y() - r)), y1 = std::min(ny_ - 1, cellY(centre.y() + r));
    if (x0 > x1 || y0 > y1) return;
    const double r2 = r * r;
    for (int iy = y0; iy <= y1; ++iy) {
      const double cy = origin_.y() + (iy + 0.5) * cell_m_ - centre.y();
      const double rest = r2 - cy * cy;
      if (rest < 0.0) continue;
      // The row's cells whose centre is within r: one run of cells, found from the chord and
      // nudged until the test holds exactly at its ends (it is monotone in |cx|).
      const double half = std::sqrt(rest);
      const auto inside = [&](int ix) {
        const double cx = origin_.x() + (ix + 0.5) * cell_m_ - centre.x();
        return cx * cx + cy * cy <= r2;
      };
      int a = std::clamp(cellX(centre.x() - half), x0, x1), b = std::clamp(cellX(centre.x() + half), x0, x1);
      while (a > x0 && inside(a - 1)) --a;
      while (a <= b && !inside(a)) ++a;
      while (b < x1 && inside(b + 1)) ++b;
      while (b >= a && !inside(b)) --b;
      if (a > b) continue;
      const std::size_t row = static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_);
      if (!run(members_.data() + starts_[row + a], members_.data() + starts_[row + b + 1])) return;
    }
  }

  int cellX(double x) const { return static_cast<int>(std::floor(per_cell_(x - origin_.x()))); }
  int cellY(double y) const { return static_cast<int>(std::floor(per_cell_(y - origin_.y()))); }

  std::vector<Landmark> faces_;
  double cell_m_ = 1.0;
  CellScale per_cell_{1.0};  // x / cell_m_, the same bits
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int nx_ = 0, ny_ = 0;
  // The faces of each cell (whose segment passes near it), cell after cell in row-major order:
  // cell k holds members_[starts_[k] .. starts_[k + 1]), so a run of cells is one run of ids.
  std::vector<std::uint32_t> starts_;
  std::vector<std::uint32_t> members_;
  mutable std::vector<std::uint32_t> seen_;
  mutable std::uint32_t stamp_ = 0;
};

// How far from an observed plane's centroid a face can lie and still match it under the gate
// (measurement.cpp): the face's line passes within
//   sqrt(gate) sigma_d + 2 sin(sqrt(2 gate) max(sigma_az, sigma_el) / 2) * range + slack
// of the centroid (the planes agree in d at the particle and in angle within the gate, and the
// centroid is `range` from the particle), and the centroid lies along the face to within the
// segment margin. Infinite when the angle gate is so wide that any face could match.
// behind_m: how far behind a face a plane may stand and still match it (an opening's filling).
double matchRadius(double range_m, double sigma_d_m, double sigma_angle_rad, double gate_mahalanobis2, double margin_m,
                   double behind_m = 0.0);
// The same radius with what does not depend on the range worked out once (a matcher asks for
// it per observation and pose): at(range_m) is matchRadius's value, to the bit.
struct MatchReach {
  MatchReach(double sigma_d_m, double sigma_angle_rad, double gate_mahalanobis2, double margin_m, double behind_m = 0.0);
  double at(double range_m) const { return infinite ? std::numeric_limits<double>::infinity() : std::hypot(across_m + chord * range_m + 0.1, margin_m); }
  double across_m = 0, chord = 0, margin_m = 0;
  bool infinite = false;
};

}  // namespace bimloc::pf::detail
