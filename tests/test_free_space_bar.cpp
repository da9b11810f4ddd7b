// The free space's unit is the bar's: a wall every ray of which went far through it at a place is
// worth exactly one face there, so two such walls are the bar of two faces (evidenceMargin), and
// one alone stays under it. Rays are cast here, in 2D against a storey built in code, so that how
// far beyond each wall a ray ended is known from the geometry.
#include "sgraph_fixtures.hpp"

#include "pf/free_space_evidence.hpp"

#include <bimloc/pf/particle_filter.hpp>
#include <bimloc/pf/range_profile.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace bimloc;
using namespace bimloc::pf::detail;

namespace {

// Two walls, 0.2 m thick, at a right angle and apart: E on the axis x = 5 (its near face at
// x = 4.9, y -3..3) and N on y = 5 (near face at y = 4.9, x -3..3). The place stands at the
// origin, where the rival's walls would be; the scan's rays went through both.
bim::Storey twoWalls() {
  bim::Storey s;
  s.walls.push_back(test::boxWall("E", {5, -3}, {5, 3}, 0.2));
  s.walls.push_back(test::boxWall("N", {-3, 5}, {3, 5}, 0.2));
  return s;
}

// Rays from the origin (lidar 0.6 m up), ending `beyond` past the near face of E (along +x, at
// y = -2..2) and of N (along +y, at x = -2..2), head-on or nearly.
pf::RangeProfile raysThrough(double beyond) {
  pf::RangeProfile p;
  p.origin_base = Eigen::Vector3d(0, 0, 0.6);
  for (int k = -4; k <= 4; ++k) {
    p.ends_base.emplace_back(static_cast<float>(4.9 + beyond), static_cast<float>(0.5 * k), 1.4f);
    p.ends_base.emplace_back(static_cast<float>(0.5 * k), static_cast<float>(4.9 + beyond), 1.4f);
  }
  return p;
}

}  // namespace

TEST(FreeSpaceBar, TwoWallsEveryRayWentThroughAreTheBarAndOneIsNot) {
  const pf::ParticleFilterConfig config;
  const FreeSpaceParams params = FreeSpaceParams::of(config, 0.0);
  const bim::Storey storey = twoWalls();
  const FreeSpaceMap map(storey);
  // Past the gate (5 sigma of the range at normal incidence: a ray 2 m off-axis has a wider
  // sigma, by its incidence and the heading's slip, and at 3.6 sigma two of the nine stay
  // within the gate), and far beyond (2 m, a wall not there at all).
  for (const double beyond : {5.0 * params.sigma_m, 2.0}) {
    const auto hits = freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, raysThrough(beyond));
    int through_e = 0, through_n = 0;
    for (const auto& h : hits) {
      through_e += h.key == 0 ? 1 : 0;
      through_n += h.key == 1 ? 1 : 0;
    }
    ASSERT_EQ(through_e, 9) << beyond;
    ASSERT_EQ(through_n, 9) << beyond;
    // Every ray beyond the gate costs the floor, one face; each wall counts once: two faces'
    // worth exactly, which passes the bar (evidence_faces less its tolerance).
    const double two_faces = config.evidence_faces * params.face_worth;
    EXPECT_DOUBLE_EQ(freeSpacePenalty({&hits}, params), two_faces) << beyond;
    EXPECT_GE(freeSpacePenalty({&hits}, params), config.evidenceMargin()) << beyond;
    // The sum of the ray's two explanations, -log((1 - w) exp(-z^2 / 2) + w), stays under the
    // floor's cap until exp(-z^2 / 2) vanishes against w in double precision: at 5 sigma two walls
    // of it missed the bar (4.1698 of 4.17 a wall); only rays metres beyond made it. (Two faces,
    // the bar before its tolerance: ParticleFilterConfig::evidence_bar_tolerance_faces.)
    const double w = std::exp(-params.face_worth), z = beyond / params.sigma_m;
    if (z < 6.0) {
      EXPECT_LT(2.0 * -std::log((1.0 - w) * std::exp(-0.5 * z * z) + w), two_faces) << beyond;
    }
    // One wall alone (a wall of the place not built yet, every ray through it): one face, under
    // the bar, as the one-deviation rule asks.
    std::vector<FreeSpaceHit> one;
    for (const auto& h : hits)
      if (h.key == 0) one.push_back(h);
    EXPECT_DOUBLE_EQ(freeSpacePenalty({&one}, params), params.face_worth) << beyond;
    EXPECT_LT(freeSpacePenalty({&one}, params), config.evidenceMargin()) << beyond;
  }
  // Within the gate the ray is the wall's noise: no cost, whatever the floor.
  EXPECT_TRUE(freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, raysThrough(2.0 * params.sigma_m)).empty());
}

// The bar is evidence_faces faces' worth less a hundredth of a face: two faces the rival cannot
// explain pass it whatever the fits' noise on the faces both places explain adds (the margins of
// random_office_26700 R001, held 12 s under an exact bar), and a face and a half, or one face,
// do not.
TEST(FreeSpaceBar, TwoFacesLessTheirNoisePassTheBarAndAFaceAndAHalfDoNot) {
  const pf::ParticleFilterConfig config;
  const double face = 0.5 * (config.gate_mahalanobis2 - 3.0);
  EXPECT_DOUBLE_EQ(config.evidenceMargin(), (config.evidence_faces - config.evidence_bar_tolerance_faces) * face);
  for (const double margin : {8.339999, 8.339168, 8.337542, 8.30})
    EXPECT_GE(margin, config.evidenceMargin()) << margin;
  for (const double margin : {7.989657, 1.5 * face, face, 2.0 * face - 0.02 * face}) EXPECT_LT(margin, config.evidenceMargin()) << margin;
  pf::ParticleFilterConfig exact = config;  // the tolerance off: the bar of sessions up to 31
  exact.evidence_bar_tolerance_faces = 0.0;
  EXPECT_DOUBLE_EQ(exact.evidenceMargin(), 2.0 * face);
  EXPECT_LT(8.339999, exact.evidenceMargin());
}
