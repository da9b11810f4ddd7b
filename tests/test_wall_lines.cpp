// Wall lines (pf/wall_lines.hpp) and the rule they serve: an observed plane is a face only
// where all of its support, not just its centroid, lies along the face's wall line. Truth is
// analytic: walls built in code, planes written down from their geometry.
//
// The case it is for (Jesse.1 Level -1): a row of identical bays opening on a corridor. A robot
// in the corridor sees the building's end wall as one run of points several metres long; at
// the next bay along the row, that plane falls on the partition between two bays, which ends
// where the bay does. Judged by the centroid alone the partition "explains" it, and the next
// bay stays a perfect rival until the robot sees some other wall the row does not repeat.
#include "face_index_fixtures.hpp"
#include "pf/measurement.hpp"
#include "pf/room_index.hpp"
#include "pf/wall_lines.hpp"
#include "sgraph_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace bimloc;
using pf::detail::Observation;

namespace {

constexpr double kBaseZ = 0.5;

// The x-range (or y-range for a wall along y) of face `id`'s wall line, in the map.
std::pair<double, double> lineRange(const bim::Storey& s, const std::vector<pf::detail::LineSpan>& lines, int id, int coord) {
  const bim::WallFace& f = s.walls[static_cast<std::size_t>(id / 2)].faces[id % 2];
  const Eigen::Vector2d a = f.start.head<2>(), dir = (f.end.head<2>() - a).normalized();
  const double p = (a + lines[static_cast<std::size_t>(id)].lo_m * dir)(coord), q = (a + lines[static_cast<std::size_t>(id)].hi_m * dir)(coord);
  return {std::min(p, q), std::max(p, q)};
}

// A vertical plane of normal n (map, towards the robot), n.p + d = 0, seen from `pose`: its
// support runs along the plane from `from` to `to` (map), and its returns' centroid is at
// `centroid` (dense near the sensor, so not the middle). As ParticleFilter::observe gives it.
Observation seen(const Eigen::Vector3d& pose, const Eigen::Vector2d& n, double d, const Eigen::Vector2d& from,
                 const Eigen::Vector2d& to, const Eigen::Vector2d& centroid, bool middle_known = true) {
  Observation o = test::planeSeenFrom(pose, n, d, centroid);
  o.extent_m = (to - from).norm();
  if (middle_known)
    o.span_middle_base = Eigen::Rotation2Dd(-pose.z()) * (0.5 * (from + to) - pose.head<2>()), o.wall_span_m = o.extent_m;
  o.z_low = -kBaseZ, o.z_high = 2.8 - kBaseZ;
  return o;
}

pf::detail::ObservationMatch matchAt(const Eigen::Vector3d& pose, const Observation& o, const pf::detail::RoomIndex& faces,
                                     bool wall_lines = true) {
  pf::ParticleFilterConfig c;
  c.use_rooms = false;
  c.match_wall_lines = wall_lines;
  pf::Particle p;
  p.x = pose.x(), p.y = pose.y(), p.yaw = pose.z(), p.room = faces.roomAt(p.x, p.y);
  std::vector<pf::detail::ObservationMatch> per;
  pf::detail::matchObservations(p, kBaseZ, {o}, faces, c, &per, false);
  return per.at(0);
}

}  // namespace

TEST(WallLines, PiecesInOnePlaneJoinAcrossADoorGapButNotAcrossAPassageOrAnOffset) {
  bim::Storey s;
  s.walls.push_back(test::boxWall("A", {0, 0}, {4, 0}, 0.2));       // 0..4
  s.walls.push_back(test::boxWall("B", {8, 0}, {4.8, 0}, 0.2));     // 4.8..8, drawn the other way: a 0.8 m door gap
  s.walls.push_back(test::boxWall("C", {9.5, 0}, {12, 0}, 0.2));    // 1.5 m further on: a passage
  s.walls.push_back(test::boxWall("D", {12.5, 0.25}, {15, 0.25}, 0.2));  // in line with nothing: 0.25 m off
  const auto lines = pf::detail::wallLines(s, {});
  ASSERT_EQ(lines.size(), 8u);
  for (int f = 0; f < 2; ++f) {
    // A and B make one line, from either end, whichever face (both sides are in line).
    EXPECT_NEAR(lineRange(s, lines, 0 + f, 0).first, 0.0, 1e-9);
    EXPECT_NEAR(lineRange(s, lines, 0 + f, 0).second, 8.0, 1e-9);
    EXPECT_NEAR(lineRange(s, lines, 2 + f, 0).first, 0.0, 1e-9);
    EXPECT_NEAR(lineRange(s, lines, 2 + f, 0).second, 8.0, 1e-9);
    // C and D are lines of their own.
    EXPECT_NEAR(lineRange(s, lines, 4 + f, 0).first, 9.5, 1e-9);
    EXPECT_NEAR(lineRange(s, lines, 4 + f, 0).second, 12.0, 1e-9);
    EXPECT_NEAR(lineRange(s, lines, 6 + f, 0).first, 12.5, 1e-9);
    EXPECT_NEAR(lineRange(s, lines, 6 + f, 0).second, 15.0, 1e-9);
  }
  // A face ignored (buried) joins no line and gets none.
  std::vector<bool> ignored(8, false);
  ignored[2] = ignored[3] = true;
  const auto without_b = pf::detail::wallLines(s, ignored);
  EXPECT_NEAR(lineRange(s, without_b, 0, 0).second, 4.0, 1e-9);
  EXPECT_NEAR(lineRange(s, without_b, 2, 0).first, 4.8, 1e-9);
}

TEST(WallLines, ANormalTurnedAroundIsAnotherLine) {
  bim::Storey s;
  // Two walls end to end, 0.2 m thick: face 0 of each looks +y. A third, drawn over the same
  // axis but 0.4 m thick, has faces 0.1 m beyond theirs: within kInLineM, one line.
  s.walls.push_back(test::boxWall("A", {0, 0}, {4, 0}, 0.2));
  s.walls.push_back(test::boxWall("B", {4, 0}, {7, 0}, 0.2));
  s.walls.push_back(test::boxWall("C", {7, 0}, {9, 0}, 0.4));
  const auto lines = pf::detail::wallLines(s, {});
  EXPECT_NEAR(lineRange(s, lines, 0, 0).second, 9.0, 1e-9);  // +y faces: A, B, C
  EXPECT_NEAR(lineRange(s, lines, 1, 0).second, 9.0, 1e-9);  // -y faces: A, B, C
  // Face 0 (+y) of A at y = 0.1 and face 1 (-y) of A at y = -0.1 never join: opposite normals.
  s.walls.push_back(test::boxWall("E", {12, 0.2}, {10, 0.2}, 0.2));  // drawn backwards: face 0 looks -y, at y = 0.1
  const auto more = pf::detail::wallLines(s, {});
  EXPECT_NEAR(lineRange(s, more, 0, 0).second, 9.0, 1e-9);   // A's +y face: not joined by E's -y face at y = 0.1
  EXPECT_NEAR(lineRange(s, more, 6, 0).first, 10.0, 1e-9);   // E's -y face: a line of its own
}

TEST(WallLines, APlaneRunningPastTheEndOfAPartitionIsNotThatPartition) {
  // An end wall along y at x = 0 (its inside face at x = 0.1, normal +x), 10 m long; a
  // partition at x = 3 from y = 5 to y = 10 (faces at x = 2.9 and 3.1). The robot at (1.5, 2)
  // sees the end wall from y = 0.1 to y = 8 (extent 7.9), its returns densest near y = 5.5.
  bim::Storey s;
  s.walls.push_back(test::boxWall("end", {0, 0}, {0, 10}, 0.2));
  s.walls.push_back(test::boxWall("partition", {3, 5}, {3, 10}, 0.2));
  const pf::detail::RoomIndex faces(s, /*use_rooms=*/false);
  const Eigen::Vector3d truth(1.5, 2.0, 0.4), next_bay(4.5, 2.0, 0.4);
  const Observation end_wall = seen(truth, {1, 0}, -0.1, {0.1, 0.1}, {0.1, 8.0}, {0.1, 5.5});
  // At the truth: the end wall's inside face (wall 0, face 1).
  const auto at_truth = matchAt(truth, end_wall, faces);
  EXPECT_EQ(at_truth.face, 1);
  EXPECT_LT(at_truth.m2, 1e-9);
  // 3 m along, the plane lands on the partition's +x face at x = 3.1: centroid (y = 5.5) on
  // it, support from y = 0.1, 4.9 m before its start. Not the partition: clutter.
  const auto at_next_bay = matchAt(next_bay, end_wall, faces);
  EXPECT_EQ(at_next_bay.face, -1);
  EXPECT_NEAR(at_next_bay.m2, pf::ParticleFilterConfig{}.gate_mahalanobis2, 1e-6);
  // With the rule off (ParticleFilterConfig::match_wall_lines; on by default, and off in the
  // search after a loss of track), the centroid alone decides, and the partition explains it.
  EXPECT_TRUE(pf::ParticleFilterConfig{}.match_wall_lines);
  EXPECT_EQ(matchAt(next_bay, end_wall, faces, false).face, 3);
  // Within the margin (0.5 m) of the partition's end, a plane is still the partition.
  const Observation short_run = seen(truth, {1, 0}, -0.1, {0.1, 5.0 - 0.4}, {0.1, 9.0}, {0.1, 6.0});
  EXPECT_EQ(matchAt(next_bay, short_run, faces).face, 3);
}

TEST(WallLines, TheSupportIsPlacedByItsMiddleNotByItsCentroid) {
  // The robot stands 0.3 m from the end of a 10 m wall drawn in two pieces (y 0-5, 5-10) and
  // sees it from y = 0.1 to y = 8: the returns crowd near it (centroid y = 1.0). Centred on the
  // centroid, the support would run to y = -2.95, past the wall's end; its middle is y = 4.05.
  bim::Storey s;
  s.walls.push_back(test::boxWall("end-a", {0, 0}, {0, 5}, 0.2));
  s.walls.push_back(test::boxWall("end-b", {0, 5}, {0, 10}, 0.2));
  const pf::detail::RoomIndex faces(s, /*use_rooms=*/false);
  const Eigen::Vector3d truth(0.4, 0.6, -0.2);
  const Observation o = seen(truth, {1, 0}, -0.1, {0.1, 0.1}, {0.1, 8.0}, {0.1, 1.0});
  EXPECT_EQ(matchAt(truth, o, faces).face, 1);  // end-a's +x face, its line running on through end-b
  // Centred on the centroid instead, the plane would be clutter at the truth.
  Observation centred = o;
  centred.span_middle_base = centred.centroid_base;
  EXPECT_EQ(matchAt(truth, centred, faces).face, -1);
  // Where the extraction gave no standing span, only the centroid is checked (along the face).
  Observation unknown = o;
  unknown.wall_span_m = 0;
  EXPECT_EQ(matchAt(truth, unknown, faces).face, 1);
}
