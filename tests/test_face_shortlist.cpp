// The local search's faces found once per scan (pf::detail::FaceShortlist) against the face
// index queried at every pose: at every pose of the region, the same match to the bit (each
// observation's face and squared distance, the log-likelihood, the count), on a floor of 16
// offices tiled from the default world, with planes as the VLP-16 model sees them.
#include "face_index_fixtures.hpp"
#include "sim_fixtures.hpp"

#include "pf/path_evidence.hpp"
#include "pf/pose_refinement.hpp"
#include "pf/room_index.hpp"
#include "sim/lidar/vlp16_config.hpp"
#include "sim/world/world.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace bimloc;
using namespace bimloc::pf::detail;

namespace {

// ParticleFilter::observe's heights and standing span, which test::observations leaves out:
// the height and through-wall rules read them.
std::vector<Observation> observationsWithSpans(const std::vector<planes::ObservedPlane>& walls, const Eigen::Isometry3d& mount) {
  std::vector<Observation> out = test::observations(walls, mount);
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const Eigen::Vector3d c = mount * walls[k].centroid;
    out[k].z_low = c.z() - 0.5 * walls[k].height_extent_m, out[k].z_high = c.z() + 0.5 * walls[k].height_extent_m;
    out[k].extent_m = walls[k].extent_m;
    if (walls[k].wall_span_middle.allFinite()) {
      out[k].wall_span_m = walls[k].wall_span_m;
      out[k].span_middle_base = (mount * walls[k].wall_span_middle).head<2>();
    }
  }
  return out;
}


// At poses of regions around six offices' truths (in their tile, in a look-alike tile, and a
// metre off), the match through each region's shortlist against the match through the index,
// under the error model `model`, for each opening margin of `margins`.
void compareShortlistWithIndex(const bim::Storey& office, const bim::Storey& big, const pf::ParticleFilterConfig& model,
                               const std::vector<double>& margins) {
  const RoomIndex every_face(big, /*use_rooms=*/false);
  ASSERT_NE(every_face.faceIndex(), nullptr);
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  std::mt19937_64 rng(28);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0, shortlisted = 0, associated = 0, hidden_checked = 0;
  for (const char* name : {"R101", "R104", "R106", "C100", "S100", "W100"}) {
    const bim::Room* room = office.findRoom(name);
    ASSERT_NE(room, nullptr);
    const double yaw = 0.4;
    const auto obs = observationsWithSpans(test::wallsSeenFrom(test::pose(room->centre.x(), room->centre.y(), yaw), mount), mount);
    ASSERT_GE(obs.size(), 3u) << name;
    // The region around the truth, in its own tile and in a look-alike one, and once wrong by a
    // metre (a rival place the search refines).
    for (const Eigen::Vector3d& centre : {Eigen::Vector3d(room->centre.x(), room->centre.y(), yaw),
                                          Eigen::Vector3d(room->centre.x() + 60.0, room->centre.y() + 20.0, yaw + 0.02),
                                          Eigen::Vector3d(room->centre.x() + 1.0, room->centre.y() - 0.7, yaw - 0.05)}) {
      for (const double margin : margins) {
        const double xy_radius = 0.6, yaw_radius = kShortlistYawRad;
        const FaceShortlist list = shortlistFaces(centre, xy_radius, yaw_radius, 0.5, obs, every_face, model, margin);
        ASSERT_EQ(list.match.size(), obs.size());
        for (int k = 0; k < 150; ++k) {
          pf::Particle p;
          // Most inside the region, some on its rim (the radius and the turn at their limits).
          const double r = k < 20 ? xy_radius : xy_radius * std::sqrt(std::abs(unit(rng))), a = M_PI * unit(rng);
          p.x = centre.x() + r * std::cos(a), p.y = centre.y() + r * std::sin(a);
          p.yaw = wrapAngle(centre.z() + (k < 20 ? (k % 2 ? 1 : -1) * yaw_radius : yaw_radius * unit(rng)));
          p.room = -1;
          if (!list.holds(p)) continue;  // rounding at the rim
          std::vector<ObservationMatch> with, without;
          const MatchResult a_res = matchObservations(p, 0.5, obs, every_face, model, &with, false,
                                                      -std::numeric_limits<double>::infinity(), margin, &list);
          p.room = every_face.roomAt(p.x, p.y);
          const MatchResult b_res = matchObservations(p, 0.5, obs, every_face, model, &without, false,
                                                      -std::numeric_limits<double>::infinity(), margin);
          EXPECT_EQ(a_res.log_likelihood, b_res.log_likelihood) << name << " pose " << k << " margin " << margin;
          EXPECT_EQ(a_res.associated, b_res.associated);
          ASSERT_EQ(with.size(), without.size());
          for (std::size_t m = 0; m < with.size(); ++m) {
            EXPECT_EQ(with[m].face, without[m].face) << name << " pose " << k << " observation " << m;
            EXPECT_EQ(with[m].m2, without[m].m2);
            hidden_checked += margin >= 0 && with[m].m2 > model.gate_mahalanobis2;
          }
          ++compared, associated += a_res.associated;
        }
        for (const auto& faces : list.match) shortlisted += static_cast<int>(faces.size());
      }
    }
  }
  EXPECT_GT(compared, 2000 * static_cast<int>(margins.size()));
  EXPECT_GT(associated, compared);  // matches, not empty comparisons (7496 in 4680 poses)
  const bool local = std::any_of(margins.begin(), margins.end(), [](double m) { return m >= 0.0; });
  if (local) {
    EXPECT_GT(hidden_checked, 0);  // some planes behind a solid face, through the shortlist too
  }
  EXPECT_GT(shortlisted, 0);
}

}  // namespace

TEST(FaceShortlist, EveryPoseOfTheRegionMatchesAsThroughTheIndex) {
  const auto& office = test::officeWorld().building().storeys[0];
  compareShortlistWithIndex(office, test::tiled(office, 4), refinementModel(pf::ParticleFilterConfig{}), {0.15, -1.0});
}

// The path evidence's refine (PathEvidence::shortlists) matches under the window's error model
// (sigmas grown by the drift over the window: wider match radii and angles) and no opening
// margin: the same bits through the shortlist there too, for the whole window's drift and a short path's.
TEST(FaceShortlist, ThePathEvidencesWindowModelMatchesAsThroughTheIndex) {
  const auto& office = test::officeWorld().building().storeys[0];
  const bim::Storey big = test::tiled(office, 4);
  const pf::ParticleFilterConfig filter;
  const PathEvidence evidence(big, filter);
  compareShortlistWithIndex(office, big, evidence.scanModel(), {-1.0});
  // The window's model at its start, with the drift of the path it covers (the narrowest).
  pf::ParticleFilterConfig short_path = filter;
  short_path.evidence_drift_of_window = true;
  compareShortlistWithIndex(office, big, PathEvidence(big, short_path).scanModel(), {-1.0});
}

// The refinement's scans each get a shortlist around the search's centre; a pose beyond it
// (turned past kShortlistYawRad) is not held, and is matched through the index.
TEST(FaceShortlist, ARegionHoldsOnlyItsPoses) {
  FaceShortlist list;
  list.centre = {10.0, 5.0, 3.1};
  list.xy_radius_m = 0.5, list.yaw_radius = 0.1;
  pf::Particle p;
  p.x = 10.3, p.y = 5.3, p.yaw = -3.1;  // across the +-pi cut: 0.083 rad from the centre's heading
  EXPECT_TRUE(list.holds(p));
  p.yaw = -3.0;
  EXPECT_FALSE(list.holds(p));
  p.yaw = 3.1, p.x = 10.45;
  EXPECT_FALSE(list.holds(p));
}

// The match radius with its range-free part worked out once (MatchReach) is the formula of
// face_index.hpp, written out here, to the bit.
TEST(FaceShortlist, TheMatchReachIsTheMatchRadiusFormula) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> sigma_d(0.01, 1.0), angle(0.001, 0.5), gate(1.0, 30.0), margin(0.0, 1.0), range(0.0, 40.0);
  int finite = 0;
  for (int k = 0; k < 20000; ++k) {
    const double s = sigma_d(rng), a = k % 50 == 0 ? 1.5 : angle(rng), g = gate(rng), m = margin(rng), r = range(rng);
    const double kk = std::sqrt(g), turn = std::sqrt(2.0) * kk * a;
    const double formula = turn >= M_PI ? std::numeric_limits<double>::infinity()
                                        : std::hypot(kk * s + 2.0 * std::sin(0.5 * turn) * r + 0.1, m);
    const MatchReach reach(s, a, g, m);
    EXPECT_EQ(reach.at(r), formula);
    EXPECT_EQ(matchRadius(r, s, a, g, m), formula);
    finite += std::isfinite(formula);
  }
  EXPECT_GT(finite, 15000);
  EXPECT_LT(finite, 20000);
}
