// Stair flights from their bodies (localizer/src/bim/stairs.cpp), on stairs built in code whose
// numbers are known by construction: a straight flight of boxes, turned, raised, with and without
// its top floor in the body; a winding one; bodies that are no stair.
#include "bim/stairs.hpp"

#include <bimloc/bim/building_json.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

using namespace bimloc::bim;
using namespace bimloc::bim::detail;

namespace {

// A closed box [x0,x1] x [y0,y1] x [z0,z1] with outward faces, moved by `pose` (a turn about z
// and a shift).
void addBox(TriangleMesh& mesh, double x0, double x1, double y0, double y1, double z0, double z1,
            const Eigen::Isometry3d& pose) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d p((i & 1) ? x1 : x0, (i & 2) ? y1 : y0, (i & 4) ? z1 : z0);
    mesh.vertices.push_back((pose * p).cast<float>());
  }
  // Corners by bits (x, y, z); each face counter-clockwise seen from outside.
  const std::array<std::array<std::uint32_t, 4>, 6> quads{{{0, 2, 3, 1},  // bottom (z0), looking down
                                                           {4, 5, 7, 6},  // top (z1), looking up
                                                           {0, 1, 5, 4},  // y0
                                                           {2, 6, 7, 3},  // y1
                                                           {0, 4, 6, 2},  // x0
                                                           {1, 3, 7, 5}}};
  for (const auto& q : quads) {
    mesh.triangles.push_back({base + q[0], base + q[1], base + q[2]});
    mesh.triangles.push_back({base + q[0], base + q[2], base + q[3]});
  }
}

struct StraightFlight {
  int risers = 16;
  double riser_m = 0.19375, going_m = 0.25, width_m = 1.0, floor_z = 0.0;
  bool top_floor_in_body = false;  // a last box level with the top floor, one going deep
};

// Steps as solid boxes rising along +x from x = 0 (the first riser), y in [0, width]: the k-th
// tread (k = 1 .. risers-1) is [(k-1) g, k g] at height k h. The last riser climbs to the top
// floor, which the body has only when top_floor_in_body.
TriangleMesh straightBody(const StraightFlight& f, const Eigen::Isometry3d& pose) {
  TriangleMesh mesh;
  const int boxes = f.top_floor_in_body ? f.risers : f.risers - 1;
  for (int k = 1; k <= boxes; ++k)
    addBox(mesh, (k - 1) * f.going_m, k * f.going_m, 0.0, f.width_m, f.floor_z, f.floor_z + k * f.riser_m, pose);
  return mesh;
}

Eigen::Isometry3d turnedAndShifted(double yaw_rad, const Eigen::Vector3d& shift) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
  pose.pretranslate(shift);
  return pose;
}

void expectFlight(const BodyFlight& got, const StraightFlight& f, const Eigen::Isometry3d& pose) {
  EXPECT_EQ(got.risers, f.risers);
  EXPECT_NEAR(got.riser_height_m, f.riser_m, 1e-4);
  EXPECT_NEAR(got.going_m, f.going_m, 1e-4);
  EXPECT_NEAR(got.width_m, f.width_m, 1e-4);
  // The run line: first riser to last riser, at mid width, on the floors' heights.
  const Eigen::Vector3d bottom = pose * Eigen::Vector3d(0.0, f.width_m / 2, f.floor_z);
  const Eigen::Vector3d top = pose * Eigen::Vector3d((f.risers - 1) * f.going_m, f.width_m / 2, f.floor_z + f.risers * f.riser_m);
  EXPECT_LT((got.bottom - bottom).norm(), 1e-4) << got.bottom.transpose() << " vs " << bottom.transpose();
  EXPECT_LT((got.top - top).norm(), 1e-4) << got.top.transpose() << " vs " << top.transpose();
}

}  // namespace

TEST(StairBody, StraightFlightGivesItsRunLineRiseAndGoing) {
  const StraightFlight f;
  const auto pose = turnedAndShifted(0.0, Eigen::Vector3d::Zero());
  std::string problem;
  const auto got = flightFromBody(straightBody(f, pose), {0.0, 3.1}, problem);
  ASSERT_TRUE(got) << problem;
  expectFlight(*got, f, pose);
}

TEST(StairBody, TurnedRaisedFlightWithItsTopFloorInTheBody) {
  StraightFlight f;
  f.risers = 7, f.riser_m = 0.18, f.going_m = 0.23, f.width_m = 0.9, f.floor_z = -1.26;
  f.top_floor_in_body = true;
  const auto pose = turnedAndShifted(2.3, Eigen::Vector3d(4.0, -7.5, 0.0));
  std::string problem;
  const auto got = flightFromBody(straightBody(f, pose), {-1.26, 0.0, 1.8}, problem);
  ASSERT_TRUE(got) << problem;
  expectFlight(*got, f, pose);
}

// Without a floor at either candidate height the size of the last face decides: a tread-sized
// one is the last tread (the floor a rise above it).
TEST(StairBody, NoFloorsKnownLastTreadSizedFaceIsATread) {
  const StraightFlight f;
  const auto pose = turnedAndShifted(-0.7, Eigen::Vector3d(1.0, 2.0, 0.0));
  std::string problem;
  const auto got = flightFromBody(straightBody(f, pose), {}, problem);
  ASSERT_TRUE(got) << problem;
  expectFlight(*got, f, pose);
}

// A winding stair of 12 wedge treads around a post: 12 risers of 0.2 m over 2.4 m, the going on
// the line through the treads' centres (the chord between two centroids).
TEST(StairBody, WindingStairCountsItsRisers) {
  TriangleMesh mesh;
  const int risers = 12;
  const double h = 0.2, r_in = 0.1, r_out = 1.0, step_rad = M_PI / 8;
  for (int k = 1; k < risers; ++k) {  // treads 1..11 as wedge prisms from the floor
    const double a0 = (k - 1) * step_rad, a1 = k * step_rad;
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (const double z : {0.0, k * h})
      for (const double a : {a0, a1})
        for (const double r : {r_in, r_out}) mesh.vertices.emplace_back(float(r * std::cos(a)), float(r * std::sin(a)), float(z));
    // 0..3 at the bottom (a0 in, a0 out, a1 in, a1 out), 4..7 on top; top face up, bottom down.
    for (const auto& t : std::vector<std::array<std::uint32_t, 3>>{{4, 5, 7}, {4, 7, 6}, {0, 3, 1}, {0, 2, 3},
                                                                  {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                                                  {1, 3, 7}, {1, 7, 5}, {0, 4, 6}, {0, 6, 2}})
      mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }
  std::string problem;
  const auto got = flightFromBody(mesh, {0.0, 2.4}, problem);
  ASSERT_TRUE(got) << problem;
  EXPECT_EQ(got->risers, risers);
  EXPECT_NEAR(got->riser_height_m, h, 1e-4);
  EXPECT_NEAR(got->bottom.z(), 0.0, 1e-6);
  EXPECT_NEAR(got->top.z(), 2.4, 1e-4);
  // Each tread's top is the quadrilateral of its four corners; their area centroids lie on one
  // circle, consecutive ones a chord of step_rad apart.
  std::vector<Eigen::Vector2d> quad{{r_in, 0.0}, {r_out, 0.0}, {r_out * std::cos(step_rad), r_out * std::sin(step_rad)},
                                    {r_in * std::cos(step_rad), r_in * std::sin(step_rad)}};
  double area = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < quad.size(); ++i) {
    const auto& a = quad[i];
    const auto& b = quad[(i + 1) % quad.size()];
    const double cross = a.x() * b.y() - b.x() * a.y();
    area += cross / 2;
    centroid += (a + b) * cross / 6;
  }
  centroid /= area;
  EXPECT_NEAR(got->going_m, 2 * centroid.norm() * std::sin(step_rad / 2), 1e-4);
}

TEST(StairBody, BodiesThatAreNoStairAreRefusedWithAReason) {
  std::string problem;
  EXPECT_FALSE(flightFromBody(TriangleMesh{}, {0.0}, problem));
  EXPECT_EQ(problem, "no body");
  TriangleMesh slab;
  addBox(slab, 0, 4, 0, 3, 0, 0.2, Eigen::Isometry3d::Identity());
  EXPECT_FALSE(flightFromBody(slab, {0.0}, problem));
  EXPECT_NE(problem.find("1 horizontal step face"), std::string::npos) << problem;
  TriangleMesh shelves;  // boxes 0.5 m apart in height: no stair's rise
  for (int k = 1; k <= 4; ++k) addBox(shelves, (k - 1) * 0.3, k * 0.3, 0, 1, 0, k * 0.5, Eigen::Isometry3d::Identity());
  EXPECT_FALSE(flightFromBody(shelves, {0.0}, problem));
  EXPECT_NE(problem.find("not a stair's rise"), std::string::npos) << problem;
}

// The attributes win where sane and in agreement with the body; Revit's feet in a metre file
// (RiserHeight 0.6357, TreadLength 0.8202 for 0.19375 m and 0.25 m) are ignored, with a warning.
TEST(StairBody, AttributesReplaceTheBodysNumbersOnlyWhenSane) {
  const StraightFlight f;
  const TriangleMesh body = straightBody(f, Eigen::Isometry3d::Identity());
  RawProduct p;
  p.ifc_class = "IfcStairFlight";
  p.global_id = "flight";
  p.flight = FlightAttributes{16, 15, 0.19375, 0.25};
  std::string problem;
  auto got = stairFlightOf(p, body, {0.0, 3.1}, problem);
  ASSERT_TRUE(got) << problem;
  EXPECT_EQ(got->source, "attributes");
  EXPECT_TRUE(problem.empty()) << problem;
  EXPECT_EQ(got->risers, 16);

  p.flight = FlightAttributes{16, 15, 0.6356627296588328, 0.8202099737532809};
  got = stairFlightOf(p, body, {0.0, 3.1}, problem);
  ASSERT_TRUE(got) << problem;
  EXPECT_EQ(got->source, "attributes+body");
  EXPECT_EQ(got->risers, 16);
  EXPECT_NEAR(got->riser_height_m, 0.19375, 1e-4);
  EXPECT_NEAR(got->going_m, 0.25, 1e-4);
  EXPECT_NE(problem.find("RiserHeight 0.635663 m"), std::string::npos) << problem;
  EXPECT_NE(problem.find("TreadLength 0.820210 m"), std::string::npos) << problem;

  p.flight = FlightAttributes{std::nullopt, std::nullopt, std::nullopt, std::nullopt};
  got = stairFlightOf(p, body, {0.0, 3.1}, problem);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->source, "body");

  got = stairFlightOf(p, TriangleMesh{}, {0.0, 3.1}, problem);
  EXPECT_FALSE(got);
  EXPECT_EQ(problem, "no usable body (no body)");
}

TEST(StairBody, StoreyAtFindsTheClosestElevationOrALanding) {
  std::vector<Storey> storeys(3);
  storeys[0].elevation_m = -1.26, storeys[1].elevation_m = 0.0, storeys[2].elevation_m = 0.1;
  EXPECT_EQ(storeyAt(-1.2, storeys), 0);
  EXPECT_EQ(storeyAt(0.07, storeys), 2);
  EXPECT_EQ(storeyAt(0.6, storeys), -1);
}

// building.json version 2 keeps the flights; a version 1 document still reads, with no stairs.
TEST(StairJson, FlightsRoundTripAndVersionOneStillReads) {
  Building b;
  b.storeys.resize(2);
  b.storeys[0].name = "ground", b.storeys[1].name = "first", b.storeys[1].elevation_m = 3.1;
  StairFlight f;
  f.id = "flight", f.name = "Stair", f.ifc_type = "IfcStairFlight", f.stair_id = "stair";
  f.bottom = {1, 2, 0}, f.top = {1, 5.75, 3.1};
  f.width_m = 0.9, f.risers = 16, f.riser_height_m = 0.19375, f.going_m = 0.25;
  f.bottom_storey = 0, f.top_storey = 1, f.source = "attributes+body";
  b.stairs.push_back(f);
  nlohmann::json doc = toJson(b);
  EXPECT_EQ(doc["version"], 2);
  EXPECT_DOUBLE_EQ(doc["stairs"][0]["rise_m"].get<double>(), 3.1);
  const Building back = buildingFromJson(doc);
  ASSERT_EQ(back.stairs.size(), 1u);
  const StairFlight& g = back.stairs[0];
  EXPECT_EQ(g.id, f.id);
  EXPECT_EQ(g.stair_id, f.stair_id);
  EXPECT_EQ(g.top, f.top);
  EXPECT_EQ(g.risers, 16);
  EXPECT_EQ(g.going_m, 0.25);
  EXPECT_EQ(g.top_storey, 1);
  EXPECT_EQ(g.source, f.source);

  doc["stairs"][0]["top_storey"] = 2;  // no such storey
  try {
    (void)buildingFromJson(doc);
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "stairs[0]: storey index 2 is not -1 or one of the 2 storeys");
  }
  doc.erase("stairs");
  doc["version"] = 1;
  EXPECT_TRUE(buildingFromJson(doc).stairs.empty());
  doc["version"] = 3;
  EXPECT_THROW((void)buildingFromJson(doc), std::runtime_error);
}

// A ramp built in code: a wedge rising 0.5 m over 6 m (1:12), 1.2 m wide, turned and shifted.
TEST(StairBody, RampGivesItsRunLineFromItsSlope) {
  const double run = 6.0, rise = 0.5, width = 1.2, floor_z = 3.1;
  const auto pose = turnedAndShifted(0.9, Eigen::Vector3d(2.0, 1.0, 0.0));
  TriangleMesh wedge;
  for (const auto& p : std::vector<Eigen::Vector3d>{{0, 0, floor_z}, {run, 0, floor_z}, {run, width, floor_z}, {0, width, floor_z},
                                                    {run, 0, floor_z + rise}, {run, width, floor_z + rise}})
    wedge.vertices.push_back((pose * p).cast<float>());
  // bottom (down), slope (up), high end (+x), two sides
  wedge.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 4, 5}, {0, 5, 3}, {1, 2, 5}, {1, 5, 4}, {0, 1, 4}, {3, 5, 2}};
  std::string problem;
  const auto got = rampFromBody(wedge, problem);
  ASSERT_TRUE(got) << problem;
  EXPECT_LT((got->bottom - pose * Eigen::Vector3d(0, width / 2, floor_z)).norm(), 1e-4) << got->bottom.transpose();
  EXPECT_LT((got->top - pose * Eigen::Vector3d(run, width / 2, floor_z + rise)).norm(), 1e-4) << got->top.transpose();
  EXPECT_NEAR(got->width_m, width, 1e-4);
  EXPECT_EQ(got->risers, 0);

  RawProduct p;
  p.ifc_class = "IfcRamp";
  const auto flight = stairFlightOf(p, wedge, {3.1}, problem);
  ASSERT_TRUE(flight) << problem;
  EXPECT_NEAR(flight->rise_m(), rise, 1e-4);
  EXPECT_NEAR(flight->run_m(), run, 1e-4);
  EXPECT_EQ(flight->source, "body");

  TriangleMesh box;  // flat: no walking slope
  addBox(box, 0, 4, 0, 1, 0, 0.2, Eigen::Isometry3d::Identity());
  EXPECT_FALSE(rampFromBody(box, problem));
  EXPECT_EQ(problem, "the body has no sloped walking surface (0.5° to 25°): no ramp");
}
