// The face index where the cells could change a result: faces that fit exactly alike
// (collinear pieces of a wall) keep the one the 1 m cells reach first, as before the match
// index moved to 2 m cells; a floor on the log-likelihood stops only matches that end below
// it; and hypotheses wanted within a margin of the best are those of the full search.
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

// Every wall cut into three collinear pieces: faces that fit an observation exactly alike
// (the same plane, bit for bit), where the face kept must not depend on the order visited.
bim::Storey splitWalls(const bim::Storey& s) {
  bim::Storey out = s;
  out.walls.clear();
  for (auto& r : out.rooms) r.walls.clear();
  for (const auto& w : s.walls)
    for (int k = 0; k < 3; ++k) {
      bim::Wall piece = w;
      piece.id += "/" + std::to_string(k);
      const double t0 = k / 3.0, t1 = (k + 1) / 3.0;
      piece.start = w.start + t0 * (w.end - w.start), piece.end = w.start + t1 * (w.end - w.start);
      for (int f = 0; f < 2; ++f) {
        const auto& face = w.faces[static_cast<std::size_t>(f)];
        piece.faces[static_cast<std::size_t>(f)].start = face.start + t0 * (face.end - face.start);
        piece.faces[static_cast<std::size_t>(f)].end = face.start + t1 * (face.end - face.start);
      }
      out.walls.push_back(piece);
    }
  return out;
}

// The definition a match through the index must meet, by brute force: the least squared
// Mahalanobis distance over every face along which the plane's points lie, and of faces tied
// at it, the one the 1 m cells reach first (RoomIndex::fineIndex: the order before the match
// index moved to 2 m cells).
std::vector<int> bruteForceFaces(const Particle& p, double z, const std::vector<Observation>& obs, const RoomIndex& rooms,
                                 const pf::ParticleFilterConfig& c, int* ties_not_lowest) {
  std::vector<int> out;
  const auto& faces = rooms.faceIndex()->faces();
  const double cy = std::cos(p.yaw), sy = std::sin(p.yaw);
  const double angle = std::max(c.sigma_azimuth_deg, c.sigma_elevation_deg) * M_PI / 180.0;
  for (const auto& o : obs) {
    const double nx = cy * o.normal_base.x() - sy * o.normal_base.y(), ny = sy * o.normal_base.x() + cy * o.normal_base.y();
    const bim::WallAxis axis = std::abs(nx) >= std::abs(ny) ? bim::WallAxis::X : bim::WallAxis::Y;
    const Eigen::Vector2d centroid(p.x + cy * o.centroid_base.x() - sy * o.centroid_base.y(),
                                   p.y + sy * o.centroid_base.x() + cy * o.centroid_base.y());
    double best = c.gate_mahalanobis2;
    std::vector<std::uint32_t> tied;
    for (std::uint32_t k = 0; k < faces.size(); ++k) {
      const Landmark& l = faces[k];
      if (l.axis != axis) continue;
      const double d_landmark = l.d + l.normal.x() * p.x + l.normal.y() * p.y + l.normal.z() * z;
      // As measurement.cpp computes it, to the bit: ties are ties of doubles.
      const double e_az = wrapAngle(o.azimuth_base + p.yaw - l.azimuth) * (1.0 / (c.sigma_azimuth_deg * M_PI / 180.0));
      const double e_el = (o.elevation - l.elevation) * (1.0 / (c.sigma_elevation_deg * M_PI / 180.0));
      const double e_d = (o.d_offset - d_landmark) * (1.0 / c.sigma_d_m);
      const double m2 = e_az * e_az + e_el * e_el + e_d * e_d;
      const double u = (centroid - l.start).dot(l.direction);
      if (m2 > best || u < -c.segment_margin_m || u > l.length_m + c.segment_margin_m) continue;
      if (m2 < best) tied.clear(), best = m2;
      tied.push_back(k);
    }
    if (tied.empty()) {
      out.push_back(-1);
      continue;
    }
    const double radius = matchRadius(o.range_m, c.sigma_d_m, angle, c.gate_mahalanobis2, c.segment_margin_m);
    std::uint32_t first = tied.front();
    // A radius of 12 m or more is matched over the list of faces (measurement.cpp): in its order.
    for (const std::uint32_t k : tied)
      if (radius < 12.0 && rooms.fineIndex()->visitsBefore(centroid, radius, k, first)) first = k;
    *ties_not_lowest += first != tied.front();
    out.push_back(faces[first].id);
  }
  return out;
}

}  // namespace

TEST(FaceIndex, SameFaceAsBruteForceWhereCollinearPiecesFitAlike) {
  const auto& office = test::officeWorld().building().storeys[0];
  const bim::Storey split = splitWalls(tiled(office, 2));
  const RoomIndex indexed(split, false);
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  pf::ParticleFilterConfig config;
  config.use_rooms = false;
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0.0, 1.0);
  int compared = 0, matched = 0, ties = 0;
  for (const char* name : {"R101", "R104", "C100", "S100"}) {
    const bim::Room* room = office.findRoom(name);
    const auto obs = observations(test::wallsSeenFrom(test::pose(room->centre.x(), room->centre.y(), -0.4), mount), mount);
    for (int k = 0; k < 40; ++k) {
      Particle p;
      p.x = room->centre.x() + 30.0 * (k % 2) + 0.5 * noise(rng), p.y = room->centre.y() + 20.0 * (k / 2 % 2) + 0.5 * noise(rng);
      p.yaw = -0.4 + 0.05 * noise(rng);
      p.room = indexed.roomAt(p.x, p.y);
      for (const double anneal : {1.0, 3.0}) {
        pf::ParticleFilterConfig c = config;
        c.sigma_azimuth_deg *= anneal, c.sigma_elevation_deg *= anneal, c.sigma_d_m *= anneal, c.segment_margin_m *= anneal;
        std::vector<ObservationMatch> a;
        matchObservations(p, 0.5, obs, indexed, c, &a);
        const std::vector<int> b = bruteForceFaces(p, 0.5, obs, indexed, c, &ties);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t o = 0; o < a.size(); ++o) {
          EXPECT_EQ(a[o].face, b[o]) << name << " particle " << k << " observation " << o;
          matched += a[o].face >= 0;
        }
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 4 * 40 * 2);
  EXPECT_GT(matched, 500);
  EXPECT_GT(ties, 10);  // ties the cells' order decides, not the lowest id
}

TEST(FaceIndex, AFloorStopsOnlyMatchesThatEndBelowIt) {
  const auto& office = test::officeWorld().building().storeys[0];
  const RoomIndex indexed(office, false);
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  pf::ParticleFilterConfig config;
  config.use_rooms = false;
  std::mt19937_64 rng(4);
  std::normal_distribution<double> noise(0.0, 1.0);
  const bim::Room* room = office.findRoom("R103");
  const auto obs = observations(test::wallsSeenFrom(test::pose(room->centre.x(), room->centre.y(), 0.2), mount), mount);
  int stopped = 0, kept = 0;
  for (int k = 0; k < 400; ++k) {
    Particle p;
    p.x = room->centre.x() + 2.0 * noise(rng), p.y = room->centre.y() + 2.0 * noise(rng), p.yaw = 0.2 + 0.3 * noise(rng);
    p.room = indexed.roomAt(p.x, p.y);
    const auto full = matchObservations(p, 0.5, obs, indexed, config);
    const double floor = -40.0 * (k % 10) / 10.0;
    const auto cut = matchObservations(p, 0.5, obs, indexed, config, nullptr, true, floor);
    EXPECT_FALSE(full.below_floor);
    if (cut.below_floor) {
      EXPECT_LT(full.log_likelihood, floor);
      ++stopped;
    } else {
      EXPECT_EQ(cut.log_likelihood, full.log_likelihood);
      EXPECT_EQ(cut.associated, full.associated);
      EXPECT_GE(full.log_likelihood, floor);
      ++kept;
    }
  }
  EXPECT_GT(stopped, 50);
  EXPECT_GT(kept, 50);
}

TEST(FaceIndex, HypothesesWantedWithinAMarginAreThoseOfTheFullSearch) {
  // What proposeEveryFit asks for: the same hypotheses (bits and order) down to the margin.
  const auto& office = test::officeWorld().building().storeys[0];
  const bim::Storey big = tiled(office, 2);
  const RoomIndex indexed(big, false);
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  pf::ParticleFilterConfig config;
  config.use_rooms = false;
  for (const char* name : {"R102", "R105", "C100"}) {
    const bim::Room* room = office.findRoom(name);
    const auto obs = observations(test::wallsSeenFrom(test::pose(room->centre.x() + 0.3, room->centre.y() - 0.2, 0.7), mount), mount);
    const auto all = poseHypotheses(obs, 0.5, indexed, config, std::numeric_limits<std::size_t>::max());
    ASSERT_FALSE(all.empty());
    for (const double within : {0.0, 5.0, 17.0, 60.0}) {
      const auto some = poseHypotheses(obs, 0.5, indexed, config, std::numeric_limits<std::size_t>::max(), within);
      std::size_t n = 0;
      while (n < all.size() && all[n].log_likelihood >= all.front().log_likelihood - within) ++n;
      ASSERT_GE(some.size(), n) << name << " within " << within;
      for (std::size_t k = 0; k < n; ++k) {
        EXPECT_EQ(some[k].x, all[k].x);
        EXPECT_EQ(some[k].y, all[k].y);
        EXPECT_EQ(some[k].yaw, all[k].yaw);
        EXPECT_EQ(some[k].log_likelihood, all[k].log_likelihood);
      }
      for (std::size_t k = n; k < some.size(); ++k) EXPECT_LT(some[k].log_likelihood, all.front().log_likelihood - within);
    }
  }
}
