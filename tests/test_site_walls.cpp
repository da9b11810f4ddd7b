// Site worlds (sim/world/site_*.cpp) against truths worked out here from the plan alone: a
// shifted or turned wall moves the ray hits to where its moved face plane says, a missing wall
// lets the rays through, partitions stand where the truth says and clear of every wall, the
// same seed gives the same world bit for bit, and the exact site is the plan's world.
#include "sim/world/world.hpp"
#include "sim_fixtures.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace bimloc::sim {
namespace {

const bim::Storey& officeStorey() { return test::officeWorld().building().storeys[0]; }

// The office's first wall longer than 3 m with no door in its middle third on face 0's side
// (rays cast at that third from 1 m in front of face 0 must meet face 0 in the plan's world).
struct Probe {
  const bim::Wall* wall = nullptr;
  std::vector<Eigen::Vector3f> origins;
  Eigen::Vector3f dir;  // -n0
};

Probe probeWall() {
  const World& world = test::officeWorld();
  const double z = officeStorey().elevation_m + 1.0;
  for (const auto& w : officeStorey().walls) {
    if (w.length_m() < 3.0) continue;
    const bim::WallFace& f = w.faces[0];
    const Eigen::Vector3d n = f.plane.n;
    Probe p{&w, {}, (-n).cast<float>()};
    bool all = true;
    for (double t : {0.35, 0.45, 0.5, 0.55, 0.65}) {
      Eigen::Vector3d o = f.start + t * (f.end - f.start) + 1.0 * n;
      o.z() = z;
      const RayHit hit = world.castRay(0, o.cast<float>(), p.dir, 0.0f, 10.0f);
      all = all && hit.hit() && std::abs(hit.range_m - 1.0) < 1e-4;
      p.origins.push_back(o.cast<float>());
    }
    if (all) return p;
  }
  return {};
}

SiteConfig editOne(const std::string& id, std::optional<double> offset_m, std::optional<double> angle_deg, bool missing) {
  SiteConfig c;
  c.preset = "test";
  WallEdit e;
  e.id = id, e.offset_m = offset_m, e.angle_deg = angle_deg, e.missing = missing;
  c.walls.edits.push_back(e);
  return c;
}

TEST(SiteWalls, ShiftedWallMovesTheHitsByExactlyItsOffset) {
  const Probe p = probeWall();
  ASSERT_NE(p.wall, nullptr) << "no wall of the office to probe";
  for (const double offset : {0.1, -0.05, 0.023}) {
    const World site = test::officeWorld().withSite(editOne(p.wall->id, offset, std::nullopt, false), 7);
    const WallTruth* truth = site.siteTruth().findWall(p.wall->id);
    ASSERT_NE(truth, nullptr);
    EXPECT_EQ(truth->offset_m, offset);
    for (const auto& o : p.origins) {
      // Face 0 moves along its own normal, towards the origin 1 m in front of it.
      const RayHit hit = site.castRay(0, o, p.dir, 0.0f, 10.0f);
      ASSERT_TRUE(hit.hit());
      EXPECT_NEAR(hit.range_m, 1.0 - offset, 1e-4) << "offset " << offset;
    }
  }
}

TEST(SiteWalls, TurnedWallHitsItsTurnedFacePlane) {
  const Probe p = probeWall();
  ASSERT_NE(p.wall, nullptr);
  const double angle_deg = 2.0, offset = 0.04;
  const World site = test::officeWorld().withSite(editOne(p.wall->id, offset, angle_deg, false), 7);
  // The truth, worked out from the plan's face plane: turned about the axis midpoint, then shifted.
  const bim::Wall& w = *p.wall;
  const Eigen::Vector3d c(0.5 * (w.start.x() + w.end.x()), 0.5 * (w.start.y() + w.end.y()), 0.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d n = R * w.faces[0].plane.n;
  const Eigen::Vector3d q = c + R * (w.faces[0].start - c) + offset * w.faces[0].plane.n;
  int turned = 0;  // rays away from the centre line, where the turn shows
  for (const auto& o : p.origins) {
    const double expected = n.dot(q - o.cast<double>()) / n.dot(p.dir.cast<double>());
    const RayHit hit = site.castRay(0, o, p.dir, 0.0f, 10.0f);
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.range_m, expected, 2e-4);
    turned += std::abs(hit.range_m - (1.0 - offset)) > 1e-3;
  }
  EXPECT_EQ(turned, 4) << "the turn changed nothing";
}

TEST(SiteWalls, MissingWallLetsTheRaysThrough) {
  const Probe p = probeWall();
  ASSERT_NE(p.wall, nullptr);
  const World site = test::officeWorld().withSite(editOne(p.wall->name, std::nullopt, std::nullopt, true), 7);
  EXPECT_TRUE(site.siteTruth().findWall(p.wall->id)->missing);
  for (const auto& o : p.origins) {
    const RayHit hit = site.castRay(0, o, p.dir, 0.0f, 50.0f);
    // Past where both faces of the wall were.
    if (hit.hit()) {
      EXPECT_GT(hit.range_m, 1.0 + p.wall->thickness_m + 0.01);
    }
  }
  // Only the meshes differ: the plan (what the localizer gets) keeps the wall.
  EXPECT_NE(site.building().storeys[0].findWall(p.wall->id), nullptr);
}

TEST(SiteWalls, ExactSiteIsThePlansWorld) {
  const World& plan = test::officeWorld();
  const World site = plan.withSite(sitePreset("exact"), 3);
  for (std::size_t s = 0; s < plan.storeyCount(); ++s) {
    EXPECT_EQ(site.building().storeys[s].mesh.vertices, plan.building().storeys[s].mesh.vertices);
    EXPECT_EQ(site.building().storeys[s].mesh.triangles, plan.building().storeys[s].mesh.triangles);
  }
  for (const auto& w : site.siteTruth().walls) EXPECT_TRUE(w.offset_m == 0 && w.angle_deg == 0 && !w.missing);
}

TEST(SiteWalls, SameSeedSameWorldBitForBit) {
  const World& plan = test::officeWorld();
  const SiteConfig c = sitePreset("heavy");
  const World a = plan.withSite(c, 11), b = plan.withSite(c, 11), other = plan.withSite(c, 12);
  EXPECT_EQ(a.building().storeys[0].mesh.vertices, b.building().storeys[0].mesh.vertices);
  EXPECT_EQ(a.building().storeys[0].mesh.triangles, b.building().storeys[0].mesh.triangles);
  EXPECT_EQ(siteTruthJson(a.siteTruth()).dump(), siteTruthJson(b.siteTruth()).dump());
  EXPECT_NE(siteTruthJson(a.siteTruth()).dump(), siteTruthJson(other.siteTruth()).dump());
  EXPECT_NE(a.building().storeys[0].mesh.vertices, other.building().storeys[0].mesh.vertices);
  // Every wall drawn within the preset's bounds.
  std::size_t moved = 0;
  for (const auto& w : a.siteTruth().walls) {
    EXPECT_LE(std::abs(w.offset_m), c.walls.max_offset_m);
    EXPECT_LE(std::abs(w.angle_deg), c.walls.max_angle_deg);
    moved += w.offset_m != 0.0;
  }
  EXPECT_GT(moved, 0u);
}

TEST(SiteWalls, PartitionsStandWhereTheTruthSaysClearOfTheWalls) {
  SiteConfig c;
  c.preset = "test";
  c.walls.partitions_per_storey = 3;
  const World site = test::officeWorld().withSite(c, 5);
  const auto& parts = site.siteTruth().partitions;
  ASSERT_FALSE(parts.empty()) << (site.siteTruth().warnings.empty() ? "" : site.siteTruth().warnings.front());
  for (const auto& p : parts) {
    // Clear of every wall body by the clearance (distance between segments, sampled).
    for (const auto& w : officeStorey().walls)
      for (int k = 0; k <= 100; ++k) {
        const Eigen::Vector2d q = p.start + (p.end - p.start) * (k / 100.0);
        const Eigen::Vector2d a = w.start.head<2>(), b = w.end.head<2>();
        const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        EXPECT_GE((a + t * (b - a) - q).norm(), c.walls.partition_clearance_m + 0.5 * w.thickness_m);
      }
    // A ray across the partition's middle, 0.5 m from its centre line, meets its face.
    const Eigen::Vector2d mid = 0.5 * (p.start + p.end), u = (p.end - p.start).normalized(), n(-u.y(), u.x());
    const Eigen::Vector2d o2 = mid + 0.5 * n;
    const Eigen::Vector3f o(float(o2.x()), float(o2.y()), float(officeStorey().elevation_m + 1.0));
    const RayHit hit = site.castRay(0, o, Eigen::Vector3f(float(-n.x()), float(-n.y()), 0.0f), 0.0f, 5.0f);
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.range_m, 0.5 - 0.5 * p.thickness_m, 1e-4);
    EXPECT_FALSE(test::officeWorld().castRay(0, o, Eigen::Vector3f(float(-n.x()), float(-n.y()), 0.0f), 0.0f, 0.6f).hit());
  }
}

TEST(SiteWalls, EditNamingNoWallIsRefused) {
  EXPECT_THROW(test::officeWorld().withSite(editOne("no-such-wall", 0.1, std::nullopt, false), 1), std::invalid_argument);
}

// SampleHouse4's curtain walls are wall landmarks of the plan, but their bodies are their panels
// and mullions, which the world does not move as one: a site leaves them as drawn, and says so.
TEST(SiteWalls, CurtainWallsAreBuiltAsDrawnAndCannotBeEdited) {
  BIMLOC_REQUIRE_SHARED(path, "SampleHouse4.ifc");
  const World plan = World::fromPlan(path);
  SiteConfig every;
  every.preset = "test";
  every.walls.fraction = 1.0, every.walls.max_offset_m = 0.2, every.walls.max_angle_deg = 1.0;
  every.walls.missing_fraction = 0.5;
  const World site = plan.withSite(every, 3);
  int curtain = 0, moved = 0;
  for (const auto& storey : plan.building().storeys)
    for (const auto& w : storey.walls)
      for (const auto& t : site.siteTruth().walls) {
        if (t.id != w.id) continue;
        if (w.ifc_type == "IfcCurtainWall") {
          ++curtain;
          EXPECT_EQ(t.offset_m, 0.0) << w.id;
          EXPECT_EQ(t.angle_deg, 0.0) << w.id;
          EXPECT_FALSE(t.missing) << w.id;
        } else {
          moved += t.missing || t.offset_m != 0.0;
        }
      }
  EXPECT_EQ(curtain, 2);
  EXPECT_EQ(moved, 5);  // every other wall shifted or left out
  EXPECT_THROW(plan.withSite(editOne("3cUkl32yn9qRSPvBJVyW_P", 0.1, std::nullopt, false), 1), std::invalid_argument);
}

}  // namespace
}  // namespace bimloc::sim
