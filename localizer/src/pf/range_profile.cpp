#include <bimloc/pf/range_profile.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::pf {

RangeProfile rangeProfile(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_base_lidar,
                          const RangeProfileConfig& config) {
  RangeProfile out;
  out.origin_base = T_base_lidar.translation();
  const double bin_rad = std::max(0.1, config.bin_deg) * M_PI / 180.0;
  const int bins = static_cast<int>(std::ceil(2.0 * M_PI / bin_rad));
  std::vector<float> best(static_cast<std::size_t>(bins), -1.0f);
  std::vector<Eigen::Vector3f> ends(static_cast<std::size_t>(bins));
  const Eigen::Matrix3f R = T_base_lidar.linear().cast<float>();
  const Eigen::Vector3f t = T_base_lidar.translation().cast<float>();
  const Eigen::Vector2f o = out.origin_base.head<2>().cast<float>();
  for (const auto& p : points_lidar) {
    const Eigen::Vector3f b = R * p + t;
    if (!b.allFinite() || b.z() < config.min_height_m || b.z() > config.max_height_m) continue;
    const Eigen::Vector2f v = b.head<2>() - o;
    const float r = v.norm();
    if (r < config.min_range_m) continue;
    const double a = std::atan2(v.y(), v.x()) + M_PI;  // [0, 2 pi]
    const int k = std::min(bins - 1, static_cast<int>(a / bin_rad));
    if (r > best[static_cast<std::size_t>(k)]) best[static_cast<std::size_t>(k)] = r, ends[static_cast<std::size_t>(k)] = b;
  }
  for (int k = 0; k < bins; ++k)
    if (best[static_cast<std::size_t>(k)] > 0.0f) out.ends_base.push_back(ends[static_cast<std::size_t>(k)]);
  return out;
}

}  // namespace bimloc::pf
