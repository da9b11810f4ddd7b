// Five real lidars in one room (../shared/realdata/nebula/, issue 29 §4 "Real frames"): the
// project's plane extraction on each real frame, the sensors aligned by their own wall planes,
// and the walls they found compared; the room measured from them against the committed plan
// worlds/nebula_room.ifc. docs/realdata_room.md has the numbers. Skips without the data.
#include "real_frames.hpp"

#include "sim/worldgen/worlds.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <string>

using namespace bimloc;

namespace {

// The brief's bar for the walls found by two sensors: the same wall within these.
constexpr double kAgreeAngle_deg = 1.0, kAgreeOffset_m = 0.03;
// Two sensors' planes are the same surface when each is the other's nearest within these (the
// room has surfaces a few centimetres apart: shelf fronts at 4.33, 4.34 and 4.37 m).
constexpr double kSameAngle_deg = 3.0, kSameOffset_m = 0.10;

using Frame = test::RealFrame;

#define REQUIRE_FRAMES(var)                              \
  const std::vector<Frame>* var = test::nebulaFrames(); \
  if (!var) GTEST_SKIP() << "../shared/realdata/nebula not found (BIMLOC_SHARED_REALDATA_DIR): skipping the real frames"

struct WallInVlp {  // a wall moved into the VLP-16's frame, in the plane
  Eigen::Vector2d n;
  double d;
};

std::vector<WallInVlp> inVlp(const Frame& f) {
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(f.in_vlp.pose.z()).toRotationMatrix();
  std::vector<WallInVlp> out;
  for (const auto& w : f.walls) {
    const Eigen::Vector2d n = r * w.normal.head<2>().normalized();
    out.push_back({n, w.d - n.dot(f.in_vlp.pose.head<2>())});
  }
  return out;
}

double angleDeg(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b))) * 180.0 / M_PI;
}

// B's nearest wall to `w` by offset, among those within kSameAngle_deg and kSameOffset_m; -1 if none.
int nearest(const WallInVlp& w, const std::vector<WallInVlp>& b) {
  int best = -1;
  for (int j = 0; j < int(b.size()); ++j)
    if (angleDeg(w.n, b[j].n) < kSameAngle_deg && std::abs(w.d - b[j].d) < kSameOffset_m &&
        (best < 0 || std::abs(w.d - b[j].d) < std::abs(w.d - b[best].d)))
      best = j;
  return best;
}

}  // namespace

// Every frame gives walls to the project's extractor (on its standing points), enough in two
// directions to fix the sensor in the room, except the Pandar40P, which sees the room's two
// ends only (its shelf side hides behind clutter at sensor height): its offset across the room
// comes from its points, not its walls.
TEST(RealFrames, PlaneExtractionFindsTheRoomsWallsInEveryFrame) {
  REQUIRE_FRAMES(f);
  for (const Frame& frame : *f) {
    SCOPED_TRACE(frame.sensor);
    EXPECT_GE(frame.walls.size(), 2u);
    for (const auto& w : frame.walls) EXPECT_LT(std::abs(w.normal.z()), std::sin(10.0 * M_PI / 180.0));
  }
  for (std::size_t k = 1; k < f->size(); ++k) {
    const Frame& frame = (*f)[k];
    SCOPED_TRACE(frame.sensor);
    EXPECT_GE(frame.in_vlp.matches.size(), 2u);
    EXPECT_EQ(frame.in_vlp.directions, frame.sensor == "40p" ? 1 : 2);
  }
}

// The Hesai frames aligned on the VLP-16 by their own walls: the walls each pair of sensors
// both found (mutual nearest, in the VLP-16's frame) agree within 1 degree and 3 cm. Pairs of
// Hesai sensors check the alignment too: each was placed on the VLP-16 independently.
TEST(RealFrames, WallsAgreeBetweenSensorsOnceAligned) {
  REQUIRE_FRAMES(f);
  int compared = 0;
  for (std::size_t i = 0; i < f->size(); ++i)
    for (std::size_t k = i + 1; k < f->size(); ++k) {
      const auto a = inVlp((*f)[i]), b = inVlp((*f)[k]);
      for (int p = 0; p < int(a.size()); ++p) {
        const int q = nearest(a[p], b);
        if (q < 0 || nearest(b[q], a) != p) continue;
        ++compared;
        SCOPED_TRACE((*f)[i].sensor + " wall " + std::to_string(p) + " vs " + (*f)[k].sensor + " wall " + std::to_string(q));
        EXPECT_LE(angleDeg(a[p].n, b[q].n), kAgreeAngle_deg);
        EXPECT_LE(std::abs(a[p].d - b[q].d), kAgreeOffset_m);
      }
    }
  // Measured: 20 pairs of walls over the 10 pairs of sensors.
  EXPECT_GE(compared, 15) << compared;
}

// The rectangle's two readings, 180 degrees apart, fit the walls alike; what told them apart,
// sensor by sensor: more walls matched, or (equal walls) more of the standing points on the
// VLP-16's (the clutter). And the five stood within 0.3 m of one another (SOURCES.md:
// "apparently from the same spot").
TEST(RealFrames, TheRectanglesSymmetryIsResolved) {
  REQUIRE_FRAMES(f);
  for (std::size_t k = 1; k < f->size(); ++k) {
    const test::WallAlignment& a = (*f)[k].in_vlp;
    SCOPED_TRACE((*f)[k].sensor);
    EXPECT_TRUE(a.matches.size() > std::size_t(a.turned_matches) ||
                (int(a.matches.size()) == a.turned_matches && a.overlap > a.turned_overlap + 0.1))
        << a.matches.size() << " walls vs " << a.turned_matches << " turned; overlap " << a.overlap << " vs " << a.turned_overlap;
    EXPECT_LT(a.pose.head<2>().norm(), 0.3);
  }
}

// The room measured from the planes (the VLP-16's ends, the wall behind the shelving seen by all
// five, the QT64's far side) is the plan committed as worlds/nebula_room.ifc, read back by the
// project's IFC reader: 14.17 m x 7.12 m within 3 cm.
TEST(RealFrames, TheCommittedPlanIsTheMeasuredRoom) {
  REQUIRE_FRAMES(f);
  // The long axis: every sensor that sees both ends (mutual-nearest walls, VLP-16's frame).
  std::map<std::string, double> length;
  for (const Frame& frame : *f) {
    double south = 0, north = 0;  // the ends: normals along the VLP-16's +y and -y
    for (const auto& w : inVlp(frame)) {
      if (angleDeg(w.n, Eigen::Vector2d::UnitY()) < 5) south = std::max(south, w.d);
      if (angleDeg(w.n, -Eigen::Vector2d::UnitY()) < 5) north = std::max(north, w.d);
    }
    if (south > 0 && north > 0) length[frame.sensor] = south + north;
  }
  ASSERT_EQ(length.size(), 3u);  // VLP-16, Pandar40P, PandarXT32
  const bim::Building plan = bim::readIfc(std::string(BIMLOC_WORLDS_DIR) + "/nebula_room.ifc");
  ASSERT_EQ(plan.storeys.size(), 1u);
  ASSERT_EQ(plan.storeys[0].rooms.size(), 1u);
  Eigen::AlignedBox2d box;
  for (const auto& p : plan.storeys[0].rooms[0].footprint) box.extend(p);
  for (const auto& [sensor, l] : length) EXPECT_NEAR(l, box.sizes().x(), kAgreeOffset_m) << sensor;
  // Across: the QT64's far side, the one sensor that sees it, to the wall behind the shelving.
  // Of the QT64's two planes there (2.19 and 2.35 m from the VLP-16), the one nearer to
  // vertical: the other leans 7.4 degrees (a panel against the wall, not the wall).
  const auto qt64 = inVlp(f->back());
  double far = 0, far_lean = 1;
  for (std::size_t p = 0; p < qt64.size(); ++p) {
    const double lean = std::abs(f->back().walls[p].normal.z());
    if (angleDeg(qt64[p].n, -Eigen::Vector2d::UnitX()) < 5 && lean < far_lean) far = qt64[p].d, far_lean = lean;
  }
  // The wall behind the shelving: in each whole frame, the best-supported plane facing the room
  // 0.4-0.7 m behind the shelving's front (4.367 m from the VLP-16), seen between and above the
  // shelves; the median of the five frames' (measured 4.89-4.99 m: 4.93).
  std::vector<double> north;
  for (const Frame& frame : *f) {
    Frame whole = frame;
    whole.walls = frame.whole_walls;
    const auto walls = inVlp(whole);
    int best = -1;
    for (int p = 0; p < int(walls.size()); ++p)
      if (angleDeg(walls[p].n, Eigen::Vector2d::UnitX()) < 5 && walls[p].d > 4.367 + 0.4 && walls[p].d < 4.367 + 0.7 &&
          (best < 0 || whole.walls[p].inliers > whole.walls[best].inliers))
        best = p;
    if (best >= 0) north.push_back(walls[best].d);
  }
  ASSERT_EQ(north.size(), f->size());
  std::sort(north.begin(), north.end());
  EXPECT_NEAR(far + north[north.size() / 2], box.sizes().y(), kAgreeOffset_m);
  EXPECT_NEAR(plan.storeys[0].rooms[0].height_m, 3.5, 1e-6);
}

// The same comparison on the whole frames (no standing points chosen in the test: the
// extractor's own standing stage, wholeFrameConfig()), for the room's sides as measured
// (docs/realdata_room.md, section 3; VLP-16's frame): each sensor's plane nearest to each side
// (within 3 degrees and 0.10 m once aligned), compared between every two sensors that have it.
// A whole frame also gives the clutter's planes (desks, cabinets: up to 40 in the QT64's), which
// are parts of surfaces seen differently from each sensor: they are not compared.
//
// Where the 1.6 degrees of the first version came from (docs/results/2026-11-27-h29place2.md):
// - the north side's shelving is no plane: one frame's pieces of it, 4 mm apart in offset, differ
//   by 2.6 degrees (the Pandar40P's at 4.364 and 4.368 m: -0.4 and -2.9 degrees), so the piece
//   nearest the side's offset is a draw among them; every pair over 1 degree involved it or
//   the second cause;
// - the alignment (alignWalls, on the standing points' walls) fixes the yaw of the Pandar64 and
//   the QT64 from two walls, one of them a piece of that shelving: the 64's ends came out turned
//   0.6-1.1 degrees from every other sensor's.
// So the sensors are aligned here by the room's walls, not its furniture: the yaw of each Hesai
// sensor on the VLP-16 from the two end walls all five see (long, plane: 3-9 mm RMS), each
// pair's angle weighted by the inverse of the two fits' azimuth variances (the extractor's own
// covariance: the maximum-likelihood yaw of independent fits); the translation by least squares
// on the same ends and on the wall behind the shelving (every sensor sees it between and above
// the shelves), weighted by the fits' offset variances (alignedOnTheRoom). Session 15 kept
// alignWalls' translation, which places the 64 and the QT64 across the room by the shelving's
// pieces: their south wall came out 4.2 cm apart (docs/results/2026-11-27-h29close.md).
// Each sensor's plane of a wall is its best-supported one there (sidePlane). The walls are held
// to the brief's 1 degree and 3 cm, the south wall included; the shelf front, furniture, to the
// 2 degrees and 5 cm the spread of its pieces allows (0.23 m in depth within one frame).
// Measured: the walls within 0.59 degrees and 2.1 cm (21 pairs; the south wall 1.5 cm, 0.59
// degrees), the shelf front within 1.48 degrees and 3.3 cm.
constexpr double kShelfAgreeAngle_deg = 2.0, kShelfAgreeOffset_m = 0.05;

struct RoomSide {
  const char* name;
  WallInVlp at;   // as measured, VLP-16's frame
  bool wall;      // false: the shelving's front (furniture)
};
const RoomSide kRoomSides[] = {{"west end", {Eigen::Vector2d::UnitY(), 6.328}, true},
                               {"east end", {-Eigen::Vector2d::UnitY(), 7.845}, true},
                               {"south wall", {-Eigen::Vector2d::UnitX(), 2.189}, true},
                               {"shelf front", {Eigen::Vector2d::UnitX(), 4.367}, false}};

// The whole frame's walls in the VLP-16's frame at alignment `pose` (x, y, yaw).
std::vector<WallInVlp> wholeInVlp(const Frame& frame, const Eigen::Vector3d& pose) {
  Frame whole = frame;
  whole.walls = frame.whole_walls;
  whole.in_vlp.pose = pose;
  return inVlp(whole);
}

// The sensor's plane of a side of the room: of its planes within 3 degrees and 0.10 m of the
// side as measured, the best supported (most voxels): the side's main surface. Not the one
// nearest the measured offset, a draw among pieces a centimetre apart that a few millimetres
// of alignment turn (the Pandar40P's west end: pieces at 6.316 m, 88.0 deg, 92 voxels and 6.339
// m, 90.7 deg, 48 voxels). -1 if none.
int sidePlane(const RoomSide& side, const std::vector<WallInVlp>& walls, const Frame& frame) {
  int best = -1;
  for (int p = 0; p < int(walls.size()); ++p)
    if (angleDeg(side.at.n, walls[p].n) < kSameAngle_deg && std::abs(side.at.d - walls[p].d) < kSameOffset_m &&
        (best < 0 || frame.whole_walls[p].inliers > frame.whole_walls[best].inliers))
      best = p;
  return best;
}

// The sensor's yaw on the VLP-16 from the end walls both see (whole frames), weighted by the
// inverse of the sum of the two fits' azimuth variances; alignWalls' translation kept.
Eigen::Vector3d alignedOnTheEnds(const Frame& frame, const Frame& vlp) {
  Eigen::Vector3d pose = frame.in_vlp.pose;
  const auto ref = wholeInVlp(vlp, Eigen::Vector3d::Zero()), mine = wholeInVlp(frame, pose);
  double sum = 0, weights = 0;
  for (int s = 0; s < 2; ++s) {
    const int r = sidePlane(kRoomSides[s], ref, vlp), m = sidePlane(kRoomSides[s], mine, frame);
    if (r < 0 || m < 0) continue;
    const Eigen::Vector2d a = mine[m].n, b = ref[r].n;
    const double w = 1.0 / (vlp.whole_walls[r].covariance(0, 0) + frame.whole_walls[m].covariance(0, 0));
    sum += w * std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)), weights += w;
  }
  if (weights > 0) pose.z() += sum / weights;
  return pose;
}

// The wall behind the shelving (docs/realdata_room.md section 3): the planes facing the room
// 0.4-0.7 m behind the shelving's front (4.367 m from the VLP-16), seen between and above the
// shelves by every sensor, in the VLP-16's frame at alignment `pose`: their indexes.
std::vector<int> northWallPieces(const std::vector<WallInVlp>& walls) {
  std::vector<int> out;
  for (int p = 0; p < int(walls.size()); ++p)
    if (angleDeg(walls[p].n, Eigen::Vector2d::UnitX()) < kSameAngle_deg && walls[p].d > kRoomSides[3].at.d + 0.4 &&
        walls[p].d < kRoomSides[3].at.d + 0.7)
      out.push_back(p);
  return out;
}

// The sensor on the VLP-16 by the walls of the room all five see: the yaw on the two end walls
// (alignedOnTheEnds), then the translation by weighted least squares on the ends and the wall
// behind the shelving: each of the sensor's pieces of them paired with the VLP-16's nearest
// piece of the same wall (within 3 degrees and 0.10 m at alignWalls' translation), each pair
// weighted by the inverse sum of the two fits' offset variances, as the yaw is by their azimuth
// variances. The across-room offset then rests on a wall, not on the shelving's pieces.
Eigen::Vector3d alignedOnTheRoom(const Frame& frame, const Frame& vlp) {
  Eigen::Vector3d pose = alignedOnTheEnds(frame, vlp);
  const auto ref = wholeInVlp(vlp, Eigen::Vector3d::Zero()), mine = wholeInVlp(frame, pose);
  std::vector<std::pair<int, int>> pairs;  // (mine, ref)
  for (int s = 0; s < 2; ++s) {
    const int r = sidePlane(kRoomSides[s], ref, vlp), m = sidePlane(kRoomSides[s], mine, frame);
    if (r >= 0 && m >= 0) pairs.emplace_back(m, r);
  }
  const std::vector<int> ref_north = northWallPieces(ref);
  std::vector<WallInVlp> ref_pieces;
  for (int r : ref_north) ref_pieces.push_back(ref[r]);
  for (int m : northWallPieces(mine)) {
    const int k = nearest(mine[m], ref_pieces);
    if (k >= 0) pairs.emplace_back(m, ref_north[k]);
  }
  // The sensor's plane moved by a further dt lies at d - n.dt: solve n.dt = d_mine - d_ref.
  Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  for (const auto& [m, r] : pairs) {
    const double w = 1.0 / (frame.whole_walls[m].covariance(2, 2) + vlp.whole_walls[r].covariance(2, 2));
    const Eigen::Vector2d n = mine[m].n;
    A += w * n * n.transpose(), b += w * n * (mine[m].d - ref[r].d);
  }
  if (std::abs(A.determinant()) > 1e-9 * A.squaredNorm()) pose.head<2>() += A.ldlt().solve(b);
  return pose;
}

TEST(RealFrames, WholeFrameWallsOfTheRoomAgreeBetweenSensors) {
  REQUIRE_FRAMES(f);
  for (const Frame& frame : *f) {
    std::cout << "[ real ] " << frame.sensor << ": " << frame.whole_walls.size() << " walls on the whole frame\n";
    EXPECT_GE(frame.whole_walls.size(), 4u) << frame.sensor;
  }
  std::vector<std::vector<WallInVlp>> walls;
  for (const Frame& frame : *f) {
    const Eigen::Vector3d pose = &frame == &f->front() ? Eigen::Vector3d::Zero() : alignedOnTheRoom(frame, f->front());
    std::cout << "[ real ] " << frame.sensor << " aligned on the room's walls: x, y " << pose.x() << ", " << pose.y() << " m, yaw "
              << pose.z() * 180 / M_PI << " deg (alignWalls " << frame.in_vlp.pose.x() << ", " << frame.in_vlp.pose.y() << " m, "
              << frame.in_vlp.pose.z() * 180 / M_PI << " deg)\n";
    walls.push_back(wholeInVlp(frame, pose));
  }
  int compared = 0;
  double worst_angle = 0, worst_offset = 0, worst_shelf_angle = 0;
  for (const RoomSide& side : kRoomSides) {
    std::vector<std::pair<std::string, WallInVlp>> seen;
    for (std::size_t k = 0; k < f->size(); ++k) {
      // A wall: its main surface. The shelving is no one surface (pieces over 0.23 m in depth,
      // each frame's best supported a different shelf): the piece nearest its measured front.
      const int w = side.wall ? sidePlane(side, walls[k], (*f)[k]) : nearest(side.at, walls[k]);
      if (w >= 0) seen.emplace_back((*f)[k].sensor, walls[k][w]);
    }
    std::cout << "[ real ] " << side.name << ":";
    for (const auto& [sensor, w] : seen)
      std::cout << " " << sensor << " " << w.d << " m " << std::atan2(w.n.y(), w.n.x()) * 180 / M_PI << " deg";
    std::cout << "\n";
    for (std::size_t i = 0; i < seen.size(); ++i)
      for (std::size_t k = i + 1; k < seen.size(); ++k) {
        SCOPED_TRACE(std::string(side.name) + ": " + seen[i].first + " vs " + seen[k].first);
        const double angle = angleDeg(seen[i].second.n, seen[k].second.n), offset = std::abs(seen[i].second.d - seen[k].second.d);
        if (!side.wall) {
          worst_shelf_angle = std::max(worst_shelf_angle, angle);
          EXPECT_LE(angle, kShelfAgreeAngle_deg);
          EXPECT_LE(offset, kShelfAgreeOffset_m);
          continue;
        }
        ++compared;
        worst_angle = std::max(worst_angle, angle);
        EXPECT_LE(angle, kAgreeAngle_deg);
        // The south wall too (the 64 and the QT64 only): placed across the room on the wall
        // behind the shelving, not on the shelving's pieces, they agree (4.2 cm apart before).
        worst_offset = std::max(worst_offset, offset);
        EXPECT_LE(offset, kAgreeOffset_m);
      }
  }
  std::cout << "[ real ] whole frames: " << compared << " pairs of room walls, worst " << worst_angle << " deg, " << worst_offset
            << " m; shelf front worst " << worst_shelf_angle << " deg\n";
  EXPECT_GE(compared, 20) << compared;
}
