#include "outside_fits.hpp"

#include <limits>

namespace bimloc::pf::detail {
namespace {

// How far outside the walls the covering room reaches: the lidar sees a facade from farther,
// but a robot about to enter the building is near it.
constexpr double kReachM = 5.0;

std::unique_ptr<bim::Storey> coveringRoom(const bim::Storey& storey) {
  auto out = std::make_unique<bim::Storey>();
  out->name = storey.name, out->id = storey.id, out->elevation_m = storey.elevation_m;
  out->walls = storey.walls;
  if (storey.walls.empty()) return out;
  Eigen::Vector2d lo = storey.walls.front().start.head<2>(), hi = lo;
  for (const auto& w : storey.walls)
    for (const Eigen::Vector3d& p : {w.start, w.end}) lo = lo.cwiseMin(p.head<2>()), hi = hi.cwiseMax(p.head<2>());
  lo.array() -= kReachM, hi.array() += kReachM;
  bim::Room all;
  all.id = storey.id + "/everywhere", all.name = "everywhere";
  all.footprint = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  all.area_m2 = (hi - lo).prod();
  all.centre = 0.5 * (lo + hi);
  out->rooms.push_back(all);
  return out;
}

ParticleFilterConfig everyFace(ParticleFilterConfig c) {
  c.use_rooms = false;
  return c;
}

}  // namespace

OutsideFits::OutsideFits(const bim::Storey& storey, const ParticleFilterConfig& config)
    : everywhere_(coveringRoom(storey)),
      every_face_(*everywhere_, /*use_rooms=*/false),
      real_(storey, /*use_rooms=*/false),
      config_(everyFace(config)) {}

OutsideFits::Fits OutsideFits::fits(const std::vector<Observation>& observations, double z_base) const {
  const auto all = poseHypotheses(observations, z_base, every_face_, config_, std::numeric_limits<std::size_t>::max());
  Fits out;
  out.anywhere = all.size();
  for (const auto& h : all) {
    if (h.log_likelihood < all.front().log_likelihood - 1.5 * config_.gate_mahalanobis2) break;
    if (real_.roomAt(h.x, h.y) < 0) out.outside.push_back(h);
  }
  return out;
}

}  // namespace bimloc::pf::detail
