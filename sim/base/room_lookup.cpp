#include "sim/base/room_lookup.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::sim {

const bim::Room* lookUpRoom(const bim::Storey& storey, const std::string& name_or_id, std::string* problem) {
  for (const auto& r : storey.rooms)
    if (r.name == name_or_id || r.id == name_or_id) return &r;
  // A long name is a use ("Office"): fine when one room has it, a guess when several do.
  std::vector<const bim::Room*> uses;
  for (const auto& r : storey.rooms)
    if (r.long_name == name_or_id) uses.push_back(&r);
  if (uses.size() == 1) return uses.front();
  if (problem) {
    if (uses.empty()) {
      *problem = "unknown room '" + name_or_id + "' on storey '" + storey.name + "'; its rooms: " + roomList(storey);
    } else {
      std::string names;
      for (const auto* r : uses) names += (names.empty() ? "" : ", ") + r->name;
      *problem = "room '" + name_or_id + "' is ambiguous on storey '" + storey.name + "': " + std::to_string(uses.size()) +
                 " rooms have that long name (" + names + "); give the room's name";
    }
  }
  return nullptr;
}

std::string roomList(const bim::Storey& storey) {
  std::string out;
  for (const auto& r : storey.rooms)
    out += (out.empty() ? "" : ", ") + (r.name.empty() ? r.id : r.name) + (r.long_name.empty() ? "" : " (" + r.long_name + ")");
  return out.empty() ? "none" : out;
}

const bim::Room* roomAt(const bim::Storey& storey, const Eigen::Vector2d& p) { return storey.roomAt(p); }

namespace {

// Beyond a footprint's bounding box no crossing count is odd; the pad covers the rounding of
// the crossing's x in pointInPolygon.
constexpr double kPad_m = 1e-6;
// A plan spanning kilometres still gets a grid of bounded size (coarser cells).
constexpr double kMaxLookupCells = 1 << 20;

}  // namespace

RoomGrid::RoomGrid(const bim::Storey& storey) : storey_(&storey) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& r : storey.rooms)
    for (const auto& p : r.footprint)
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (lo.x() > hi.x()) return;  // no room: every lookup is nullptr
  origin_ = lo - Eigen::Vector2d(1.0, 1.0);
  const Eigen::Vector2d span = hi - origin_ + Eigen::Vector2d(1.0, 1.0);
  // Bounded in area and along each side: a room written 1e30 m long (one damaged vertex) on a
  // storey 15 m wide asked for 3e17 cells in a row, which overflowed the int.
  cell_m_ = std::max({1.0, std::sqrt(span.x() * span.y() / kMaxLookupCells), std::max(span.x(), span.y()) / kMaxLookupCells});
  nx_ = static_cast<int>(std::ceil(span.x() / cell_m_)) + 1;
  ny_ = static_cast<int>(std::ceil(span.y() / cell_m_)) + 1;
  cells_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), {});
  for (int r = 0; r < static_cast<int>(storey.rooms.size()); ++r) {
    const auto& footprint = storey.rooms[static_cast<std::size_t>(r)].footprint;
    if (footprint.empty()) continue;
    Eigen::Vector2d a(1e300, 1e300), b(-1e300, -1e300);
    bool finite = true;
    for (const auto& p : footprint) finite &= p.allFinite(), a = a.cwiseMin(p), b = b.cwiseMax(p);
    if (!finite) a = origin_, b = origin_ + Eigen::Vector2d(nx_, ny_) * cell_m_;  // no box: a candidate everywhere
    const int x0 = std::max(0, cellX(a.x() - kPad_m)), x1 = std::min(nx_ - 1, cellX(b.x() + kPad_m));
    const int y0 = std::max(0, cellY(a.y() - kPad_m)), y1 = std::min(ny_ - 1, cellY(b.y() + kPad_m));
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) cells_[static_cast<std::size_t>(iy) * nx_ + ix].push_back(r);
  }
  // A cell no footprint edge comes near is answered as a whole (geometry2d.hpp), as the
  // localizer's RoomIndex does.
  std::vector<const bim::Polygon2*> footprints;
  for (const auto& room : storey.rooms) footprints.push_back(&room.footprint);
  sure_ = bim::wholeCellAnswers(footprints, cells_, origin_, cell_m_, nx_, ny_);
}

int RoomGrid::cellX(double x) const { return static_cast<int>(std::floor((x - origin_.x()) / cell_m_)); }
int RoomGrid::cellY(double y) const { return static_cast<int>(std::floor((y - origin_.y()) / cell_m_)); }

const bim::Room* RoomGrid::at(const Eigen::Vector2d& p) const {
  if (!p.allFinite() || cells_.empty()) return nullptr;  // pointInPolygon holds no NaN, no point of a roomless storey
  const double fx = std::floor((p.x() - origin_.x()) / cell_m_), fy = std::floor((p.y() - origin_.y()) / cell_m_);
  if (fx < 0 || fy < 0 || fx >= nx_ || fy >= ny_) return nullptr;  // beyond every footprint's box
  const std::size_t k = static_cast<std::size_t>(fy) * nx_ + static_cast<std::size_t>(fx);
  if (const int sure = sure_[k]; sure != bim::kCellUnsure) return sure < 0 ? nullptr : &storey_->rooms[static_cast<std::size_t>(sure)];
  for (const int r : cells_[k])
    if (bim::pointInPolygon(storey_->rooms[static_cast<std::size_t>(r)].footprint, p)) return &storey_->rooms[static_cast<std::size_t>(r)];
  return nullptr;
}

}  // namespace bimloc::sim
