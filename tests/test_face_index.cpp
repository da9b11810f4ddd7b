// The face index against brute force: every face within the radius is visited once, and a
// match through the index is the match over every face (the same double, the same count).
#include "face_index_fixtures.hpp"
#include "sim_fixtures.hpp"

#include "pf/face_index.hpp"
#include "pf/hypotheses.hpp"
#include "pf/measurement.hpp"
#include "sim/lidar/vlp16_config.hpp"
#include "sim/world/world.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <set>

using namespace bimloc;
using namespace bimloc::pf::detail;
using bimloc::pf::Particle;
using bimloc::test::observations;
using bimloc::test::tiled;

namespace {

double segmentDistance(const Landmark& f, const Eigen::Vector2d& p) {
  const double u = std::clamp((p - f.start).dot(f.direction), 0.0, f.length_m);
  return (f.start + u * f.direction - p).norm();
}

}  // namespace

TEST(FaceIndex, VisitsEveryFaceWithinTheRadiusExactlyOnce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(0.0, 60.0), len(0.1, 25.0), ang(-M_PI, M_PI), rad(0.0, 9.0);
  std::vector<Landmark> faces;
  for (int i = 0; i < 400; ++i) {
    Landmark l;
    l.start = {pos(rng), pos(rng)};
    const double a = i % 3 == 0 ? ang(rng) : (i % 3 == 1 ? 0.0 : M_PI / 2);  // most walls axis-aligned
    l.direction = {std::cos(a), std::sin(a)};
    l.length_m = len(rng);
    faces.push_back(l);
  }
  for (const double cell : {0.5, 1.0, 2.0, 3.7}) {
    const FaceIndex index(faces, cell);
    for (int q = 0; q < 2000; ++q) {
      const Eigen::Vector2d c(pos(rng) * 1.2 - 6.0, pos(rng) * 1.2 - 6.0);
      const double r = rad(rng);
      std::multiset<const Landmark*> visited;
      index.forEachNear(c, r, [&](const Landmark& l) { visited.insert(&l); });
      for (const auto& l : index.faces()) {
        EXPECT_LE(visited.count(&l), 1u);
        if (segmentDistance(l, c) <= r) {
          EXPECT_EQ(visited.count(&l), 1u) << "cell " << cell << " query " << q;
        }
      }
    }
  }
}

TEST(FaceIndex, MatchThroughTheIndexIsTheMatchOverEveryFace) {
  const auto& office = test::officeWorld().building().storeys[0];
  const bim::Storey big = tiled(office, 4);  // 16 offices floors: 16x the faces
  const RoomIndex indexed(big, false), brute(big, false, true, 0.5, /*index_faces=*/false);
  ASSERT_NE(indexed.faceIndex(), nullptr);
  ASSERT_EQ(brute.faceIndex(), nullptr);
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  pf::ParticleFilterConfig config;
  config.use_rooms = false;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  int compared = 0, associated = 0;
  for (const char* name : {"R101", "R106", "C100", "S100", "W100"}) {
    const bim::Room* room = office.findRoom(name);
    ASSERT_NE(room, nullptr);
    const auto obs = observations(test::wallsSeenFrom(test::pose(room->centre.x(), room->centre.y(), 0.3), mount), mount);
    for (int k = 0; k < 60; ++k) {
      // Near the true pose (matches), in the other tiles (look-alikes), and anywhere.
      Particle p;
      const int tile_x = k % 4, tile_y = (k / 4) % 4;
      const double spread = k < 30 ? 0.3 : 3.0;
      p.x = room->centre.x() + 30.0 * tile_x + spread * noise(rng);
      p.y = room->centre.y() + 20.0 * tile_y + spread * noise(rng);
      p.yaw = 0.3 + (k < 30 ? 0.05 : 1.0) * noise(rng);
      p.room = indexed.roomAt(p.x, p.y);
      for (const double anneal : {1.0, 2.0, 6.0}) {
        pf::ParticleFilterConfig c = config;
        c.sigma_azimuth_deg *= anneal, c.sigma_elevation_deg *= anneal, c.sigma_d_m *= anneal, c.segment_margin_m *= anneal;
        const auto a = matchObservations(p, 0.5, obs, indexed, c);
        const auto b = matchObservations(p, 0.5, obs, brute, c);
        EXPECT_EQ(a.log_likelihood, b.log_likelihood) << name << " particle " << k << " anneal " << anneal;
        EXPECT_EQ(a.associated, b.associated);
        ++compared, associated += a.associated;
      }
    }
  }
  EXPECT_EQ(compared, 5 * 60 * 3);
  EXPECT_GT(associated, 1000);  // the comparison is not of empty matches
}

TEST(FaceIndex, HypothesesThroughTheIndexFindTheTrueAndEveryLookAlikePose) {
  // Every tile holds the same offices: a view of one fits all 16 tiles at the same place in
  // the tile. Through the index, the hypotheses over every face must still hold each of them.
  const auto& office = test::officeWorld().building().storeys[0];
  const bim::Storey big = tiled(office, 4);
  const RoomIndex indexed(big, false);
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  pf::ParticleFilterConfig config;
  config.use_rooms = false;
  const bim::Room* room = office.findRoom("R102");
  const Eigen::Vector3d truth(room->centre.x() + 0.4, room->centre.y() - 0.7, 1.1);
  const auto obs = observations(test::wallsSeenFrom(test::pose(truth.x(), truth.y(), truth.z()), mount), mount);
  const auto hyps = poseHypotheses(obs, 0.5, indexed, config, 100000);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      bool found = false;
      for (const auto& h : hyps)
        found |= std::hypot(h.x - truth.x() - 30.0 * i, h.y - truth.y() - 20.0 * j) < 0.1 &&
                 std::abs(wrapAngle(h.yaw - truth.z())) < 2.0 * M_PI / 180.0;
      EXPECT_TRUE(found) << "tile " << i << "," << j;
    }
}
