#include "peers/amcl/particles.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace bimloc::peers::amcl {

int kldLimit(int k, double err, double z, int min_particles, int max_particles) {
  if (k <= 1) return max_particles;  // as ROS: no spread to measure yet
  const double km1 = k - 1.0;
  const double b = 2.0 / (9.0 * km1);
  const double x = 1.0 - b + std::sqrt(b) * z;
  const double n = std::ceil(km1 / (2.0 * err) * x * x * x);
  if (!(n >= min_particles)) return min_particles;
  if (n > max_particles) return max_particles;
  return static_cast<int>(n);
}

std::array<int, 3> binOf(const PlanarPose& pose) {
  // ROS pf_kdtree_alloc: size = {0.50, 0.50, 10 deg}.
  constexpr double kXy = 0.5, kYaw = 10.0 * M_PI / 180.0;
  const auto key = [](double v, double size) { return static_cast<int>(std::floor(std::clamp(v / size, -1e9, 1e9))); };
  return {key(pose.x(), kXy), key(pose.y(), kXy), key(pose.z(), kYaw)};
}

std::vector<Particle> resampleKld(const std::vector<Particle>& particles, const AmclConfig& config, double w_diff,
                                  const std::function<PlanarPose(std::mt19937_64&)>& random_pose, std::mt19937_64& rng) {
  // The cumulative weights, searched by bisection (ROS scans them linearly: same draws).
  std::vector<double> c(particles.size() + 1, 0.0);
  for (std::size_t i = 0; i < particles.size(); ++i) c[i + 1] = c[i] + particles[i].weight;
  const double total = c.back();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::set<std::array<int, 3>> bins;
  std::vector<Particle> out;
  const int max_particles = std::max(1, config.max_particles);
  std::vector<int> limit_cache(static_cast<std::size_t>(max_particles) + 2, -1);  // by k (ROS limit_cache)
  while (static_cast<int>(out.size()) < max_particles) {
    Particle p;
    if (unit(rng) < w_diff || !(total > 0)) {
      p.pose = random_pose(rng);
    } else {
      const double r = unit(rng) * total;
      const auto it = std::upper_bound(c.begin() + 1, c.end(), r);
      const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(it - c.begin()) - 1, particles.size() - 1);
      p.pose = particles[i].pose;
    }
    out.push_back(p);
    bins.insert(binOf(p.pose));
    const int k = static_cast<int>(bins.size());
    int& limit = limit_cache[static_cast<std::size_t>(std::min(k, max_particles + 1))];
    if (limit < 0) limit = kldLimit(k, config.kld_err, config.kld_z, config.min_particles, max_particles);
    if (static_cast<int>(out.size()) > limit) break;  // ROS: "sample_count > limit"
  }
  for (Particle& p : out) p.weight = 1.0 / static_cast<double>(out.size());
  return out;
}

}  // namespace bimloc::peers::amcl
