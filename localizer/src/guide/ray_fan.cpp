#include "ray_fan.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace bimloc::guide::detail {

// Why a segment left out of a ray's list never passes castRay's test (t > 0, t < best <= max_m,
// 0 <= u <= 1), with computed t and u:
// - Where the ray is more than kMarginRad off the segment's direction, |denom| >= 1e-4 |e|, so
//   t and u are off their exact values by about 1e-12 of the scale (|w| / |e| for u): a computed
//   hit is within ~1e-10 m of a true point of the segment at t > 0. From an origin kNearM or more
//   away, that point's bearing is within ~1e-7 rad of the ray's, inside the widened arc, and its
//   distance is at least the segment's, so within max_m + kMarginM.
// - Rays within kMarginRad of the segment's direction (either way) are listed whatever the
//   distance, and segments within kNearM of the origin for every ray.
RayFan::RayFan(const std::vector<Segment2>& segments, const Eigen::Vector2d& origin, double heading, int rays, double max_m)
    : segments_(&segments) {
  const int n = std::max(1, rays);
  const double step = 2.0 * M_PI / n;
  // Per segment, up to three ranges of ray numbers (unwrapped; empty when the last is before the first).
  struct Ranges {
    std::array<long, 6> k{};
    int count = 0;
    bool all = false;
  };
  std::vector<Ranges> ranges(segments.size());
  const auto add = [&](Ranges& r, double from_rad, double to_rad) {
    const long k0 = static_cast<long>(std::ceil((from_rad - heading) / step));
    const long k1 = static_cast<long>(std::floor((to_rad - heading) / step));
    if (k1 - k0 + 1 >= n) r.all = true;
    if (k1 < k0 || r.all) return;
    r.k[static_cast<std::size_t>(2 * r.count)] = k0;
    r.k[static_cast<std::size_t>(2 * r.count + 1)] = k1;
    ++r.count;
  };
  const auto wrapped = [n](long k) { return static_cast<std::size_t>(((k % n) + n) % n); };
  std::vector<int> count(static_cast<std::size_t>(n), 0);
  std::vector<int> last(static_cast<std::size_t>(n), -1);
  // Counted, then filled: each ray's list in the segments' order, each segment once per ray.
  const auto visit = [&](auto&& each) {
    std::fill(last.begin(), last.end(), -1);
    for (std::size_t j = 0; j < segments.size(); ++j) {
      const Ranges& r = ranges[j];
      const int id = static_cast<int>(j);
      if (r.all) {
        for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) each(k, id);
        continue;
      }
      for (int c = 0; c < r.count; ++c)
        for (long k = r.k[static_cast<std::size_t>(2 * c)]; k <= r.k[static_cast<std::size_t>(2 * c + 1)]; ++k) {
          const std::size_t kk = wrapped(k);
          if (last[kk] == id) continue;
          last[kk] = id;
          each(kk, id);
        }
    }
  };
  for (std::size_t j = 0; j < segments.size(); ++j) {
    const Segment2& s = segments[j];
    Ranges& r = ranges[j];
    const double dist = distanceTo(s, origin);
    if (!(dist >= kNearM) || !s.a.allFinite() || !s.b.allFinite()) {
      r.all = true;
      continue;
    }
    const Eigen::Vector2d e = s.b - s.a;
    if (e.squaredNorm() > 0) {
      const double along = std::atan2(e.y(), e.x());
      add(r, along - kMarginRad, along + kMarginRad);
      add(r, along + M_PI - kMarginRad, along + M_PI + kMarginRad);
    }
    if (dist > max_m + kMarginM) continue;
    const Eigen::Vector2d va = s.a - origin, vb = s.b - origin;
    const double from = std::atan2(va.y(), va.x());
    const double span = std::atan2(va.x() * vb.y() - va.y() * vb.x(), va.dot(vb));  // (-pi, pi]
    const double lo = span >= 0 ? from : from + span;
    add(r, lo - kMarginRad, lo + std::abs(span) + kMarginRad);
  }
  visit([&](std::size_t k, int) { ++count[k]; });
  first_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) first_[k + 1] = first_[k] + count[k];
  order_.resize(static_cast<std::size_t>(first_.back()));
  std::vector<int> at(first_.begin(), first_.end() - 1);
  visit([&](std::size_t k, int id) { order_[static_cast<std::size_t>(at[k]++)] = id; });
}

double RayFan::cast(int k, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction, double max_m, int* wall) const {
  double best = max_m;
  if (wall) *wall = -1;
  const auto ray = static_cast<std::size_t>(k);
  for (int i = first_[ray]; i < first_[ray + 1]; ++i) {
    const Segment2& s = (*segments_)[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])];
    if (rayMeets(s, origin, direction, best) && wall) *wall = s.wall;
  }
  return best;
}

}  // namespace bimloc::guide::detail
