#include "particle_set.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::pf::detail {

std::vector<Particle> spreadOverRooms(const RoomIndex& rooms, std::size_t count, std::mt19937_64& rng) {
  std::vector<Particle> particles(count);
  std::vector<double> areas;
  for (std::size_t r = 0; r < rooms.roomCount(); ++r) areas.push_back(std::max(1e-6, rooms.room(int(r)).area_m2));
  if (areas.empty()) return particles;
  std::discrete_distribution<int> pick(areas.begin(), areas.end());
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), unit(0.0, 1.0);
  for (auto& p : particles) {
    const bim::Room& room = rooms.room(pick(rng));
    Eigen::Vector2d lo = room.footprint.front(), hi = lo;
    for (const auto& v : room.footprint) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    Eigen::Vector2d xy = room.centre;
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const Eigen::Vector2d q(lo.x() + unit(rng) * (hi.x() - lo.x()), lo.y() + unit(rng) * (hi.y() - lo.y()));
      if (bim::pointInPolygon(room.footprint, q)) {
        xy = q;
        break;
      }
    }
    p.x = xy.x(), p.y = xy.y(), p.yaw = yaw(rng), p.log_weight = 0.0;
    p.room = rooms.roomAt(p.x, p.y);
  }
  return particles;
}

int inject(std::vector<Particle>& particles, const std::vector<Hypothesis>& hyps, std::size_t count, double bonus,
           const RoomIndex& rooms, std::mt19937_64& rng) {
  if (hyps.empty() || count == 0) return 0;
  std::size_t good = 0;
  while (good < hyps.size() && hyps[good].log_likelihood > hyps[0].log_likelihood - 3.0) ++good;
  std::vector<std::size_t> order(particles.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  count = std::min(count, particles.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(),
                    [&](std::size_t a, std::size_t b) { return particles[a].log_weight < particles[b].log_weight; });
  double max_lw = -1e300;
  for (const auto& p : particles) max_lw = std::max(max_lw, p.log_weight);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick(0, good - 1);  // no favourite among equals
  for (std::size_t k = 0; k < count; ++k) {
    const auto& h = hyps[pick(rng)];
    Particle& p = particles[order[k]];
    p.x = h.x + 0.05 * n(rng), p.y = h.y + 0.05 * n(rng), p.yaw = wrapAngle(h.yaw + 0.02 * n(rng));
    p.room = rooms.roomAt(p.x, p.y);
    p.log_weight = max_lw + bonus;
  }
  return static_cast<int>(count);
}

std::size_t resample(std::vector<Particle>& particles, const std::vector<double>& w, std::size_t count, std::size_t best,
                     double roughening_xy_m, double roughening_yaw_rad, const RoomIndex& rooms, std::mt19937_64& rng) {
  std::vector<Particle> next;
  next.reserve(count);
  const double n = static_cast<double>(count);
  std::uniform_real_distribution<double> start(0.0, 1.0 / n);
  std::normal_distribution<double> jitter(0.0, 1.0);
  const double r = start(rng);
  double c = w[0];
  std::size_t i = 0, new_best = 0;
  bool best_copied = false;
  for (std::size_t m = 0; m < count; ++m) {
    const double u = r + static_cast<double>(m) / n;
    while (u > c && i + 1 < particles.size()) c += w[++i];
    Particle p = particles[i];
    p.x += roughening_xy_m * jitter(rng);
    p.y += roughening_xy_m * jitter(rng);
    p.yaw = wrapAngle(p.yaw + roughening_yaw_rad * jitter(rng));
    p.room = rooms.roomAt(p.x, p.y);
    p.log_weight = 0.0;
    if (i == best && !best_copied) new_best = m, best_copied = true;
    next.push_back(p);
  }
  particles.swap(next);
  return new_best;  // after resampling all weigh the same
}

std::size_t heaviest(const std::vector<Particle>& particles) {
  std::size_t i = 0;
  for (std::size_t k = 1; k < particles.size(); ++k)
    if (particles[k].log_weight > particles[i].log_weight) i = k;
  return i;
}

std::vector<double> normalisedWeights(const std::vector<Particle>& particles) {
  double max_lw = -1e300;
  for (const auto& p : particles) max_lw = std::max(max_lw, p.log_weight);
  std::vector<double> w(particles.size());
  double sum = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) sum += w[i] = std::exp(particles[i].log_weight - max_lw);
  for (auto& v : w) v /= sum;
  return w;
}

Eigen::Vector3d weightedMean(const std::vector<Particle>& particles, const std::vector<double>& w) {
  double x = 0, y = 0, s = 0, c = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    x += w[i] * particles[i].x, y += w[i] * particles[i].y;
    s += w[i] * std::sin(particles[i].yaw), c += w[i] * std::cos(particles[i].yaw);
  }
  return {x, y, std::atan2(s, c)};
}

}  // namespace bimloc::pf::detail
