// Free-space (negative) evidence: what the scans rule out. The planes' margin weighs the walls a
// place explains; two offices alike in their walls but not in where their doors are stay tied
// on planes for as long as the robot stays in one of them, although every ray through the true
// door went through the other office's solid wall. Here each ray of a scan's range profile
// (range_profile.hpp) is cast from a candidate place through the plan's wall faces:
//   - through: it ends beyond the first solid face it crosses (not in an opening) by more than
//     gate_sigmas sigmas of its range: the place has a wall where the scan saw none;
//   - open: it ends open_m or more short of every face along it: the place has free space where
//     the scan saw something;
//   - else it is consistent (ended on a wall, or short of one by clutter): no cost.
// The model is a beam model with a uniform clutter floor (Thrun et al., Probabilistic Robotics
// 6.3: the wall's N(r; t, sigma) or the floor w), restricted to rays that reach beyond t: such a
// reading has no short-reading explanation. Its cost is that of the better explanation (a
// generalized likelihood ratio), min(z^2 / 2, -log w): the Gaussian's, then exactly -log w, which
// the floor w is chosen to make one face's worth (half the planes' gate less its 3 dof, the unit
// of ParticleFilterConfig::evidenceMargin). Every ray beyond the 3-sigma gate costs it (4.5 >
// 4.17). The sum of the two explanations only tended to it, so two walls never made the bar of
// two faces (docs/results/2026-11-28-h28miss.md). Short rays
// are what people, furniture and stacked material do: the open cost is a small constant per
// ray, and bounded per region and in total.
//
// Counted once per wall (like FaceMargin counts a face once): a wall's through-rays over the
// whole window contribute the mean of their costs, times min(1, rays / support_rays). So a
// wall missing on a construction site costs the true place at most one face, below the bar of
// two; a wall that really is not at the place costs a wrong place about one face per wall.
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/pf/particle_filter.hpp>
#include <bimloc/pf/range_profile.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace bimloc::pf::detail {

// One ray's cost against a place, and what it is counted under: a wall index (through it), or
// kOpenKeyBase + a 2 m region cell of the floor where it ended (in the open).
struct FreeSpaceHit {
  std::int32_t key = 0;
  float cost = 0;
  std::int32_t ray = -1;  // the ray's index in the scan's profile
};
constexpr std::int32_t kOpenKeyBase = 1 << 28;
// Costless marks of rays that ended on a wall (kOnWallBase + wall): another place's open ray
// that this place explains is counted against that place under kExplainedBase + this wall.
constexpr std::int32_t kOnWallBase = 1 << 29;
constexpr std::int32_t kExplainedBase = 3 << 28;
// Costless marks of open rays that ended in one of the place's own openings (+ its wall): in a
// doorway, where a shut leaf would stop them; in a window, where its pane does. Such a ray the
// other place ends on its wall counts against this place under kDoorExplainedBase + the wall,
// at door_worth (a doorway), or not at all (a window).
constexpr std::int32_t kInDoorwayBase = 4 << 28;
constexpr std::int32_t kInWindowBase = 5 << 28;
constexpr std::int32_t kDoorExplainedBase = 6 << 28;

struct FreeSpaceParams {
  double sigma_m = 0.15;           // a ray's range sigma at normal incidence (noise, drift, plan)
  double gate_sigmas = 3.0;
  double sigma_yaw_rad = 0.0175;   // the place's heading, as fitted: moves a far ray sideways
  double face_worth = 4.17;        // one face of the planes' margin: 0.5 (gate - 3)
  int support_rays = 3;
  double open_m = 1.0;
  double open_wall_faces = 0.25;   // per open region, in faces
  double open_faces = 1.0;         // all open regions, in faces
  bool explained = false;          // pairs: an open ray the other place ends on its wall
  double door_worth = 1.61;        // -log P(a door shut): a ray in the place's doorway, explained
  static FreeSpaceParams of(const ParticleFilterConfig& c, double drift_m);
};

// The cost of one ray ending `beyond_m` past the wall it crossed, range sigma `sigma_m`:
// min(z^2 / 2, cap), z = beyond / sigma: the wall's Gaussian or the clutter floor w = exp(-cap),
// whichever explains the ray better. 0 at the wall, exactly cap from z = sqrt(2 cap) on (beyond
// the 3-sigma gate at the default cap): a wall its rays went through is one face, no less.
double throughCost(double beyond_m, double sigma_m, double cap);

// The plan's wall faces in a grid, for rays: the first solid face a ray crosses.
class FreeSpaceMap {
 public:
  // The storey must outlive the map (its faces' openings are pointed at, not copied).
  explicit FreeSpaceMap(const bim::Storey& storey, double cell_m = 1.0);
  FreeSpaceMap(bim::Storey&&, double = 1.0) = delete;
  struct Crossing {
    double t = 0;             // along the ray, metres
    int wall = -1;            // the storey's wall index
    double cos_incidence = 1; // |cos| between the ray and the face normal
    bool uncertain = false;   // within a few centimetres of the face's end: a corner, no verdict
  };
  // The first solid crossing of the ray o + t u (u unit, map x y; its height goes from z0 at
  // t = 0 by dz_per_m), 0 < t <= max_t. Openings the ray passes through are not crossings.
  // lateral_per_m (the place's heading sigma) and position_sigma_m (its position's) say how far
  // along a face the crossing may be off: that close to a face's end or an opening's edge it
  // is `uncertain`. `scratch` (optional): a list to hold the faces tried, so that a caller
  // casting many rays allocates it once.
  std::optional<Crossing> firstCrossing(const Eigen::Vector2d& o, const Eigen::Vector2d& u, double z0, double dz_per_m,
                                        double max_t, double lateral_per_m = 0.0, double position_sigma_m = 0.0,
                                        std::vector<std::uint32_t>* scratch = nullptr) const;
  int regionKey(const Eigen::Vector2d& p) const;  // a 2 m cell of the floor
  // Where the ray passes through one of the plan's openings within `reach` of t_ref along it
  // (the nearest such pass): the opening's wall, and whether it is a doorway (it reaches down
  // to the wall's base: a leaf, shut or not, stands in it) or a window (a sill: a pane fills it).
  // `scratch`, as firstCrossing's: the faces tried, reused ray after ray.
  struct OpeningPass {
    double t = 0;
    int wall = -1;
    double cos_incidence = 1;
    bool doorway = false;
    double edge_m = 0;  // along the face, from the pass to the hole's nearer jamb
    double head_m = 0;  // in height, from the pass to the hole's head
  };
  std::optional<OpeningPass> openingPass(const Eigen::Vector2d& o, const Eigen::Vector2d& u, double z0, double dz_per_m, double t_ref,
                                         double reach, std::vector<std::uint32_t>* scratch = nullptr) const;

 private:
  struct Face {
    Eigen::Vector2d start, direction, normal;
    double length_m = 0;
    double z_bottom = 0, z_top = 0;  // map heights; unbounded when unknown
    const std::vector<bim::FaceOpening>* openings = nullptr;
    int wall = -1;
    // Where the ray o + t u meets the face's line start + s direction (t along the ray, s along
    // the face); false when it runs parallel to it. firstCrossing's and openingPass' test.
    bool meets(const Eigen::Vector2d& o, const Eigen::Vector2d& u, double& t, double& s) const {
      const double denom = u.x() * direction.y() - u.y() * direction.x();
      if (std::abs(denom) < 1e-9) return false;
      const Eigen::Vector2d w = start - o;
      t = (w.x() * direction.y() - w.y() * direction.x()) / denom;
      s = (w.x() * u.y() - w.y() * u.x()) / denom;
      return true;
    }
  };
  std::vector<Face> faces_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_m_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<std::uint32_t>> cells_;
};

// The hits of one scan's profile with the base at map pose `pose` (x, y, yaw), base height z_base.
std::vector<FreeSpaceHit> freeSpaceHits(const FreeSpaceMap& map, const FreeSpaceParams& params, const Eigen::Vector3d& pose, double z_base,
                                        const RangeProfile& profile);

// The evidence against a place over a window (its scans' hits): per key the mean cost of its
// rays times min(1, rays / support_rays); through keys add up, open keys add up to at most
// open_faces faces.
double freeSpacePenalty(const std::vector<const std::vector<FreeSpaceHit>*>& per_scan, const FreeSpaceParams& params);
// The same against X given another place Y (scan by scan, the same rays): X's open rays that end
// on Y's wall w count per wall w, one face's worth per ray, times min(1, rays / support_rays).
// But a ray that ended in X's own opening is what the plan allows there: a window's pane (no
// evidence), or a doorway's leaf shut on the site (door_worth per X's wall, the same ramp).
struct FreeSpaceCost {
  double rest = 0;                                      // through and open, as freeSpacePenalty
  std::vector<std::pair<std::int32_t, double>> explained;  // per Y's wall: the worth of X's open rays ending on it
  double doors = 0;  // X's open rays Y ends on its wall that ended in X's own doorways: door_worth per X's wall
};
// `counted`: per Y's wall, what the planes already counted for it (one wall is one face's worth,
// whatever saw it: that much is taken off; its rays stay in the bounded open term as well).
FreeSpaceCost freeSpaceCostGiven(const std::vector<const std::vector<FreeSpaceHit>*>& x, const std::vector<const std::vector<FreeSpaceHit>*>& y,
                                 const FreeSpaceParams& params, const std::vector<double>& counted);
// An upper bound, over every y and `counted`, of what freeSpaceCostGiven(x, y) counts against x
// (its rest and its explained worths).
double freeSpacePenaltyBound(const std::vector<const std::vector<FreeSpaceHit>*>& x, const FreeSpaceParams& params);

}  // namespace bimloc::pf::detail
