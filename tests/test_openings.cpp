// Openings cut from the bodies rebuilt from their extrusions: a synthetic wall against analytic
// geometry, and ExampleHOM's doors (IFC++'s own door meshes as the truth) against Embree rays
// and the base's planner.
#include "test_support.hpp"

#include "bim/extraction.hpp"
#include "bim/ifc_file.hpp"
#include "bim/ifc_geometry.hpp"
#include "bim/openings.hpp"
#include "sim/base/base_trajectory.hpp"
#include "sim/runner/room_scenarios.hpp"
#include "sim/world/mesh_io.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>

using namespace bimloc;
using bim::detail::Extrusion;

namespace {

// A prism as ProfileReader gives it: the profile's corners at the base, then moved by `dir`.
Extrusion prism(const std::vector<Eigen::Vector3d>& profile, const Eigen::Vector3d& dir) {
  Extrusion e;
  e.z_min = std::numeric_limits<double>::infinity();
  e.z_max = -e.z_min;
  for (const auto& p : profile) {
    e.footprint.emplace_back(p.x(), p.y());
    e.corners.push_back(p);
    e.corners.push_back(p + dir);
    e.z_min = std::min({e.z_min, p.z(), (p + dir).z()});
    e.z_max = std::max({e.z_max, p.z(), (p + dir).z()});
  }
  e.vertical = std::abs(dir.normalized().z()) > 0.999;
  return e;
}

// A wall at an angle: origin s, unit direction u along its length, left = u turned by +90 deg.
struct WallFrame {
  Eigen::Vector3d s{1.0, 2.0, 1.0};
  Eigen::Vector3d u = Eigen::Vector3d(std::cos(0.5), std::sin(0.5), 0.0);
  Eigen::Vector3d left = Eigen::Vector3d(-std::sin(0.5), std::cos(0.5), 0.0);
  double length = 5.0, thickness = 0.3, height = 2.8;
  Eigen::Vector3d at(double along, double across, double up) const {
    return s + along * u + across * left + up * Eigen::Vector3d::UnitZ();
  }
  Extrusion body() const {
    return prism({at(0, 0, 0), at(length, 0, 0), at(length, thickness, 0), at(0, thickness, 0)},
                 height * Eigen::Vector3d::UnitZ());
  }
  // An opening [a0, a1] x [z0, z1] in the wall's plane, extruded across it from `b0` over `depth`.
  Extrusion opening(double a0, double a1, double z0, double z1, double b0 = -0.1, double depth = 0.5) const {
    return prism({at(a0, b0, z0), at(a1, b0, z0), at(a1, b0, z1), at(a0, b0, z1)}, depth * left);
  }
};

struct Rect {
  double a0, a1, z0, z1;
  bool contains(double a, double z, double margin) const {
    return a > a0 - margin && a < a1 + margin && z > z0 - margin && z < z1 + margin;
  }
};

std::string writeTemp(const bim::TriangleMesh& mesh) {
  const std::string path = test::tempDir("openings") + "/wall.ply";
  sim::writeMesh(mesh, path);
  return path;
}

double meshArea(const bim::TriangleMesh& m) {
  double area = 0.0;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d a = m.vertices[t[0]].cast<double>(), b = m.vertices[t[1]].cast<double>(),
                          c = m.vertices[t[2]].cast<double>();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

// Closed and consistently oriented: every directed edge has its reverse exactly once.
void expectClosed(const bim::TriangleMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << "open edge " << e.first << "-" << e.second;
  }
}

}  // namespace

TEST(Openings, BoxWallWithBoxOpeningsHasExactlyTheirHoles) {
  const WallFrame w;
  const Rect door{1.0, 1.9, 0.0, 2.1}, window{3.0, 4.2, 0.9, 2.2};
  const auto cut = bim::detail::cutOpenings(
      w.body(), {w.opening(door.a0, door.a1, door.z0 - 0.2, door.z1), w.opening(window.a0, window.a1, window.z0, window.z1)});
  EXPECT_EQ(cut.cut, 2u);
  EXPECT_TRUE(cut.not_cut.empty());
  expectClosed(cut.mesh);
  // Area: the box, less both holes on both faces and the door's gap in the bottom face, plus
  // the reveals (perimeter x thickness; the door has none at the bottom).
  const double box = 2 * (w.length * w.thickness + w.length * w.height + w.thickness * w.height);
  const double holes = 2 * (door.a1 - door.a0) * (door.z1 - door.z0) + 2 * (window.a1 - window.a0) * (window.z1 - window.z0) +
                       w.thickness * (door.a1 - door.a0);
  const double reveals = w.thickness * ((door.a1 - door.a0) + 2 * (door.z1 - door.z0)) +
                         w.thickness * 2 * ((window.a1 - window.a0) + (window.z1 - window.z0));
  EXPECT_NEAR(meshArea(cut.mesh), box - holes + reveals, 1e-4);

  const sim::World world = sim::World::fromMesh(writeTemp(cut.mesh));
  // Rays across the wall on a grid over its face: through inside a hole, onto the face (1 m
  // away) elsewhere. Points within 1 cm of a hole's edge are left out (grazing rays).
  int through = 0, hits = 0;
  for (int ia = 1; ia < 100; ++ia)
    for (int iz = 1; iz < 56; ++iz) {
      const double a = 0.05 * ia, z = 0.05 * iz;
      const bool in_hole = door.contains(a, z, -0.01) || window.contains(a, z, -0.01);
      if (!in_hole && (door.contains(a, z, 0.01) || window.contains(a, z, 0.01))) continue;
      for (const double side : {-1.0, 1.0}) {
        const double b = side < 0 ? -1.0 : w.thickness + 1.0;
        const Eigen::Vector3f origin = w.at(a, b, z).cast<float>(), dir = (-side * w.left).cast<float>();
        const sim::RayHit hit = world.castRay(0, origin, dir, 0.0f, 3.0f);
        if (in_hole) {
          EXPECT_FALSE(hit.hit()) << "a " << a << " z " << z;
          ++through;
        } else {
          ASSERT_TRUE(hit.hit()) << "a " << a << " z " << z;
          EXPECT_NEAR(hit.range_m, 1.0, 1e-4);
          ++hits;
        }
      }
    }
  EXPECT_GT(through, 500);
  EXPECT_GT(hits, 5000);
  // The reveals: from the middle of each hole along the wall, and up to the lintel.
  const auto range = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& dir) {
    return world.castRay(0, from.cast<float>(), dir.cast<float>(), 0.0f, 10.0f).range_m;
  };
  const double mid_b = 0.5 * w.thickness;
  EXPECT_NEAR(range(w.at(1.45, mid_b, 1.0), w.u), 0.45, 1e-4);
  EXPECT_NEAR(range(w.at(1.45, mid_b, 1.0), -w.u), 0.45, 1e-4);
  EXPECT_NEAR(range(w.at(1.45, mid_b, 1.0), Eigen::Vector3d::UnitZ()), 1.1, 1e-4);
  EXPECT_NEAR(range(w.at(3.6, mid_b, 1.5), Eigen::Vector3d::UnitZ()), 0.7, 1e-4);
  EXPECT_NEAR(range(w.at(3.6, mid_b, 1.5), -Eigen::Vector3d::UnitZ()), 0.6, 1e-4);
}

TEST(Openings, ANicheLeavesTheWallClosedBehindIt) {
  const WallFrame w;
  // 10 cm deep from the left face (b in [0, 0.1]), entered from outside the wall.
  const auto cut = bim::detail::cutOpenings(w.body(), {w.opening(2.0, 3.0, 1.0, 2.0, -0.2, 0.3)});
  ASSERT_EQ(cut.cut, 1u);
  expectClosed(cut.mesh);
  const sim::World world = sim::World::fromMesh(writeTemp(cut.mesh));
  const auto hit = world.castRay(0, w.at(2.5, -1.0, 1.5).cast<float>(), w.left.cast<float>(), 0.0f, 3.0f);
  ASSERT_TRUE(hit.hit());
  EXPECT_NEAR(hit.range_m, 1.1, 1e-4);
}

TEST(Openings, OpeningsThatAreNotBoxesAlongTheWallAreReportedAndTheWallStaysWhole) {
  const WallFrame w;
  Extrusion turned = w.opening(2.0, 3.0, 0.0, 2.0);
  const Eigen::AngleAxisd turn(0.3, Eigen::Vector3d::UnitZ());
  for (auto& c : turned.corners) c = w.at(2.5, 0.15, 0) + turn * (c - w.at(2.5, 0.15, 0));
  Extrusion triangle = w.opening(2.0, 3.0, 0.0, 2.0);
  triangle.corners.resize(6);  // a three-point profile
  const Extrusion away = w.opening(7.0, 8.0, 0.0, 2.0);  // beyond the wall's end
  const auto cut = bim::detail::cutOpenings(w.body(), {turned, triangle, away});
  EXPECT_EQ(cut.cut, 0u);
  ASSERT_EQ(cut.not_cut.size(), 3u);
  EXPECT_NE(cut.not_cut[0].second.find("not a box along"), std::string::npos) << cut.not_cut[0].second;
  EXPECT_NE(cut.not_cut[1].second.find("3 points"), std::string::npos) << cut.not_cut[1].second;
  EXPECT_NE(cut.not_cut[2].second.find("does not meet"), std::string::npos) << cut.not_cut[2].second;
  const auto whole = bim::detail::prismMesh(w.body());
  EXPECT_EQ(cut.mesh.triangles, whole.triangles);

  // A body that is not a box (an L-shaped footprint) keeps its prism: each opening is named.
  const Extrusion l_shape = prism({w.at(0, 0, 0), w.at(5, 0, 0), w.at(5, 1, 0), w.at(4, 1, 0), w.at(4, 0.3, 0), w.at(0, 0.3, 0)},
                                  w.height * Eigen::Vector3d::UnitZ());
  const auto kept = bim::detail::cutOpenings(l_shape, {w.opening(1.0, 2.0, 0.0, 2.0)});
  ASSERT_EQ(kept.not_cut.size(), 1u);
  EXPECT_NE(kept.not_cut[0].second.find("not a box"), std::string::npos);
}

namespace {

struct Door {
  std::string name;
  Eigen::Vector3d lo, hi;  // bounding box of IFC++'s mesh of the door
};

// ExampleHOM's doors as IFC++ meshes them (their tessellated bodies): a reading of the plan
// that shares nothing with the openings we cut.
std::vector<Door> doorsOf(const std::string& plan) {
  const auto raw = bim::detail::readRawModel(bim::detail::readPlanText(plan), plan);
  std::vector<Door> doors;
  for (const auto& p : raw.elements) {
    if (p.ifc_class != "IfcDoor" || p.mesh.empty()) continue;
    Door d{p.name, p.mesh.vertices[0].cast<double>(), p.mesh.vertices[0].cast<double>()};
    for (const auto& v : p.mesh.vertices) d.lo = d.lo.cwiseMin(v.cast<double>()), d.hi = d.hi.cwiseMax(v.cast<double>());
    doors.push_back(d);
  }
  return doors;
}

const sim::World& exampleHom(const std::string& plan) {
  static const sim::World world = sim::World::fromPlan(plan);
  return world;
}

std::size_t storeyAt(const bim::Building& b, double z) {
  std::size_t s = 0;
  for (std::size_t i = 0; i < b.storeys.size(); ++i)
    if (b.storeys[i].elevation_m <= z + 0.1) s = i;
  return s;
}

}  // namespace

TEST(Openings, ExampleHomDoorsAreFreePassagesInTheStoreyMeshes) {
  BIMLOC_REQUIRE_SHARED(plan, "ExampleHOM.ifc");
  const auto doors = doorsOf(plan);
  ASSERT_EQ(doors.size(), 11u);
  const sim::World& world = exampleHom(plan);
  int beside = 0;
  for (const auto& d : doors) {
    const Eigen::Vector3d size = d.hi - d.lo, centre = 0.5 * (d.lo + d.hi);
    // Across the wall: the door's thin horizontal side; along it: its width.
    const bool across_x = size.x() < size.y();
    const Eigen::Vector3d n = across_x ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d t = across_x ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    const double width = size.dot(t), depth = size.dot(n);
    ASSERT_LT(depth, 0.5) << d.name;
    ASSERT_GT(width, 0.7) << d.name;
    const std::size_t storey = storeyAt(world.building(), d.lo.z());
    const double z = d.lo.z() + 1.0;
    const auto cast = [&](const Eigen::Vector3d& at) {
      const Eigen::Vector3d from(at.x(), at.y(), z);
      return world.castRay(storey, (from - 0.6 * n).cast<float>(), n.cast<float>(), 0.0f, 1.2f);
    };
    // Through the doorway, at its centre and 10 cm inside each jamb.
    for (const double along : {0.0, -0.5 * width + 0.1, 0.5 * width - 0.1})
      EXPECT_FALSE(cast(centre + along * t).hit()) << d.name << " is closed at " << along << " m from its centre";

    // Beside each edge: the wall, 0.5 m from the edge, or halfway to the end of the wall (its
    // profile's box) or to the next door in it where those come closer.
    const bim::Wall* host = nullptr;
    for (const auto& w : world.building().storeys[storey].walls) {
      const Eigen::Vector3d axis = (w.end - w.start).normalized();
      const Eigen::Vector3d rel = Eigen::Vector3d(centre.x(), centre.y(), w.start.z()) - w.start;
      if (std::abs(axis.dot(t)) > 0.99 && std::abs(rel.dot(n)) < 0.5 * w.thickness_m && rel.dot(axis) > 0 &&
          rel.dot(axis) < w.length_m())
        host = &w;
    }
    ASSERT_NE(host, nullptr) << d.name << ": in no wall";
    for (const double side : {-1.0, 1.0}) {
      const double edge = side * centre.dot(t) + 0.5 * width;  // coordinates along side * t
      double free = std::max(side * host->start.dot(t), side * host->end.dot(t)) - edge;
      for (const auto& e : doors) {
        const Eigen::Vector3d c = 0.5 * (e.lo + e.hi);
        const double near = std::min(side * e.lo.dot(t), side * e.hi.dot(t));
        if (&e != &d && std::abs((c - centre).dot(n)) < 0.05 && std::abs(c.z() - centre.z()) < 0.5 && near > edge)
          free = std::min(free, near - edge);
      }
      ASSERT_GT(free, 0.1) << d.name;
      const double offset = std::min(0.5, 0.5 * free);
      EXPECT_TRUE(cast(centre + side * (0.5 * width + offset) * t).hit())
          << d.name << ": no wall " << offset << " m beside its edge";
      beside += offset == 0.5;
    }
  }
  EXPECT_GE(beside, 13);  // 13 of the 22 sides at the full 0.5 m
}

TEST(Openings, ExampleHomBasePlansATourOutOfEveryRoom) {
  BIMLOC_REQUIRE_SHARED(plan, "ExampleHOM.ifc");
  const sim::World& world = exampleHom(plan);
  int tours = 0;
  for (const std::string storey : {"GroundFloor", "1stFloor"}) {
    sim::RoomScenarioOptions options;
    options.plan = plan;
    options.storey = storey;
    const auto& rooms = world.building().storeys[world.storeyIndex(storey)].rooms;
    ASSERT_EQ(rooms.size(), 5u);
    for (const auto& scenario : sim::roomScenarios(world, options)) {
      // A tour through every other room of the storey, none of them skipped.
      sim::MotionConfig motion = scenario.motion;
      motion.kind = sim::MotionConfig::Kind::Tour;
      motion.skip_unreachable_rooms = false;
      motion.rooms.clear();
      for (const auto& r : rooms)
        if (r.name != scenario.start.room) motion.rooms.push_back(r.name);
      const sim::Pose2 start = sim::startPose(scenario, world);
      EXPECT_NO_THROW(sim::BaseTrajectory::plan(world, world.storeyIndex(storey), start, motion, 600.0, 1))
          << storey << ": " << scenario.start.room;
      ++tours;
    }
  }
  EXPECT_EQ(tours, 10);
}

TEST(Openings, ExampleHomOpeningsAreAllCutAndTheWallsKeepTheirFaces) {
  BIMLOC_REQUIRE_SHARED(plan, "ExampleHOM.ifc");
  const auto raw = bim::detail::readRawModel(bim::detail::readPlanText(plan), plan);
  std::vector<std::string> warnings;
  const auto bodies = bim::detail::rebuiltBodies(raw, warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_EQ(raw.openings.size(), 24u);  // all of them void rebuilt walls
  // The walls keep the faces of their profiles, and the cut bodies fit the same boxes.
  const auto& storeys = exampleHom(plan).building().storeys;
  int walls = 0;
  for (const auto& p : raw.walls) {
    if (!p.mesh.empty()) continue;
    auto cut = p;
    cut.mesh = bodies.at(p.entity_id);
    std::string problem;
    const auto fitted = bim::detail::wallFromGeometry(cut, problem);
    ASSERT_TRUE(fitted) << problem;
    for (const auto& s : storeys)
      for (const auto& wall : s.walls) {
        if (wall.id != p.global_id) continue;
        ++walls;
        EXPECT_EQ(wall.source, "profile");
        for (int f = 0; f < 2; ++f) {
          EXPECT_LT((wall.faces[f].plane.n - fitted->faces[f].plane.n).norm(), 1e-6) << p.name;
          EXPECT_NEAR(wall.faces[f].plane.d, fitted->faces[f].plane.d, 1e-5) << p.name;
        }
      }
  }
  EXPECT_EQ(walls, 16);
}

// The elements whose openings IFC++ was not asked to cut (own_opening_cuts.hpp) are cut by
// rebuiltBodies; should one not cut as read, the storey mesh has it whole and the reader says so.
TEST(Openings, AnElementLeftToUsWhoseOpeningsDoNotCutIsNamed) {
  const WallFrame w;
  bim::detail::RawModel raw;
  bim::detail::RawProduct wall;
  wall.entity_id = 7, wall.global_id = "3vB2YO$MX4xv5uCqZZG05x", wall.name = "W", wall.ifc_class = "IfcWall";
  wall.mesh = bim::detail::prismMesh(w.body());
  wall.sole_body = w.body();
  raw.walls.push_back(wall);
  raw.openings_left_to_us = {7};
  bim::detail::RawOpening door;
  door.voided_entity_id = 7, door.extrusion = w.opening(1.0, 1.9, 0.0, 2.1), door.sole = true;
  raw.openings.push_back(door);
  std::vector<std::string> warnings;
  auto bodies = bim::detail::rebuiltBodies(raw, warnings);
  EXPECT_EQ(bodies.count(7), 1u);  // cut, unsaid
  EXPECT_TRUE(warnings.empty());

  // The same door turned 0.3 rad off the wall: not a box along it, not cut.
  for (auto& c : raw.openings[0].extrusion->corners) c = w.at(1.45, 0.15, 0) + Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * (c - w.at(1.45, 0.15, 0));
  bodies = bim::detail::rebuiltBodies(raw, warnings);
  EXPECT_EQ(bodies.count(7), 0u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("IfcWall #7 3vB2YO$MX4xv5uCqZZG05x 'W': its openings are not cut from the storey mesh"), std::string::npos)
      << warnings[0];
  // Not left to us: IFC++ cut it, its mesh is kept, nothing to say.
  raw.openings_left_to_us.clear(), warnings.clear();
  bodies = bim::detail::rebuiltBodies(raw, warnings);
  EXPECT_EQ(bodies.count(7), 0u);
  EXPECT_TRUE(warnings.empty());
}
