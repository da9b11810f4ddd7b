// FreeSpaceMap::openingPass: where a ray that ended in a place's open passed through one of the
// plan's openings near its end (free_space_evidence.hpp). The explained-rays evidence
// (free_space_explained) counts an open ray of place X that another place Y ends on its wall
// against X, a face's worth per Y's wall. A ray that ended in X's own opening was stopped by
// what the plan puts there: a window's pane (glass returns a share of the rays on every site,
// and beyond an outer window nothing else does, so the bin's farthest return is the pane), or
// a door's leaf, which a site may have shut (docs/sites.md: 20 % on the construction preset).
// Counted a face against X, the true place paid a face for each of its own windows and shut
// doors that a rival's wall happened to line up with (AC90R1-Jasmin Keller 003 on the
// construction site: two windows and a shut door, the start lost).
#include "free_space_evidence.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::pf::detail {
namespace {

// An opening whose bottom is this close to its wall's base is a doorway; higher, a sill: a
// window. (The margin the plan's openings are drawn to, as kFreeSpaceOpeningMarginM.)
constexpr double kDoorwaySillM = 0.1;

}  // namespace

std::optional<FreeSpaceMap::OpeningPass> FreeSpaceMap::openingPass(const Eigen::Vector2d& o, const Eigen::Vector2d& u, double z0,
                                                                   double dz_per_m, double t_ref, double reach,
                                                                   std::vector<std::uint32_t>* scratch) const {
  std::optional<OpeningPass> best;
  if (faces_.empty() || !(reach >= 0.0)) return best;
  // The cells the ray's stretch [t_ref - reach, t_ref + reach] lies in: a box of them (the
  // stretch is a metre or two; firstCrossing's walk is for whole rays).
  const Eigen::Vector2d a = o + u * std::max(0.0, t_ref - reach), b = o + u * (t_ref + reach);
  const auto cell = [&](double v, double origin) { return static_cast<int>(std::floor((v - origin) / cell_m_)); };
  const int x0 = std::max(0, cell(std::min(a.x(), b.x()), origin_.x())), x1 = std::min(nx_ - 1, cell(std::max(a.x(), b.x()), origin_.x()));
  const int y0 = std::max(0, cell(std::min(a.y(), b.y()), origin_.y())), y1 = std::min(ny_ - 1, cell(std::max(a.y(), b.y()), origin_.y()));
  std::vector<std::uint32_t> own;
  std::vector<std::uint32_t>& tried = scratch ? *scratch : own;
  tried.clear();
  for (int iy = y0; iy <= y1; ++iy)
    for (int ix = x0; ix <= x1; ++ix)
      for (const std::uint32_t i : cells_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix)]) {
        if (std::find(tried.begin(), tried.end(), i) != tried.end()) continue;
        tried.push_back(i);
        const Face& f = faces_[i];
        if (!f.openings || f.openings->empty()) continue;
        double t = 0, s = 0;
        if (!f.meets(o, u, t, s)) continue;
        if (!(t > 1e-6) || std::abs(t - t_ref) > reach || (best && std::abs(t - t_ref) >= std::abs(best->t - t_ref))) continue;
        const double z = z0 + dz_per_m * t;
        for (const auto& hole : *f.openings) {
          if (s < hole.along_min_m || s > hole.along_max_m || z < hole.z_min_m || z > hole.z_max_m) continue;
          OpeningPass pass;
          pass.t = t, pass.wall = f.wall, pass.cos_incidence = std::abs(u.dot(f.normal));
          // A wall of unknown height has no base to tell a doorway by: a window (no evidence).
          pass.doorway = std::isfinite(f.z_bottom) && hole.z_min_m <= f.z_bottom + kDoorwaySillM;
          pass.edge_m = std::min(s - hole.along_min_m, hole.along_max_m - s);
          pass.head_m = hole.z_max_m - z;
          best = pass;
          break;
        }
      }
  return best;
}

}  // namespace bimloc::pf::detail
