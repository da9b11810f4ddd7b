#include "start_prior.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bimloc::pf::detail {
namespace {

// Three sigmas: a Gaussian prior truncated where it has 0.3 % of its mass left.
constexpr double kSigmas = 3.0;

}  // namespace

StartPrior::StartPrior(const bim::Storey& storey, const RoomIndex& rooms, const ParticleFilterConfig& c) : index_(&rooms) {
  for (const auto& name : c.prior_rooms) {
    const bim::Room* room = storey.findRoom(name);
    if (!room) {
      std::string known;
      for (const auto& r : storey.rooms) known += (known.empty() ? "" : ", ") + r.name;
      throw std::invalid_argument("prior room '" + name + "' is not a room of storey '" + storey.name + "' (rooms: " + known + ")");
    }
    for (std::size_t i = 0; i < rooms.roomCount(); ++i)
      if (&rooms.room(static_cast<int>(i)) == room) {
        rooms_.push_back(static_cast<int>(i));
        areas_.push_back(std::max(1e-6, room->area_m2));
      }
  }
  if (c.prior_pose) {
    if (!c.prior_pose->allFinite() || !(c.prior_sigma_m > 0) || !(c.prior_sigma_yaw_deg > 0))
      throw std::invalid_argument("prior pose: x, y, yaw and sigmas must be finite, sigmas positive");
    pose_ = *c.prior_pose;
    sigma_m_ = c.prior_sigma_m;
    sigma_yaw_rad_ = c.prior_sigma_yaw_deg * M_PI / 180.0;
  }
}

bool StartPrior::admits(const Eigen::Vector3d& start) const {
  if (!rooms_.empty()) {
    const int r = index_->roomAt(start.x(), start.y());
    if (std::find(rooms_.begin(), rooms_.end(), r) == rooms_.end()) return false;
  }
  if (pose_) {
    if (std::hypot(start.x() - pose_->x(), start.y() - pose_->y()) > kSigmas * sigma_m_) return false;
    if (std::abs(wrapAngle(start.z() - pose_->z())) > kSigmas * sigma_yaw_rad_) return false;
  }
  return true;
}

Particle StartPrior::draw(std::mt19937_64& rng) const {
  Particle p;
  std::uniform_real_distribution<double> unit(0.0, 1.0), yaw(-M_PI, M_PI);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    if (pose_) {
      p.x = pose_->x() + sigma_m_ * normal(rng), p.y = pose_->y() + sigma_m_ * normal(rng);
      p.yaw = wrapAngle(pose_->z() + sigma_yaw_rad_ * normal(rng));
    } else {
      const bim::Room& room = index_->room(rooms_[std::discrete_distribution<std::size_t>(areas_.begin(), areas_.end())(rng)]);
      Eigen::Vector2d lo = room.footprint.front(), hi = lo;
      for (const auto& v : room.footprint) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
      p.x = lo.x() + unit(rng) * (hi.x() - lo.x()), p.y = lo.y() + unit(rng) * (hi.y() - lo.y()), p.yaw = yaw(rng);
    }
    p.room = index_->roomAt(p.x, p.y);
    if (admits({p.x, p.y, p.yaw})) return p;
  }
  return p;  // a prior with (almost) no room in it: the last draw
}

}  // namespace bimloc::pf::detail
