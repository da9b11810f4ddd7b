// Site people and sensor effects: a person occludes exactly the rays that cross its cylinder
// where it is at their firing's instant (independent truth: the ray's closest approach to the
// cylinder's axis, by the test's own geometry); a person's path is walked at its speed there
// and back; dark surfaces lose their stated fraction of the returns (binomial bound); mixed
// points lie between the two surfaces of an edge and come at their stated rate.
#include "sim/lidar/vlp16.hpp"
#include "sim/world/site_people.hpp"
#include "sim/world/world.hpp"
#include "sim_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace bimloc::sim {
namespace {

// The scan's returns by (cycle, laser); ranges recovered from the points.
std::map<std::pair<int, int>, float> returnsOf(const LidarScan& scan) {
  std::map<int, int> laser_of_ring;
  for (int k = 0; k < kVlp16Lasers; ++k) laser_of_ring[vlp16Ring(k)] = k;
  std::map<std::pair<int, int>, float> out;
  for (const auto& p : scan.points) {
    const int k = laser_of_ring.at(p.ring);
    const int c = static_cast<int>(std::lround((p.time - k * kVlp16FiringPeriod_s) / kVlp16CyclePeriod_s));
    const Eigen::Vector3f v = Eigen::Vector3f(p.x, p.y, p.z) - Eigen::Vector3f(0, 0, float(vlp16VerticalOffsetM(k)));
    out[{c, k}] = v.norm();
  }
  return out;
}

Vlp16Config exactLidar() {
  Vlp16Config c;
  c.range_noise_sigma_m = 0.0;  // ranges as cast
  return c;
}

const bim::Room& room101() {
  const bim::Room* r = test::officeWorld().building().storeys[0].findRoom("R101");
  EXPECT_NE(r, nullptr);
  return *r;
}

TEST(SitePeople, APersonWalksItsPathThereAndBack) {
  PersonTruth p;
  p.waypoints = {{0, 0}, {3, 0}, {3, 4}};  // 7 m
  p.speed_mps = 1.0;
  EXPECT_TRUE(personCentreAt(p, 0.0).isApprox(Eigen::Vector2d(0, 0)));
  EXPECT_TRUE(personCentreAt(p, 2.0).isApprox(Eigen::Vector2d(2, 0)));
  EXPECT_TRUE(personCentreAt(p, 5.0).isApprox(Eigen::Vector2d(3, 2)));
  EXPECT_TRUE(personCentreAt(p, 7.0).isApprox(Eigen::Vector2d(3, 4)));
  EXPECT_TRUE(personCentreAt(p, 9.0).isApprox(Eigen::Vector2d(3, 2))) << "on the way back";
  EXPECT_TRUE(personCentreAt(p, 13.0).isApprox(Eigen::Vector2d(1, 0)));
  EXPECT_TRUE(personCentreAt(p, 14.0 + 2.0).isApprox(Eigen::Vector2d(2, 0))) << "a loop takes 14 s";
  p.phase_m = 3.0;
  EXPECT_TRUE(personCentreAt(p, 1.0).isApprox(Eigen::Vector2d(3, 1)));
}

TEST(SitePeople, APersonOccludesExactlyTheRaysThatCrossItsCylinderAtThatTime) {
  const World& plan = test::officeWorld();
  const bim::Room& room = room101();
  // The robot at the room's centre; a person walking across in front of it, 1.2 m off.
  SiteConfig config;
  config.preset = "test";
  PersonPath path;
  path.waypoints = {room.centre + Eigen::Vector2d(-1.0, 1.2), room.centre + Eigen::Vector2d(1.0, 1.2)};
  path.speed_mps = 1.5;
  config.people.paths = {path};
  ASSERT_EQ(personPathProblem(plan, 0, path, config.people.radius_m), "") << "the test's path is clear";
  const World site = plan.withSite(config, 3);
  ASSERT_EQ(site.siteTruth().people.size(), 1u);
  const PersonTruth& person = site.siteTruth().people[0];

  int crossing = 0, clear = 0;
  const Vlp16 lidar(exactLidar());
  // Level, and tilted by 8 deg (a walking robot rolls and pitches: the lasers' fans lean).
  for (const double roll : {0.0, 0.14}) {
    const Eigen::Isometry3d T = test::pose(room.centre.x(), room.centre.y(), 0.3, room.floor_z + 0.5) *
                                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
    const auto base = [&](double) { return T; };
    const double t0 = 0.4 + roll;
    RayRecord rays;
    const auto before = returnsOf(lidar.scan(plan, 0, base, t0, 7, 2));
    const auto after = returnsOf(lidar.scan(site, 0, base, t0, 7, 2, &rays));
    const float r = float(person.radius_m), z0 = float(person.floor_z), z1 = float(person.floor_z + person.height_m);
    for (std::size_t i = 0; i < rays.origins.size(); ++i) {
      const int c = int(i) / kVlp16Lasers, k = int(i) % kVlp16Lasers;
      const auto b = before.find({c, k});
      if (b == before.end()) continue;
      const Eigen::Vector3d o = rays.origins[i].cast<double>(), d = rays.directions[i].cast<double>();
      // Positions are updated per firing block of 16 cycles, at its first cycle's instant.
      const Eigen::Vector2d centre = personCentreAt(person, t0 + (c / 16) * 16 * kVlp16CyclePeriod_s);
      // Closest approach of the ray's horizontal projection to the axis; the entry is the
      // chord's near end, half a chord before it.
      const Eigen::Vector2d dh = d.head<2>(), w = centre - o.head<2>();
      const double a = dh.squaredNorm(), t_close = w.dot(dh) / a, miss = (o.head<2>() + t_close * dh - centre).norm();
      const double half = miss < r ? std::sqrt((r * r - miss * miss) / a) : 0.0, t_entry = t_close - half;
      const double z_entry = o.z() + t_entry * d.z();
      const bool crosses = miss < r - 2e-3 && t_entry > 0.05 && z_entry > z0 + 2e-3 && z_entry < z1 - 2e-3 &&
                           t_entry < b->second - 2e-3;
      const bool misses = miss > r + 2e-3 || t_entry > b->second + 2e-3;
      const auto a_it = after.find({c, k});
      if (crosses) {
        ++crossing;
        ASSERT_NE(a_it, after.end());
        EXPECT_NEAR(a_it->second, t_entry, 2e-4) << "cycle " << c << " laser " << k;
      } else if (misses) {
        ++clear;
        ASSERT_NE(a_it, after.end());
        EXPECT_EQ(a_it->second, b->second) << "a ray past the person changed, cycle " << c << " laser " << k;
      }
    }
  }
  EXPECT_GT(crossing, 400) << "the person is in view";
  EXPECT_GT(clear, 40000);
}

TEST(SitePeople, PresetsHavePeopleInTheirRoomsClearOfTheWalls) {
  const World& plan = test::officeWorld();
  const World construction = plan.withSite(sitePreset("construction"), 5);
  const World heavy = plan.withSite(sitePreset("heavy"), 5);
  EXPECT_EQ(construction.siteTruth().people.size(), 2u * plan.storeyCount());
  EXPECT_GT(heavy.siteTruth().people.size(), construction.siteTruth().people.size());
  for (const PersonTruth& p : heavy.siteTruth().people) {
    const bim::Room* room = plan.building().storeys[p.storey].findRoom(p.room);
    ASSERT_NE(room, nullptr);
    PersonPath path;
    path.waypoints = p.waypoints;
    EXPECT_EQ(personPathProblem(heavy, p.storey, path, p.radius_m), "");
  }
}

// A site whose every surface is dark: each return is lost with the stated probability.
TEST(SiteSensor, DarkSurfacesLoseTheirFractionOfTheReturns) {
  const World& plan = test::officeWorld();
  SiteConfig config;
  config.preset = "test";
  config.sensor.dark_fraction = 1.0;
  config.sensor.dark_dropout = 0.3;
  const World site = plan.withSite(config, 2);
  const Vlp16 lidar(exactLidar());
  const bim::Room& room = room101();
  const auto base = [&](double) { return test::pose(room.centre.x(), room.centre.y(), 0.0, room.floor_z + 0.5); };
  std::size_t n = 0, kept = 0;
  for (int turn = 0; turn < 3; ++turn) {
    const auto before = returnsOf(lidar.scan(plan, 0, base, 0.1 * turn, 1, turn));
    const auto after = returnsOf(lidar.scan(site, 0, base, 0.1 * turn, 1, turn));
    n += before.size();
    for (const auto& [key, range] : after) {
      ASSERT_TRUE(before.count(key));
      EXPECT_EQ(range, before.at(key)) << "a kept return keeps its range";
      ++kept;
    }
  }
  const double p_keep = 0.7, sd = std::sqrt(n * p_keep * (1 - p_keep));
  EXPECT_NEAR(double(kept), n * p_keep, 5 * sd) << kept << " of " << n;
}

TEST(SiteSensor, MixedPointsLieBetweenTheTwoSurfacesOfAnEdge) {
  const World& plan = test::officeWorld();
  SiteConfig config;
  config.preset = "test";
  config.sensor.mixed_probability = 0.4;
  config.sensor.mixed_jump_m = 0.3;
  const World site = plan.withSite(config, 2);
  const Vlp16 lidar(exactLidar());
  const bim::Room& room = room101();
  // Several spots of the room and the corridor: door jambs, wall ends and far walls.
  const bim::Room* corridor = plan.building().storeys[0].findRoom("C100");
  ASSERT_NE(corridor, nullptr);
  int edges = 0, mixed = 0;
  for (int turn = 0; turn < 4; ++turn) {
    const Eigen::Vector2d at = turn < 2 ? room.centre + Eigen::Vector2d(0.5 * turn, 0) : Eigen::Vector2d(4.0 * turn, 6.1);
    const auto base = [&](double) { return test::pose(at.x(), at.y(), 0.0, room.floor_z + 0.5); };
    const auto before = returnsOf(lidar.scan(plan, 0, base, 0.1 * turn, 1, turn));
    const auto after = returnsOf(lidar.scan(site, 0, base, 0.1 * turn, 1, turn));
    ASSERT_EQ(before.size(), after.size()) << "mixed points are moved, never lost";
    for (const auto& [key, r] : before) {
      const auto prev = before.find({key.first - 1, key.second});
      const float got = after.at(key);
      if (prev == before.end() || std::abs(r - prev->second) <= 0.3f) {
        EXPECT_EQ(got, r) << "no edge, no mixing";
        continue;
      }
      ++edges;
      EXPECT_GE(got, std::min(r, prev->second) - 1e-4f);
      EXPECT_LE(got, std::max(r, prev->second) + 1e-4f);
      mixed += got != r;
    }
  }
  ASSERT_GT(edges, 50) << "the room's view has depth edges";
  const double sd = std::sqrt(edges * 0.4 * 0.6);
  EXPECT_NEAR(mixed, edges * 0.4, 5 * sd + 1);
}

}  // namespace
}  // namespace bimloc::sim
