// The match by side (wallSide, landmark.hpp) against brute force: a plane is matched against
// the faces of its axis that face its way only, because a face of the other side can never
// pass the gate. Checked on the bound itself (opposite sides are 90 deg apart) and on the
// match: through the side lists and side indices it is the match over every face of the axis
// (the tests' brute-force RoomIndex, built without an index), to the bit, on the default world
// tiled and turned so that walls run at every angle, 45 deg included.
#include "face_index_fixtures.hpp"
#include "sim_fixtures.hpp"

#include "pf/measurement.hpp"
#include "pf/room_index.hpp"
#include "sim/lidar/vlp16_config.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace bimloc;
using namespace bimloc::pf::detail;

namespace {

// The storey turned by `angle` about the map's origin (n . p + d = 0 holds for R n, R p).
bim::Storey turned(const bim::Storey& s, double angle) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  bim::Storey out = s;
  for (auto& w : out.walls) {
    w.start = R * w.start, w.end = R * w.end;
    for (auto& f : w.faces) f.plane.n = R * f.plane.n, f.start = R * f.start, f.end = R * f.end;
  }
  for (auto& r : out.rooms) {
    r.centre = R.topLeftCorner<2, 2>() * r.centre;
    for (auto& q : r.footprint) q = R.topLeftCorner<2, 2>() * q;
  }
  return out;
}

}  // namespace

TEST(WallSides, OppositeSidesOfOneAxisAreAtLeastNinetyDegreesApart) {
  std::mt19937_64 rng(2812);
  std::uniform_real_distribution<double> ang(-M_PI, M_PI), tilt(0.0, 1.2), near45(-1e-9, 1e-9);
  int opposite = 0;
  for (int i = 0; i < 200000; ++i) {
    // Half of them within a hair of the diagonals, where the axis changes.
    const double a = i % 2 ? ang(rng) : (std::floor(ang(rng) / (0.5 * M_PI)) + 0.5) * 0.5 * M_PI + near45(rng);
    const double b = i % 4 < 2 ? ang(rng) : (std::floor(ang(rng) / (0.5 * M_PI)) + 0.5) * 0.5 * M_PI + near45(rng);
    const double ca = std::cos(tilt(rng)), cb = std::cos(tilt(rng));
    const Eigen::Vector2d n(ca * std::cos(a), ca * std::sin(a)), m(cb * std::cos(b), cb * std::sin(b));
    const int sn = wallSide(n.x(), n.y()), sm = wallSide(m.x(), m.y());
    if (sn < 0 || sm < 0) {
      EXPECT_LT(std::max(std::abs(sn < 0 ? n.x() : m.x()), std::abs(sn < 0 ? n.y() : m.y())), 0.5);
      continue;
    }
    if (sn / 2 != sm / 2 || sn == sm) continue;
    ++opposite;
    EXPECT_LE(n.dot(m), 1e-15) << a << " " << b;
    EXPECT_GE(std::abs(wrapAngle(a - b)), 0.5 * M_PI - 1e-12) << a << " " << b;
  }
  EXPECT_GT(opposite, 10000);
  EXPECT_EQ(wallSide(std::nan(""), 1.0), -1);
  EXPECT_EQ(wallSide(0.3, -0.3), -1);
  EXPECT_EQ(wallSide(-0.8, 0.8), 1);  // on the diagonal: the x axis (|nx| >= |ny|), as Landmark::axis
}

TEST(WallSides, MatchBySideIsTheMatchOverEveryFaceOfTheAxis) {
  const auto& office = test::officeWorld().building().storeys[0];
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  std::mt19937_64 rng(2813);
  std::normal_distribution<double> noise(0.0, 1.0);
  int compared = 0, associated = 0;
  for (const double angle : {0.0, 0.6, 0.25 * M_PI, 2.0}) {
    const bim::Storey big = turned(test::tiled(office, 2), angle);
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(angle).toRotationMatrix();
    for (const bool use_rooms : {true, false}) {
      const RoomIndex sided(big, use_rooms), brute(big, use_rooms, true, 0.5, /*index_faces=*/false);
      pf::ParticleFilterConfig config;
      config.use_rooms = use_rooms;
      for (const char* name : {"R101", "R106", "C100", "S100"}) {
        const bim::Room* room = office.findRoom(name);
        ASSERT_NE(room, nullptr);
        const auto obs = test::observations(test::wallsSeenFrom(test::pose(room->centre.x(), room->centre.y(), 0.3), mount), mount);
        for (int k = 0; k < 24; ++k) {
          // Near the true pose of a tile (matches), farther, and turned every way.
          const Eigen::Vector2d at = R * Eigen::Vector2d(room->centre.x() + 30.0 * (k % 2), room->centre.y() + 20.0 * ((k / 2) % 2));
          const double spread = k < 12 ? 0.2 : 2.0;
          pf::Particle p;
          p.x = at.x() + spread * noise(rng), p.y = at.y() + spread * noise(rng);
          p.yaw = 0.3 + angle + (k < 12 ? 0.05 : 1.5) * noise(rng);
          p.room = sided.roomAt(p.x, p.y);
          // Outside every room, a filter matches through the index, which the brute force has not.
          if (use_rooms && p.room < 0) continue;
          for (const double anneal : {1.0, 2.0, 6.0}) {
            pf::ParticleFilterConfig c = config;
            c.sigma_azimuth_deg *= anneal, c.sigma_elevation_deg *= anneal, c.sigma_d_m *= anneal, c.segment_margin_m *= anneal;
            std::vector<ObservationMatch> ma, mb;
            const auto a = matchObservations(p, 0.5, obs, sided, c, &ma);
            const auto b = matchObservations(p, 0.5, obs, brute, c, &mb);
            EXPECT_EQ(a.log_likelihood, b.log_likelihood) << angle << " " << name << " particle " << k << " anneal " << anneal;
            EXPECT_EQ(a.associated, b.associated);
            ASSERT_EQ(ma.size(), mb.size());
            for (std::size_t i = 0; i < ma.size(); ++i) {
              // Of faces that fit alike, the brute force keeps the first in its list, an index the
              // first in its cells' order (face_index_ties): the same face where both go by the list.
              if (use_rooms) {
                EXPECT_EQ(ma[i].face, mb[i].face) << angle << " " << name << " particle " << k << " plane " << i;
              }
              EXPECT_EQ(ma[i].m2, mb[i].m2);
              EXPECT_EQ(ma[i].filling, mb[i].filling);
            }
            ++compared, associated += a.associated;
          }
        }
      }
    }
  }
  EXPECT_GT(compared, 4 * 4 * 24 * 3);
  EXPECT_GT(associated, 1500);  // the comparison is not of empty matches
}

TEST(WallSides, AnIndexOfSomeFacesVisitsThoseTheWholeIndexVisitsInItsOrder) {
  std::mt19937_64 rng(2814);
  std::uniform_real_distribution<double> pos(0.0, 60.0), len(0.1, 25.0), ang(-M_PI, M_PI), rad(0.0, 9.0);
  std::bernoulli_distribution coin(0.3);
  std::vector<Landmark> faces;
  std::vector<bool> keep;
  for (int i = 0; i < 400; ++i) {
    Landmark l;
    l.start = {pos(rng), pos(rng)};
    const double a = i % 3 == 0 ? ang(rng) : (i % 3 == 1 ? 0.0 : M_PI / 2);
    l.direction = {std::cos(a), std::sin(a)};
    l.length_m = len(rng);
    faces.push_back(l), keep.push_back(coin(rng));
  }
  for (const double cell : {1.0, 2.0}) {
    const FaceIndex whole(faces, cell), some(faces, cell, keep);
    int visited = 0;
    for (int q = 0; q < 2000; ++q) {
      const Eigen::Vector2d c(pos(rng) * 1.2 - 6.0, pos(rng) * 1.2 - 6.0);
      const double r = rad(rng);
      std::vector<std::size_t> expected, got;
      whole.forEachNear(c, r, [&](const Landmark& l) {
        const auto i = static_cast<std::size_t>(&l - whole.faces().data());
        if (keep[i]) expected.push_back(i);
      });
      some.forEachNear(c, r, [&](const Landmark& l) { got.push_back(static_cast<std::size_t>(&l - some.faces().data())); });
      EXPECT_EQ(got, expected) << "cell " << cell << " query " << q;
      visited += static_cast<int>(got.size());
    }
    EXPECT_GT(visited, 5000);
  }
}
