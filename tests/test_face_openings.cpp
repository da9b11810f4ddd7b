// Wall face openings (localizer/src/bim/face_openings.cpp): the holes of a wall's faces from its
// body mesh, against the analytic openings cut into a box wall and against a second export of
// the same house; and the S-Graph's association, which takes no plane in a hole for the wall.
#include "test_support.hpp"

#include "bim/extraction.hpp"
#include "bim/openings.hpp"
#include "sgraph/association.hpp"

#include <bimloc/bim/building_json.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace bimloc;
using bim::detail::Extrusion;

namespace {

// A vertical prism over a counter-clockwise footprint.
Extrusion prism(const std::vector<Eigen::Vector2d>& footprint, double z0, double z1) {
  Extrusion e;
  e.footprint = footprint;
  for (const auto& p : footprint) e.corners.emplace_back(p.x(), p.y(), z0), e.corners.emplace_back(p.x(), p.y(), z1);
  e.z_min = z0, e.z_max = z1, e.vertical = true;
  return e;
}

// A wall along x from 0 to 5 m, y in [0, 0.3], 2.6 m tall, with openings [a0, a1] x [z0, z1]
// (x and z) cut through it.
struct Hole {
  double a0, a1, z0, z1;
};
bim::detail::RawProduct wallWithHoles(const std::vector<Hole>& holes) {
  std::vector<Extrusion> cuts;
  for (const auto& h : holes) cuts.push_back(prism({{h.a0, -0.1}, {h.a1, -0.1}, {h.a1, 0.4}, {h.a0, 0.4}}, h.z0, h.z1));
  const auto cut = bim::detail::cutOpenings(prism({{0, 0}, {5, 0}, {5, 0.3}, {0, 0.3}}, 0.0, 2.6), cuts);
  EXPECT_EQ(cut.cut, holes.size());
  bim::detail::RawProduct p;
  p.global_id = "w";
  p.ifc_class = "IfcWall";
  p.mesh = cut.mesh;
  return p;
}

// The openings of every face, in x (not along the face): comparable between the two faces.
std::vector<Hole> openingsInX(const bim::WallFace& face) {
  std::vector<Hole> out;
  const double dir = face.end.x() > face.start.x() ? 1.0 : -1.0;
  for (const auto& o : face.openings) {
    const double a = face.start.x() + dir * o.along_min_m, b = face.start.x() + dir * o.along_max_m;
    out.push_back({std::min(a, b), std::max(a, b), o.z_min_m, o.z_max_m});
  }
  std::sort(out.begin(), out.end(), [](const Hole& l, const Hole& r) { return l.a0 < r.a0; });
  return out;
}

}  // namespace

TEST(FaceOpenings, AWindowAndADoorCutIntoABoxWallAreFoundOnBothFaces) {
  const Hole door{1.0, 1.9, 0.0, 2.1}, window{3.0, 4.2, 0.9, 2.2};
  const auto p = wallWithHoles({door, window});
  std::string problem;
  const auto wall = bim::detail::wallFromGeometry(p, problem);
  ASSERT_TRUE(wall) << problem;
  for (const auto& face : wall->faces) {
    bim::WallFace f = face;
    f.openings = bim::detail::faceOpenings(face, wall->start.z(), wall->height_m, p.mesh);
    const auto found = openingsInX(f);
    ASSERT_EQ(found.size(), 2u);
    // To the 5 cm raster: every edge within one cell of the truth.
    for (const auto& [got, truth] : {std::pair{found[0], door}, std::pair{found[1], window}}) {
      EXPECT_NEAR(got.a0, truth.a0, 0.05);
      EXPECT_NEAR(got.a1, truth.a1, 0.05);
      EXPECT_NEAR(got.z0, truth.z0, 0.05);
      EXPECT_NEAR(got.z1, truth.z1, 0.05);
    }
  }
}

TEST(FaceOpenings, SmallHolesAndGapsOverTheWholeHeightAreNoOpenings) {
  // A 0.2 m duct, and the wall cut in two over its whole height (as a wall drawn in two
  // pieces, or a mitred corner, leaves the face): neither is a hole a plane could be seen in.
  const auto p = wallWithHoles({{1.0, 1.2, 1.0, 1.2}, {3.0, 3.5, 0.0, 2.6}});
  std::string problem;
  const auto wall = bim::detail::wallFromGeometry(p, problem);
  ASSERT_TRUE(wall) << problem;
  for (const auto& face : wall->faces) EXPECT_TRUE(bim::detail::faceOpenings(face, 0.0, 2.6, p.mesh).empty());
  // A face the body has no triangle on says nothing: no openings rather than one hole.
  EXPECT_TRUE(bim::detail::faceOpenings(wall->faces[0], 0.0, 2.6, bim::TriangleMesh{}).empty());
}

TEST(FaceOpenings, SurviveTheBuildingJson) {
  bim::Building b;
  bim::Storey s;
  bim::Wall w;
  w.id = "w";
  w.end = Eigen::Vector3d(5, 0, 0);
  w.faces[0].openings = {{1.0, 1.9, 0.0, 2.1}, {3.0, 4.2, 0.9, 2.2}};
  s.walls.push_back(w);
  b.storeys.push_back(s);
  const bim::Building back = bim::buildingFromJson(bim::toJson(b));
  const auto& o = back.storeys.at(0).walls.at(0).faces[0].openings;
  ASSERT_EQ(o.size(), 2u);
  EXPECT_DOUBLE_EQ(o[1].along_min_m, 3.0);
  EXPECT_DOUBLE_EQ(o[1].z_max_m, 2.2);
  EXPECT_TRUE(back.storeys.at(0).walls.at(0).faces[1].openings.empty());
}

// The FZK-Haus exported twice (ArchiCAD 11 to IFC2X3, ArchiCAD 20 to IFC4: two files, two
// geometry paths): its walls' openings agree, and its west wall has its two windows and the
// door where both files put them.
TEST(FaceOpenings, TheFzkHausHasTheSameOpeningsInBothExports) {
  BIMLOC_REQUIRE_SHARED(a_path, "AC11-FZK-Haus-IFC.ifc");
  BIMLOC_REQUIRE_SHARED(b_path, "AC20-FZK-Haus.ifc");
  bim::ExtractOptions options;
  options.build_meshes = false;
  const bim::Building a = bim::readIfc(a_path, options), b = bim::readIfc(b_path, options);
  int compared = 0, openings = 0;
  for (const auto& wa : a.storeys.at(0).walls) {
    const bim::Wall* wb = b.storeys.at(0).findWall(wa.id);
    if (!wb) continue;
    for (std::size_t k = 0; k < 2; ++k) {
      const auto& oa = wa.faces[k].openings;
      const auto& ob = wb->faces[k].openings;
      ASSERT_EQ(oa.size(), ob.size()) << wa.id << " face " << k;
      for (std::size_t i = 0; i < oa.size(); ++i) {
        EXPECT_NEAR(oa[i].along_min_m, ob[i].along_min_m, 0.051) << wa.id;
        EXPECT_NEAR(oa[i].along_max_m, ob[i].along_max_m, 0.051) << wa.id;
        EXPECT_NEAR(oa[i].z_min_m, ob[i].z_min_m, 0.051) << wa.id;
        EXPECT_NEAR(oa[i].z_max_m, ob[i].z_max_m, 0.051) << wa.id;
      }
      openings += static_cast<int>(oa.size());
    }
    ++compared;
  }
  EXPECT_GE(compared, 9);
  EXPECT_GE(openings, 20);
  const bim::Wall* west = a.storeys.at(0).findWall("3rPX_Juz59peXXY6wDJl18");  // x in [0, 0.3], y in [0, 10]
  ASSERT_TRUE(west);
  const bim::WallFace& in = west->faces[0].plane.n.x() > 0 ? west->faces[0] : west->faces[1];
  ASSERT_EQ(in.openings.size(), 3u);  // two windows and the entrance door, on the room side
  int doors = 0;
  for (const auto& o : in.openings) doors += o.z_min_m < 0.05;
  EXPECT_EQ(doors, 1);
}

namespace {

// A plan wall node along x, face 0 looking +y at y = 0 (face 1 `thickness_m` behind), with
// `opening` in face 0; and a keyframe 3 m in front of it, looking at it (lidar = base).
sgraph::detail::WallNode wallNodeAlongX(double length_m, double thickness_m, const bim::FaceOpening& opening) {
  sgraph::detail::WallNode node;
  node.face[0].centre = Eigen::Vector2d(2.5, 0.0);
  node.face[0].e = Eigen::Vector2d::UnitY();
  node.face[0].side = 1.0;
  node.face[0].h = 0.0;
  node.face[1] = node.face[0];
  node.face[1].side = -1.0;
  node.face[1].h = -thickness_m;
  node.start = {Eigen::Vector2d(0, 0), Eigen::Vector2d(length_m, -thickness_m)};
  node.end = {Eigen::Vector2d(length_m, 0), Eigen::Vector2d(0, -thickness_m)};
  node.openings[0] = {opening};
  return node;
}

sgraph::detail::Keyframe keyframeBeforeTheWall() {
  sgraph::detail::Keyframe kf;
  kf.pose = {2.5, 3.0, -M_PI / 2};  // looking -y, at the wall
  kf.A = Eigen::Matrix3d::Identity();
  kf.b = Eigen::Vector3d::Zero();
  return kf;
}

}  // namespace

TEST(FaceOpenings, TheSGraphTakesNoPlaneInAFaceOpeningForTheWall) {
  // A plan wall node along x (face 0 looking +y at y = 0, 5 m long) with a window
  // [1.5, 3.5] x [0.9, 2.1]; a keyframe 3 m in front of it, looking at it; an observed plane
  // 0.12 m behind the face (the glass): inside the gate, and its support inside the window.
  sgraph::detail::WallNode node = wallNodeAlongX(5.0, 0.3, {1.5, 3.5, 0.9, 2.1});
  const sgraph::detail::Keyframe kf = keyframeBeforeTheWall();
  sgraph::SGraphConfig config;
  sgraph::detail::ScanObservation glass;
  glass.minimal = planes::minimalPlane(Eigen::Vector3d(-1, 0, 0), 3.12);  // in the lidar frame: ahead, 3.12 m
  glass.covariance = Eigen::Vector3d(1e-4, 1e-4, 4e-4).asDiagonal();
  glass.normal_map = Eigen::Vector2d::UnitY();
  glass.centroid_map = Eigen::Vector2d(2.5, -0.12);
  glass.extent_m = 1.8;
  glass.z_map = 1.5;
  glass.height_extent_m = 1.0;
  glass.axis = bim::WallAxis::Y;
  EXPECT_TRUE(std::isinf(sgraph::detail::matchDistance2(node, 0, kf, glass, config)));
  // The same plane where the face has no hole is the wall (within the gate).
  node.openings[0].clear();
  EXPECT_LT(sgraph::detail::matchDistance2(node, 0, kf, glass, config), config.association_gate_mahalanobis2);
  // A plane of the wall around the window (its support wider than the hole) is the wall too.
  node.openings[0] = {{1.5, 3.5, 0.9, 2.1}};
  sgraph::detail::ScanObservation wall = glass;
  wall.minimal[2] = 3.0, wall.centroid_map.y() = 0.0, wall.extent_m = 4.0, wall.height_extent_m = 2.4, wall.z_map = 1.2;
  EXPECT_LT(sgraph::detail::matchDistance2(node, 0, kf, wall, config), config.association_gate_mahalanobis2);
}

TEST(FaceOpenings, TheSGraphJudgesAPaneByWhereItStandsNotByItsCentroid) {
  // The Duplex's living-room window (A102, the south wall): 4.85 m wide, along 0.4-5.25, z
  // 0.1-2.5 (node as above: face 0 looking +y at y = 0); a keyframe 3 m before it. The pane 0.37
  // m behind the face is seen from near the window's west end: its returns are dense there, so
  // its centroid lies 0.15 m west of the middle of where it stands (0.5-5.1 m) and its heights'
  // mean 0.45 m below their middle (0.3-2.2 m). Centroid -+ half the extents (0.2-5.1 m, z
  // -0.15-1.75) overflows the grown opening (0.25-5.4, z -0.05-2.65); where it stands does not.
  sgraph::detail::WallNode node = wallNodeAlongX(8.4, 0.417, {0.4, 5.25, 0.1, 2.5});
  const sgraph::detail::Keyframe kf = keyframeBeforeTheWall();
  sgraph::SGraphConfig config;
  // Seen from a pose 0.34 m north of the truth, the pane lies 0.03 m behind the face: in the gate.
  sgraph::detail::ScanObservation pane;
  pane.minimal = planes::minimalPlane(Eigen::Vector3d(-1, 0, 0), 3.03);
  pane.covariance = Eigen::Vector3d(1e-4, 1e-4, 4e-4).asDiagonal();
  pane.normal_map = Eigen::Vector2d::UnitY();
  pane.centroid_map = Eigen::Vector2d(2.65, -0.03);
  pane.extent_m = 4.9;  // the whole support, a strip of the reveal included
  pane.height_extent_m = 1.9;
  pane.axis = bim::WallAxis::Y;
  // What the graph read before: the centroid's height, no span. The pane is the wall.
  pane.z_map = 0.8;
  EXPECT_LT(sgraph::detail::matchDistance2(node, 0, kf, pane, config), config.association_gate_mahalanobis2);
  // Where the support stands (the plane's wall span) and its heights' middle: the window.
  pane.span_middle_map = Eigen::Vector2d(2.8, -0.03), pane.span_m = 4.6;
  pane.z_map = 1.25;
  EXPECT_TRUE(std::isinf(sgraph::detail::matchDistance2(node, 0, kf, pane, config)));
  // The same support where the face is solid is the wall.
  node.openings[0].clear();
  EXPECT_LT(sgraph::detail::matchDistance2(node, 0, kf, pane, config), config.association_gate_mahalanobis2);
}

TEST(FaceOpenings, ARectangleIsInsideTheHolesWhereOpeningsSideBySideCoverIt) {
  // A window (along 1.3-4.3, z 0.5-2.5) and a door beside it (4.4-5.3, z 0-2.5): 0.1 m of wall
  // between them, less than twice the margin.
  const std::vector<bim::FaceOpening> openings{{1.3, 4.3, 0.5, 2.5}, {4.4, 5.3, 0.0, 2.5}};
  EXPECT_TRUE(bim::insideOpening(openings, 1.4, 4.2, 0.6, 2.4, 0.0));   // in the window
  EXPECT_TRUE(bim::insideOpening(openings, 1.4, 5.2, 0.6, 2.4, 0.15));  // across both: one hole
  EXPECT_FALSE(bim::insideOpening(openings, 1.4, 5.2, 0.6, 2.4, 0.0));  // the 0.1 m of wall between, no margin
  EXPECT_FALSE(bim::insideOpening(openings, 1.4, 5.2, 0.1, 2.4, 0.15));  // below the window's sill
  EXPECT_TRUE(bim::insideOpening(openings, 4.5, 5.2, 0.1, 2.4, 0.15));   // the door alone goes down to the floor
  EXPECT_FALSE(bim::insideOpening(openings, 0.0, 5.2, 0.6, 2.4, 0.15));  // past the window's end
  EXPECT_FALSE(bim::insideOpening({}, 1.4, 1.5, 0.6, 0.7, 0.15));
  EXPECT_FALSE(bim::insideOpening(openings, 0.0, 1e12, 0.6, 2.4, 0.15));  // wider than every hole: at once
  EXPECT_FALSE(bim::insideOpening(openings, 2.0, std::nan(""), 0.6, 2.4, 0.15));
}
