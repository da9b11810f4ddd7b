// The path evidence's per-face margin (FaceMargin, path_verdict.cpp): one wall is one face
// whichever of the two places missed it in a scan. The truth here is the margin's own
// definition: P over Q is minus Q over P when each of P's faces is one of Q's (twins), and a miss
// weighs the same against either place.
#include "pf/path_evidence.hpp"

#include <bimloc/pf/particle_filter.hpp>

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace bimloc;
using pf::detail::FaceMargin;
using pf::detail::ObservationMatch;

namespace {

struct Look {
  ObservationMatch at_p, at_q;
  bool p_out = false, q_out = false;  // the scan's room prior (one look per scan here)
};

double marginOf(const std::vector<Look>& looks, double gate, bool swapped) {
  FaceMargin margin;
  for (const Look& l : looks) {
    margin.addScan(swapped ? l.q_out : l.p_out, swapped ? l.p_out : l.q_out);
    margin.add(swapped ? l.at_q : l.at_p, swapped ? l.at_p : l.at_q);
  }
  return margin.total(gate, static_cast<double>(looks.size()));
}

}  // namespace

TEST(FaceMargin, AMissOfEitherPlaceWeighsTheSameOverManyGeneratedWindows) {
  // Twins: P's face 2 f is Q's face 100 + 6 f. Each look matches both (m2 drawn), or one place
  // misses (m2 = gate), after the face has been matched by both at least once. P over Q must
  // be minus Q over P; before misses of P were filed under Q's face, one miss of the best in
  // twenty looks counted in full (random_hall_26215 R001: the truth 5.6 under its twin).
  const double gate = pf::ParticleFilterConfig{}.gate_mahalanobis2;
  std::mt19937 rng(2831);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int window = 0; window < 200; ++window) {
    const int faces = 1 + static_cast<int>(unit(rng) * 6);
    const int n = 2 + static_cast<int>(unit(rng) * 40);
    std::vector<Look> looks;
    std::vector<char> seen(static_cast<std::size_t>(faces), 0);
    for (int k = 0; k < n; ++k) {
      const int f = static_cast<int>(unit(rng) * faces);
      Look l;
      l.at_p = {2 * f, static_cast<float>(unit(rng) * gate)};
      l.at_q = {100 + 6 * f, static_cast<float>(unit(rng) * gate)};
      l.p_out = unit(rng) < 0.1, l.q_out = unit(rng) < 0.1;
      const double miss = unit(rng);
      if (seen[static_cast<std::size_t>(f)] && miss < 0.15) l.at_p = {-1, static_cast<float>(gate)};
      else if (seen[static_cast<std::size_t>(f)] && miss < 0.3) l.at_q = {-1, static_cast<float>(gate)};
      seen[static_cast<std::size_t>(f)] = 1;
      looks.push_back(l);
    }
    const double pq = marginOf(looks, gate, false), qp = marginOf(looks, gate, true);
    EXPECT_NEAR(pq, -qp, 1e-9) << "window " << window;
  }
}

TEST(FaceMargin, OneMissInElevenLooksIsAnEleventhOfAFace) {
  const double gate = pf::ParticleFilterConfig{}.gate_mahalanobis2;
  std::vector<Look> looks(10, Look{{4, 0.5f}, {9, 0.1f}});
  looks.push_back(Look{{-1, static_cast<float>(gate)}, {9, 0.1f}});
  // Ten looks: Q better by 0.5 (0.5 - 0.1) / 2 = 0.2 each; the miss: (gate - 0.1) / 2.
  const double expected = -(10 * 0.2 + 0.5 * (gate - 0.1)) / 11.0;
  EXPECT_NEAR(marginOf(looks, gate, false), expected, 1e-6);
  EXPECT_NEAR(marginOf(looks, gate, true), -expected, 1e-6);
}

TEST(FaceMargin, AFaceOnlyTheRivalExplainsIsAFaceOfItsOwn) {
  // No look where both explained Q's face 9: nothing to file it under but itself, in full.
  const double gate = pf::ParticleFilterConfig{}.gate_mahalanobis2;
  std::vector<Look> looks(5, Look{{4, 0.2f}, {7, 0.2f}});
  looks.push_back(Look{{-1, static_cast<float>(gate)}, {9, 0.3f}});
  looks.push_back(Look{{-1, static_cast<float>(gate)}, {9, 0.3f}});
  EXPECT_NEAR(marginOf(looks, gate, false), -0.5 * (gate - 0.3), 1e-6);
}
