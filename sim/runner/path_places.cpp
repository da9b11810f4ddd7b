#include "sim/runner/path_places.hpp"

#include "sim/base/room_lookup.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim {

std::vector<ScenarioResult::Place> pathPlaces(const pf::UpdateReport& report, const bim::Storey& storey) {
  if (!report.path_best) return {};
  std::vector<std::pair<Eigen::Vector3d, double>> all{{*report.path_best, 0.0}};
  all.insert(all.end(), report.path_rivals.begin(), report.path_rivals.end());
  double sum = 0;
  for (const auto& [pose, margin] : all) sum += std::exp(-std::min(margin, 700.0));
  std::vector<ScenarioResult::Place> places;
  for (const auto& [pose, margin] : all) {
    const bim::Room* room = roomAt(storey, pose.head<2>());
    places.push_back({pose.x(), pose.y(), pose.z() * 180.0 / M_PI, std::exp(-std::min(margin, 700.0)) / sum,
                      room ? room->name : std::string("(outside)"), storey.name});
  }
  return places;
}

}  // namespace bimloc::sim
