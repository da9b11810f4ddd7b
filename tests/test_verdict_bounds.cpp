// The path verdict's margin is the lowest of its rivals' full margins (planes and free space),
// never addFreeSpace's lower bound of one (the planes' margin less the best's free-space penalty,
// left to the rivals the fitting loop did not reach). Built in code: five rooms of one size, the
// robot in the first, where three more walls stand that the others lack; one wall of every room
// the scan's rays went through (a wall not built yet), so every place pays the same penalty. The
// verdict's margin is checked against the brute force: every candidate's full margin, scored
// afresh (PathEvidence::marginBetween).
#include "sgraph_fixtures.hpp"

#include "face_observation.hpp"
#include "pf/path_evidence.hpp"

#include <bimloc/pf/particle_filter.hpp>
#include <bimloc/pf/range_profile.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace bimloc;
using pf::detail::Pose2;

namespace {

constexpr int kRooms = 5;             // the robot's and four others, 10 m apart along x
constexpr double kRoomPitchM = 10.0;  // a room is 6 m x 4 m: its rays (2 m beyond) reach no other

// Room k spans x 10k .. 10k + 6, y 0 .. 4 (walls 0.2 m thick on those lines). Room 0 also has
// I1, along x at y = 1 (its face y = 1.1 looks up at the robot), and I2, along y at x = 4.6 (its
// face x = 4.5 looks back at it).
bim::Storey fiveRooms() {
  bim::Storey s;
  for (int k = 0; k < kRooms; ++k) {
    const double x0 = kRoomPitchM * k, x1 = x0 + 6.0;
    const std::string id = "R" + std::to_string(k);
    s.walls.push_back(test::boxWall(id + "S", {x0, 0}, {x1, 0}, 0.2));
    s.walls.push_back(test::boxWall(id + "E", {x1, 0}, {x1, 4}, 0.2));
    s.walls.push_back(test::boxWall(id + "N", {x1, 4}, {x0, 4}, 0.2));
    s.walls.push_back(test::boxWall(id + "W", {x0, 4}, {x0, 0}, 0.2));
    s.rooms.push_back(test::boxRoom(id, x0, 0, x1, 4, {}));
  }
  s.walls.push_back(test::boxWall("I1", {2.0, 1.0}, {4.0, 1.0}, 0.2));
  s.walls.push_back(test::boxWall("I2", {4.6, 0.4}, {4.6, 1.6}, 0.2));
  return s;
}

// The face of wall `w` that looks at `base`, as an exact observation (analytic: the inverse of
// matchObservations' model), its centroid at the face's middle.
pf::detail::Observation faceSeenFrom(const bim::Storey& storey, std::size_t w, const Pose2& base) {
  const bim::Wall& wall = storey.walls.at(w);
  for (const bim::WallFace& face : wall.faces)
    if (const auto o = test::observeFace(face, base)) return *o;
  ADD_FAILURE() << "wall " << w << " not seen";
  return {};
}

}  // namespace

TEST(VerdictBounds, TheMarginIsTheLowestFullMarginNeverALowerBound) {
  const bim::Storey storey = fiveRooms();
  const pf::ParticleFilterConfig config;  // free-space evidence on, its explained rays off
  ASSERT_TRUE(config.free_space_evidence);
  const double bar = config.evidenceMargin();
  // The robot in room 0 at (3, 2.5), heading +x; odometry at its origin (one scan).
  const Pose2 truth(3.0, 2.5, 0.0), odom = Pose2::Zero();
  // It sees S's inner face (y = 0.1), which every room has, and I1's and I2's, which only room 0
  // has: elsewhere two faces unexplained, 2 x 5.67 = 11.34 (half the gate each), over the bar.
  const std::size_t south = 0, i1 = 4 * kRooms, i2 = 4 * kRooms + 1;
  std::vector<pf::detail::Observation> seen;
  for (std::size_t w : {south, i1, i2}) seen.push_back(faceSeenFrom(storey, w, truth));
  // Nine rays ahead-left (+y), through N (inner face y = 3.9) and 2 m beyond: at every place the
  // same, one face's worth (4.17) each (free_space_evidence.hpp).
  pf::RangeProfile profile;
  profile.origin_base = Eigen::Vector3d(0, 0, 0.6);
  for (int k = -4; k <= 4; ++k)
    profile.ends_base.emplace_back(static_cast<float>(0.25 * k), static_cast<float>(3.9 + 2.0 - truth.y()), 1.4f);
  pf::detail::PathEvidence evidence(storey, config);
  ASSERT_TRUE(evidence.addScan(odom, 0.0, seen, &profile));
  // The candidates: the truth; the truth 0.55 m along x (another place by the false-convergence
  // bound, 0.5 m, until fitting moves it back onto the truth: I2's face pulls it, within the
  // gate); and the same pose in each other room.
  evidence.propose(truth, odom);
  evidence.propose(truth + Pose2(0.55, 0.0, 0.0), odom);
  for (int k = 1; k < kRooms; ++k) evidence.propose(truth + Pose2(kRoomPitchM * k, 0.0, 0.0), odom);
  ASSERT_EQ(evidence.candidatePoses(odom).size(), static_cast<std::size_t>(kRooms + 1));

  const pf::detail::PathVerdict v = evidence.verdict(odom);
  ASSERT_TRUE(v.has_best);
  EXPECT_LT((v.best.head<2>() - truth.head<2>()).norm(), 0.01);
  // The brute force: every candidate another place from the best now, its full margin.
  double lowest = std::numeric_limits<double>::infinity();
  int others = 0;
  for (const Pose2& q : evidence.candidatePoses(odom)) {
    if (pf::detail::near(q, v.best, pf::detail::kOtherPlaceM, pf::detail::kOtherPlaceRad)) continue;
    ++others;
    lowest = std::min(lowest, evidence.marginBetween(v.best, q, odom));
  }
  EXPECT_EQ(others, kRooms - 1);  // the offset candidate, fitted, is the truth's place
  EXPECT_NEAR(v.margin, lowest, 1e-9);
  EXPECT_NEAR(lowest, 11.34, 0.05);  // two faces the other rooms lack; the rays cost all alike
  EXPECT_GE(v.margin, bar);
  // The case: the offset candidate's full margin (I2's face 0.55 m off, about 3.2) was the
  // lowest addFreeSpace found, so the rooms' margins were left as bounds, 11.34 - 4.17 = 7.17;
  // the loop fitted three and the fourth's bound stood as the minimum, under the bar.
  EXPECT_NEAR(v.loop_margin, 11.34 - 4.17, 0.05);
  EXPECT_LT(v.loop_margin, bar);
}
