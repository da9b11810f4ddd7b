#include "sim/base/stair_links.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>

namespace bimloc::sim {
namespace {

// A half landing: the next flight starts where this one ends, within a landing's size in plan
// (a U-turn stair puts it beside, a quarter turn at the corner) and at the same height.
constexpr double kLandingReach_m = 4.0;
constexpr double kLandingHeight_m = 0.05;

// The flight going on from the landing at the top of `f`: the nearest one starting there,
// preferring the same stair.
const bim::StairFlight* nextFlight(const bim::Building& b, const bim::StairFlight& f) {
  const bim::StairFlight* best = nullptr;
  double best_score = std::numeric_limits<double>::infinity();
  for (const auto& g : b.stairs) {
    if (&g == &f || std::abs(g.bottom.z() - f.top.z()) > kLandingHeight_m || !(g.rise_m() > 0.0)) continue;
    const double d = (g.bottom - f.top).head<2>().norm();
    if (d > kLandingReach_m) continue;
    const double score = d + (g.stair_id == f.stair_id ? 0.0 : kLandingReach_m);
    if (score < best_score) best_score = score, best = &g;
  }
  return best;
}

}  // namespace

std::vector<StairLink> stairLinks(const bim::Building& b) {
  std::vector<StairLink> links;
  const int storeys = static_cast<int>(b.storeys.size());
  for (const auto& f : b.stairs) {
    if (f.bottom_storey < 0 || f.bottom_storey >= storeys || !(f.rise_m() > 0.0)) continue;
    StairLink up;
    up.from = static_cast<std::size_t>(f.bottom_storey);
    const bim::StairFlight* cur = &f;
    up.flights.push_back(cur);
    // A chain longer than the building's flights loops: no link.
    while (cur && cur->top_storey < 0 && up.flights.size() <= b.stairs.size()) {
      cur = nextFlight(b, *cur);
      if (cur) up.flights.push_back(cur);
    }
    if (!cur || cur->top_storey < 0 || cur->top_storey >= storeys || cur->top_storey == f.bottom_storey) continue;
    up.to = static_cast<std::size_t>(cur->top_storey);
    StairLink down = up;
    std::swap(down.from, down.to);
    down.up = false;
    std::reverse(down.flights.begin(), down.flights.end());
    links.push_back(std::move(up));
    links.push_back(std::move(down));
  }
  return links;
}

std::optional<std::vector<const StairLink*>> stairRoute(const std::vector<StairLink>& links, std::size_t from,
                                                        std::size_t to) {
  std::map<std::size_t, const StairLink*> via;  // storey -> the link that reached it
  std::deque<std::size_t> queue{from};
  via[from] = nullptr;
  while (!queue.empty() && !via.count(to)) {
    const std::size_t s = queue.front();
    queue.pop_front();
    for (const auto& l : links)
      if (l.from == s && !via.count(l.to)) via[l.to] = &l, queue.push_back(l.to);
  }
  if (!via.count(to)) return std::nullopt;
  std::vector<const StairLink*> route;
  for (std::size_t s = to; s != from; s = via[s]->from) route.push_back(via[s]);
  std::reverse(route.begin(), route.end());
  return route;
}

std::vector<std::size_t> reachableStoreys(const std::vector<StairLink>& links, std::size_t start) {
  std::vector<std::size_t> order{start};
  for (std::size_t i = 0; i < order.size(); ++i)
    for (const auto& l : links)
      if (l.from == order[i] && std::find(order.begin(), order.end(), l.to) == order.end()) order.push_back(l.to);
  return order;
}

}  // namespace bimloc::sim
