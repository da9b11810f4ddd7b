// The explained rays (free_space_explained) at a place's own openings, against the geometry of
// two twin rooms built in code that differ only by what stands in one wall: a doorway in X, a
// solid wall in Y. A ray that ended in X's doorway plane is, at Y, on Y's wall; X's shut leaf
// explains it at the site's probability of a shut door, so it counts -log(0.2) against X, not
// a face. A ray that ended in X's window is the pane: nothing. A ray through X's open doorway
// and beyond is what tells the rooms apart, a face against Y, as before. Without explained
// rays (the default), a ray that ended at the frame of a place's own opening is no evidence.
#include "sgraph_fixtures.hpp"

#include "pf/free_space_evidence.hpp"

#include <bimloc/pf/particle_filter.hpp>
#include <bimloc/pf/range_profile.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

using namespace bimloc;
using namespace bimloc::pf::detail;

namespace {

constexpr double kFaceWorth = 0.5 * (11.34 - 3.0);

FreeSpaceParams explainedParams() {
  pf::ParticleFilterConfig c;
  c.free_space_explained = true;
  return FreeSpaceParams::of(c, 0.0);
}

// Rays from the base's origin (lidar 0.6 m up), ends at 1.4 m: the profile's band.
pf::RangeProfile profileOf(const std::vector<Eigen::Vector2d>& ends) {
  pf::RangeProfile p;
  p.origin_base = Eigen::Vector3d(0, 0, 0.6);
  for (const auto& e : ends) p.ends_base.emplace_back(static_cast<float>(e.x()), static_cast<float>(e.y()), 1.4f);
  return p;
}

// The room's east wall, axis x = 5 (faces at 4.9 and 5.1), y -15..15, 2.8 m high from z 0,
// with a hole y -1..1 from z_min to 2.1 (a doorway from 0, a window from a sill), or none; and
// a wall 2 m beyond it (faces at 6.9, 7.1).
bim::Storey eastWall(std::optional<double> hole_z_min) {
  bim::Storey s;
  s.walls.push_back(test::boxWall("East", {5, -15}, {5, 15}, 0.2));
  s.walls.push_back(test::boxWall("Beyond", {7, -15}, {7, 15}, 0.2));
  if (!hole_z_min) return s;
  // Along each face from its start: faces[0] runs +y from y = -15, faces[1] -y from y = 15.
  for (auto& face : s.walls[0].faces) {
    const double sign = face.end.y() > face.start.y() ? 1.0 : -1.0;
    const double lo = sign * (-1.0 - face.start.y()), hi = sign * (1.0 - face.start.y());
    face.openings.push_back({std::min(lo, hi), std::max(lo, hi), *hole_z_min, 2.1});
  }
  return s;
}

// Three rays that ended in the east wall's plane inside y -1..1 (a leaf, a pane or Y's wall).
const std::vector<Eigen::Vector2d> kInTheHole{{5.0, 0.0}, {5.0, 0.4}, {5.0, -0.4}};

}  // namespace

TEST(FreeSpaceOpenings, ARayThroughTheHoleIsFoundWithItsKind) {
  const bim::Storey door = eastWall(0.0), window = eastWall(0.9);
  const FreeSpaceMap at_door(door), at_window(window);
  const Eigen::Vector2d o(0, 0), u(1, 0);
  // The ray at height 1.0: it crosses the face at x = 4.9 (t 4.9) and 5.1 inside the hole; the
  // nearest to its end at t = 5.0 within 0.5 m, either face (0.1 m both ways).
  const auto pass = at_door.openingPass(o, u, 1.0, 0.0, 5.0, 0.5);
  ASSERT_TRUE(pass);
  EXPECT_NEAR(std::abs(pass->t - 5.0), 0.1, 1e-9);
  EXPECT_EQ(pass->wall, 0);
  EXPECT_TRUE(pass->doorway);
  EXPECT_NEAR(pass->cos_incidence, 1.0, 1e-12);
  const auto pane = at_window.openingPass(o, u, 1.0, 0.0, 5.0, 0.5);
  ASSERT_TRUE(pane);
  EXPECT_FALSE(pane->doorway);  // a sill 0.9 m above the wall's base
  // Beside the hole (y = 3) the wall is solid there: no pass; nor beyond reach of the end.
  EXPECT_FALSE(at_door.openingPass(o, Eigen::Vector2d(5, 3).normalized(), 1.0, 0.0, std::hypot(5, 3), 0.5));
  EXPECT_FALSE(at_door.openingPass(o, u, 1.0, 0.0, 2.0, 0.5));
  // Above the doorway's head (2.1 m): the wall's body, no pass.
  EXPECT_FALSE(at_door.openingPass(o, u, 2.5, 0.0, 5.0, 0.5));
}

TEST(FreeSpaceOpenings, TheTwinWithTheDoorPaysTheShutLeafNotAWall) {
  const FreeSpaceParams params = explainedParams();
  EXPECT_NEAR(params.door_worth, -std::log(0.2), 1e-12);
  EXPECT_LT(params.door_worth, kFaceWorth);
  const bim::Storey with_door = eastWall(0.0), solid = eastWall(std::nullopt);
  const FreeSpaceMap x_map(with_door), y_map(solid);
  // The same rays from the same pose in X (a doorway in the east wall) and in Y (none).
  const auto at_x = freeSpaceHits(x_map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(kInTheHole));
  const auto at_y = freeSpaceHits(y_map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(kInTheHole));
  int open = 0, in_doorway = 0, on_wall = 0;
  for (const auto& h : at_x) {
    open += h.key >= kOpenKeyBase && h.key < kOnWallBase;
    in_doorway += h.key == kInDoorwayBase + 0;
  }
  for (const auto& h : at_y) on_wall += h.key == kOnWallBase + 0;
  EXPECT_EQ(open, 3);        // nothing solid in X up to 1 m past the ends: X's open ...
  EXPECT_EQ(in_doorway, 3);  // ... in its own doorway
  EXPECT_EQ(on_wall, 3);     // Y's wall where X has its doorway
  const std::vector<const std::vector<FreeSpaceHit>*> x{&at_x}, y{&at_y};
  const FreeSpaceCost against_x = freeSpaceCostGiven(x, y, params, {});
  EXPECT_TRUE(against_x.explained.empty());                // not a face under Y's wall
  EXPECT_NEAR(against_x.doors, params.door_worth, 1e-6);  // one leaf, three rays: in full
  EXPECT_NEAR(against_x.rest, 0.0, 1e-9);                  // and no longer in the open term
  // One leaf is one event: twice the rays are still one door's worth.
  const auto twice = at_x;
  const FreeSpaceCost doubled = freeSpaceCostGiven({&at_x, &twice}, {&at_y, &at_y}, params, {});
  EXPECT_NEAR(doubled.doors, params.door_worth, 1e-6);
  // Against Y: its rays end on its wall, nothing.
  const FreeSpaceCost against_y = freeSpaceCostGiven(y, x, params, {});
  EXPECT_TRUE(against_y.explained.empty());
  EXPECT_NEAR(against_y.doors + against_y.rest, 0.0, 1e-9);
  // Within the bound over every other place.
  EXPECT_LE(against_x.rest + against_x.doors, freeSpacePenaltyBound(x, params) + 1e-9);
}

TEST(FreeSpaceOpenings, ARayEndingOnAWindowsPaneIsNoEvidence) {
  const FreeSpaceParams params = explainedParams();
  const bim::Storey with_window = eastWall(0.9), solid = eastWall(std::nullopt);
  const FreeSpaceMap x_map(with_window), y_map(solid);
  const auto at_x = freeSpaceHits(x_map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(kInTheHole));
  const auto at_y = freeSpaceHits(y_map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(kInTheHole));
  int in_window = 0;
  for (const auto& h : at_x) in_window += h.key == kInWindowBase + 0;
  EXPECT_EQ(in_window, 3);
  // Nothing under Y's wall, no leaf: what is left is the bounded open term, as without explained rays.
  const FreeSpaceCost against_x = freeSpaceCostGiven({&at_x}, {&at_y}, params, {});
  EXPECT_TRUE(against_x.explained.empty());
  EXPECT_EQ(against_x.doors, 0.0);
  EXPECT_NEAR(against_x.rest, freeSpacePenalty({&at_x}, params), 1e-9);
}

TEST(FreeSpaceOpenings, ARayThroughTheDoorwayAndBeyondStillCountsAFaceAgainstTheTwin) {
  // The rays X sees through its open doorway end on the wall beyond (x = 6.9): consistent in X,
  // through Y's solid wall: a face against Y, and X's doorway marks play no part.
  const FreeSpaceParams params = explainedParams();
  const bim::Storey with_door = eastWall(0.0), solid = eastWall(std::nullopt);
  const FreeSpaceMap x_map(with_door), y_map(solid);
  const std::vector<Eigen::Vector2d> beyond{{6.9, 0.0}, {6.9, 0.4}, {6.9, -0.4}};
  const auto at_x = freeSpaceHits(x_map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(beyond));
  const auto at_y = freeSpaceHits(y_map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(beyond));
  for (const auto& h : at_x) EXPECT_EQ(h.key, kOnWallBase + 1) << "in X the rays end on the wall beyond";
  const FreeSpaceCost against_y = freeSpaceCostGiven({&at_y}, {&at_x}, params, {});
  EXPECT_GT(against_y.rest, 0.9 * kFaceWorth);
  const FreeSpaceCost against_x = freeSpaceCostGiven({&at_x}, {&at_y}, params, {});
  EXPECT_NEAR(against_x.rest + against_x.doors, 0.0, 1e-9);
}

TEST(FreeSpaceOpenings, ARayEndingAtTheFrameOfThePlacesOwnOpeningIsNoEvidence) {
  // Without explained rays (the default): a ray that ended in the east wall's own hole, inside
  // the wall's body (x 4.9-5.1) and at a jamb (|y| 0.96-0.99 of the hole's 1: its reveal or
  // frame, by the geometry built above), is no free space at the place: no hit, doorway or
  // window alike, as a crossing there gets no verdict. A ray that ended in the middle of the
  // hole (a leaf or a pane), one through the doorway that ended 0.5 m past the wall (beyond the
  // gate) and one in the room's open still cost the open quarter face each.
  pf::ParticleFilterConfig c;
  ASSERT_FALSE(c.free_space_explained);
  const FreeSpaceParams params = FreeSpaceParams::of(c, 0.0);
  ASSERT_LT(params.gate_sigmas * params.sigma_m, 0.5);
  const std::vector<Eigen::Vector2d> jambs{{5.05, 0.99}, {4.95, -0.99}, {5.0, 0.98}};
  for (const double sill : {0.0, 0.9}) {
    const bim::Storey with_hole = eastWall(sill);
    const FreeSpaceMap map(with_hole);
    EXPECT_TRUE(freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(jambs)).empty()) << "sill " << sill;
    const auto open = freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, profileOf({{5.0, 0.0}, {5.6, 0.0}, {3.0, 0.0}}));
    ASSERT_EQ(open.size(), 3u) << "sill " << sill;
    for (const auto& h : open) {
      EXPECT_GE(h.key, kOpenKeyBase);
      EXPECT_LT(h.key, kOnWallBase);
      EXPECT_NEAR(h.cost, params.open_wall_faces * kFaceWorth, 1e-5);
    }
  }
  // The solid twin: the jamb rays end in its wall's body, on it or just in it: never open.
  const bim::Storey solid = eastWall(std::nullopt);
  const FreeSpaceMap solid_map(solid);
  for (const auto& h : freeSpaceHits(solid_map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(jambs)))
    EXPECT_LT(h.key, kOpenKeyBase) << "a ray in Y's solid wall is not in Y's open";
}
