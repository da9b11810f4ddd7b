#include "peers/amcl/likelihood_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::peers::amcl {
namespace {

// Felzenszwalb & Huttenlocher, "Distance Transforms of Sampled Functions" (2012), algorithm 1:
// the lower envelope of the parabolas (q - p)^2 + f(p), in place, in O(n). f holds squared
// distances in cells (a large number where the row has no obstacle yet).
void squaredDistance1d(std::vector<double>& f, std::vector<int>& v, std::vector<double>& z, std::vector<double>& out) {
  const int n = static_cast<int>(f.size());
  const double inf = std::numeric_limits<double>::infinity();
  int k = 0;
  v[0] = 0, z[0] = -inf, z[1] = inf;
  const auto meet = [&f](int q, int p) { return ((f[q] + static_cast<double>(q) * q) - (f[p] + static_cast<double>(p) * p)) / (2.0 * (q - p)); };
  for (int q = 1; q < n; ++q) {
    double s = meet(q, v[k]);
    while (s <= z[k]) s = meet(q, v[--k]);  // z[0] = -inf stops it
    ++k;
    v[k] = q, z[k] = s, z[k + 1] = inf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double d = q - v[k];
    out[q] = d * d + f[v[k]];
  }
  std::copy(out.begin(), out.end(), f.begin());
}

}  // namespace

LikelihoodField::LikelihoodField(const Grid& grid, double max_dist_m) : grid_(&grid), max_dist_m_(max_dist_m) {
  // An exact Euclidean transform, capped afterwards (ROS amcl grows a brushfire out to
  // max_occ_dist, which gives the same distances up to its propagation's approximation).
  const int w = grid.width, h = grid.height;
  const double far = 1e12;  // "no obstacle": finite so that the parabola arithmetic stays exact
  std::vector<double> d2(grid.size());
  for (std::size_t c = 0; c < d2.size(); ++c) d2[c] = grid.occupied[c] ? 0.0 : far;
  const int n = std::max(w, h);
  std::vector<double> f(n), out(n), z(n + 1);
  std::vector<int> v(n);
  f.resize(w), out.resize(w);
  for (int j = 0; j < h; ++j) {
    std::copy_n(d2.begin() + static_cast<std::ptrdiff_t>(grid.index(0, j)), w, f.begin());
    squaredDistance1d(f, v, z, out);
    std::copy_n(f.begin(), w, d2.begin() + static_cast<std::ptrdiff_t>(grid.index(0, j)));
  }
  f.resize(h), out.resize(h);
  for (int i = 0; i < w; ++i) {
    for (int j = 0; j < h; ++j) f[j] = d2[grid.index(i, j)];
    squaredDistance1d(f, v, z, out);
    for (int j = 0; j < h; ++j) d2[grid.index(i, j)] = f[j];
  }
  distance_m_.resize(d2.size());
  for (std::size_t c = 0; c < d2.size(); ++c)
    distance_m_[c] = static_cast<float>(std::min(max_dist_m, std::sqrt(d2[c]) * grid.resolution_m));
}

}  // namespace bimloc::peers::amcl
