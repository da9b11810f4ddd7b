#include "peers/amcl/clusters.hpp"

#include <cmath>
#include <map>

namespace bimloc::peers::amcl {
namespace {

struct Sums {
  double w = 0, x = 0, y = 0, c = 0, s = 0, xx = 0, xy = 0, yy = 0;
  void add(const Particle& p) {
    const double v = p.weight;
    w += v, x += v * p.pose.x(), y += v * p.pose.y(), c += v * std::cos(p.pose.z()), s += v * std::sin(p.pose.z());
    xx += v * p.pose.x() * p.pose.x(), xy += v * p.pose.x() * p.pose.y(), yy += v * p.pose.y() * p.pose.y();
  }
  PoseStats stats() const {
    PoseStats out;
    out.weight = w;
    if (!(w > 0)) return out;
    out.mean = {x / w, y / w, std::atan2(s, c)};
    out.covariance(0, 0) = xx / w - out.mean.x() * out.mean.x();
    out.covariance(0, 1) = out.covariance(1, 0) = xy / w - out.mean.x() * out.mean.y();
    out.covariance(1, 1) = yy / w - out.mean.y() * out.mean.y();
    out.covariance(2, 2) = -2.0 * std::log(std::max(1e-300, std::hypot(c, s) / w));
    return out;
  }
};

}  // namespace

SetStats clusterStats(const std::vector<Particle>& particles) {
  // Label the occupied bins by connected component, bins first seen first.
  std::map<std::array<int, 3>, int> label;
  std::vector<std::array<int, 3>> order;
  for (const Particle& p : particles) {
    const auto key = binOf(p.pose);
    if (label.emplace(key, -1).second) order.push_back(key);
  }
  int clusters = 0;
  std::vector<std::array<int, 3>> stack;
  for (const auto& seed : order) {
    if (label[seed] >= 0) continue;
    label[seed] = clusters;
    stack.push_back(seed);
    while (!stack.empty()) {
      const auto b = stack.back();
      stack.pop_back();
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int da = -1; da <= 1; ++da) {
            const auto it = label.find({b[0] + dx, b[1] + dy, b[2] + da});
            if (it == label.end() || it->second >= 0) continue;
            it->second = clusters;
            stack.push_back(it->first);
          }
    }
    ++clusters;
  }
  Sums all;
  std::vector<Sums> per(static_cast<std::size_t>(clusters));
  for (const Particle& p : particles) {
    all.add(p);
    per[static_cast<std::size_t>(label[binOf(p.pose)])].add(p);
  }
  SetStats out;
  out.clusters = clusters;
  out.set = all.stats();
  std::size_t best = 0;
  for (std::size_t k = 1; k < per.size(); ++k)
    if (per[k].w > per[best].w) best = k;
  out.best = per.empty() ? out.set : per[best].stats();
  return out;
}

}  // namespace bimloc::peers::amcl
