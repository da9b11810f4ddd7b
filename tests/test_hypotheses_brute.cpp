// The pose hypotheses against brute force: every ordered pair of observations against every
// ordered pair of faces (no face index, no floor, each solved pose scored, repeats and all),
// written out here from the definitions in hypotheses.cpp. poseHypotheses skips pairs of faces
// the robot cannot see together (the face index), stops scoring below a floor, and scores a
// pose solved by several pairs once (dropRepeatedPoses); none of that may change a hypothesis
// the callers use: the global search's fits within its margin (proposeEveryFit), and the
// seeds, every room's, all of them (seedHypotheses).
#include "face_index_fixtures.hpp"
#include "sim_fixtures.hpp"

#include "pf/hypotheses.hpp"
#include "pf/measurement.hpp"
#include "sim/lidar/vlp16_config.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <string>
#include <tuple>

using namespace bimloc;
using namespace bimloc::pf::detail;
using bimloc::pf::Particle;
using bimloc::test::observations;
using bimloc::test::tiled;

namespace {

constexpr double kBruteTolRad = 5.0 * M_PI / 180.0;
constexpr double kBruteMinTurnRad = 30.0 * M_PI / 180.0;

// Observation i on face a and j on face b: the pose, when the relative angles agree, the two
// planes are not near parallel, each plane's points lie along its face and the pose is in a
// room (`room`, or any when -1).
bool bruteSolve(const std::vector<Observation>& obs, std::size_t i, std::size_t j, const Landmark& a, const Landmark& b,
                double z, int room, const RoomIndex& rooms, double margin_m, Particle& p) {
  const double turn = wrapAngle(obs[j].azimuth_base - obs[i].azimuth_base);
  if (std::abs(turn) < kBruteMinTurnRad || std::abs(turn) > M_PI - kBruteMinTurnRad) return false;
  if (std::abs(wrapAngle(b.azimuth - a.azimuth - turn)) > kBruteTolRad) return false;
  if (!atFaceHeight(obs[i], a, z) || !atFaceHeight(obs[j], b, z)) return false;
  Eigen::Matrix2d A;
  A << a.normal.x(), a.normal.y(), b.normal.x(), b.normal.y();
  if (std::abs(A.determinant()) < 0.3) return false;
  const Eigen::Vector2d rhs(obs[i].d_offset - a.d - a.normal.z() * z, obs[j].d_offset - b.d - b.normal.z() * z);
  const Eigen::Vector2d xy = A.inverse() * rhs;
  // Each plane's centroid along its face (within the segment margin).
  const double yaw = wrapAngle(a.azimuth - obs[i].azimuth_base);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  for (const auto& [o, f] : {std::pair<const Observation*, const Landmark*>{&obs[i], &a}, {&obs[j], &b}}) {
    const Eigen::Vector2d q = o->centroid_base;
    const Eigen::Vector2d at(xy.x() + cy * q.x() - sy * q.y(), xy.y() + sy * q.x() + cy * q.y());
    const double u = (at - f->start).dot(f->direction);
    if (u < -margin_m || u > f->length_m + margin_m) return false;
  }
  p = Particle{};
  p.x = xy.x(), p.y = xy.y(), p.yaw = wrapAngle(a.azimuth - obs[i].azimuth_base), p.room = rooms.roomAt(xy.x(), xy.y());
  return p.room >= 0 && (room < 0 || p.room == room);
}

// Every pose of every pair scored in full; those explaining three planes, best first (ties by
// x, y, yaw), near-duplicates (0.2 m, 5 deg of a better one) out, at most max_count.
std::vector<Hypothesis> bruteHypotheses(const std::vector<Observation>& obs, double z, const RoomIndex& rooms,
                                        const pf::ParticleFilterConfig& c, const std::vector<Landmark>& every_face,
                                        std::size_t max_count, const std::vector<char>* only_rooms = nullptr) {
  std::vector<Hypothesis> all;
  const int room_count = c.use_rooms ? static_cast<int>(rooms.roomCount()) : 1;
  for (int r = 0; r < room_count; ++r) {
    if (only_rooms && !(*only_rooms)[static_cast<std::size_t>(r)]) continue;
    const std::vector<Landmark>& faces = c.use_rooms ? rooms.landmarks(r) : every_face;
    for (std::size_t i = 0; i < obs.size(); ++i)
      for (std::size_t j = 0; j < obs.size(); ++j)
        for (std::size_t a = 0; a < faces.size(); ++a)
          for (std::size_t b = 0; b < faces.size(); ++b) {
            Particle p;
            if (i == j || a == b || !bruteSolve(obs, i, j, faces[a], faces[b], z, c.use_rooms ? r : -1, rooms, c.segment_margin_m, p)) continue;
            const MatchResult m = matchObservations(p, z, obs, rooms, c);
            if (m.associated >= 3) all.push_back({p.x, p.y, p.yaw, p.room, m.log_likelihood, m.associated});
          }
  }
  std::sort(all.begin(), all.end(), [](const Hypothesis& a, const Hypothesis& b) {
    return a.log_likelihood != b.log_likelihood ? a.log_likelihood > b.log_likelihood
                                                : std::tie(a.x, a.y, a.yaw) < std::tie(b.x, b.y, b.yaw);
  });
  std::vector<Hypothesis> kept;
  for (const auto& h : all) {
    bool duplicate = false;
    for (const auto& o : kept)
      duplicate |= (h.x - o.x) * (h.x - o.x) + (h.y - o.y) * (h.y - o.y) < 0.04 && std::abs(wrapAngle(h.yaw - o.yaw)) < kBruteTolRad;
    if (duplicate) continue;
    kept.push_back(h);
    if (kept.size() >= max_count) break;
  }
  return kept;
}

void expectSame(const std::vector<Hypothesis>& got, const std::vector<Hypothesis>& want, std::size_t n, const char* what) {
  ASSERT_GE(got.size(), n) << what;
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_EQ(got[k].x, want[k].x) << what << " #" << k;
    EXPECT_EQ(got[k].y, want[k].y) << what << " #" << k;
    EXPECT_EQ(got[k].yaw, want[k].yaw) << what << " #" << k;
    EXPECT_EQ(got[k].log_likelihood, want[k].log_likelihood) << what << " #" << k;
    EXPECT_EQ(got[k].associated, want[k].associated) << what << " #" << k;
  }
}

struct BruteCase {
  const char* room;
  double dx, dy, yaw;
};
constexpr BruteCase kBruteCases[] = {{"R102", 0.3, -0.2, 0.7}, {"R105", -0.4, 0.5, 2.2}, {"C100", 0.6, 0.1, -1.3}};

// The default world tiled 2 x 2: every view has a look-alike in each tile.
const bim::Storey& bruteFloor() {
  static const bim::Storey big = tiled(test::officeWorld().building().storeys[0], 2);
  return big;
}

// The planes seen from the case's pose (in the first tile), as the filter observes them.
std::vector<Observation> bruteView(const BruteCase& c) {
  const bim::Room* room = test::officeWorld().building().storeys[0].findRoom(c.room);
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  return observations(test::wallsSeenFrom(test::pose(room->centre.x() + c.dx, room->centre.y() + c.dy, c.yaw), mount), mount);
}

}  // namespace

TEST(HypothesesBrute, GlobalSearchFitsWithinTheMarginAreThoseOfBruteForce) {
  // proposeEveryFit's search: every face of a 2 x 2 tiling of the default world (look-alikes in
  // every tile), the fits within 1.5 gates of the best.
  const RoomIndex indexed(bruteFloor(), false);
  const RoomIndex brute(bruteFloor(), false, true, 0.5, /*index_faces=*/false);
  pf::ParticleFilterConfig config;
  config.use_rooms = false;
  const double wanted = 1.5 * config.gate_mahalanobis2;
  for (const auto& c : kBruteCases) {
    const auto obs = bruteView(c);
    const auto want = bruteHypotheses(obs, 0.5, indexed, config, brute.landmarks(0), std::numeric_limits<std::size_t>::max());
    ASSERT_FALSE(want.empty()) << c.room;
    std::size_t n = 0;
    while (n < want.size() && want[n].log_likelihood >= want.front().log_likelihood - wanted) ++n;
    EXPECT_GE(n, 4u) << c.room << ": every tile's look-alike is within the margin";
    const auto got = poseHypotheses(obs, 0.5, indexed, config, std::numeric_limits<std::size_t>::max(), wanted, false);
    expectSame(got, want, n, c.room);
    for (std::size_t k = n; k < got.size(); ++k) EXPECT_LT(got[k].log_likelihood, want.front().log_likelihood - wanted) << c.room;
  }
}

TEST(HypothesesBrute, SeedsOverEveryRoomAreThoseOfBruteForce) {
  // seedHypotheses: each room's faces (and its neighbours'), every hypothesis kept, up to the
  // filter's 1000.
  const RoomIndex rooms(bruteFloor(), true);
  pf::ParticleFilterConfig config;
  for (const auto& c : kBruteCases) {
    const auto obs = bruteView(c);
    const auto max_count = static_cast<std::size_t>(config.max_hypotheses);
    const auto want = bruteHypotheses(obs, 0.5, rooms, config, {}, max_count);
    const auto got = poseHypotheses(obs, 0.5, rooms, config, max_count);
    EXPECT_GE(want.size(), 4u) << c.room;
    EXPECT_EQ(got.size(), want.size()) << c.room;
    expectSame(got, want, std::min(got.size(), want.size()), c.room);
  }
}

TEST(HypothesesBrute, SeedsOfRandomViewsAreThoseOfBruteForce) {
  // Twelve views drawn with a fixed seed over the default world's rooms (in the first tile of
  // the 2 x 2 tiling), each one's seeds over every room against brute force: the seeds' own
  // shortcuts (pairs passed over at their angle or height, each (observation, face) heading
  // worked out once, a pose solved twice scored once) keep every hypothesis, to the bit.
  const RoomIndex rooms(bruteFloor(), true);
  pf::ParticleFilterConfig config;
  const auto max_count = static_cast<std::size_t>(config.max_hypotheses);
  const auto& office = test::officeWorld().building().storeys[0];
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  std::mt19937 rng(24101);
  std::uniform_real_distribution<double> offset(-0.4, 0.4), heading(-M_PI, M_PI);
  int with_seeds = 0;
  for (int k = 0; k < 12; ++k) {
    const bim::Room& room = office.rooms[static_cast<std::size_t>(k) % office.rooms.size()];
    const double x = room.centre.x() + offset(rng), y = room.centre.y() + offset(rng), yaw = heading(rng);
    const auto obs = observations(test::wallsSeenFrom(test::pose(x, y, yaw), mount), mount);
    const auto want = bruteHypotheses(obs, 0.5, rooms, config, {}, max_count);
    const auto got = poseHypotheses(obs, 0.5, rooms, config, max_count);
    const std::string what = room.name + " view " + std::to_string(k);
    EXPECT_EQ(got.size(), want.size()) << what;
    expectSame(got, want, std::min(got.size(), want.size()), what.c_str());
    with_seeds += want.empty() ? 0 : 1;
  }
  EXPECT_GE(with_seeds, 9) << "most views fix a pose";
}

TEST(HypothesesBrute, ASeedsShareOfTheRoomsIsBruteForceOverThoseRooms) {
  // seed_poses_per_weighing: after the first weighing the seeds search the rooms in turn until
  // a budget of poses is solved. Each share holds exactly brute force's hypotheses over the
  // rooms it searched; successive shares go round the storey, each room once per round; and
  // with no budget the share is the whole storey.
  const RoomIndex rooms(bruteFloor(), true);
  pf::ParticleFilterConfig config;
  const auto max_count = static_cast<std::size_t>(config.max_hypotheses);
  const int count = static_cast<int>(rooms.roomCount());
  for (const auto& c : kBruteCases) {
    const auto obs = bruteView(c);
    RoomShare whole;
    whole.next_room = 5;
    const auto all = poseHypotheses(obs, 0.5, rooms, config, max_count, std::numeric_limits<double>::infinity(), false, &whole);
    EXPECT_EQ(whole.rooms_searched, count) << c.room;
    EXPECT_EQ(whole.next_room, 5) << c.room;
    expectSame(all, poseHypotheses(obs, 0.5, rooms, config, max_count), all.size(), c.room);

    RoomShare share;
    share.poses = 8;
    std::vector<int> times(static_cast<std::size_t>(count), 0);
    int calls = 0, searched = 0;
    while (searched < count) {
      std::vector<char> in(static_cast<std::size_t>(count), 0);
      const int first = share.next_room;
      const auto got = poseHypotheses(obs, 0.5, rooms, config, max_count, std::numeric_limits<double>::infinity(), false, &share);
      ASSERT_GE(share.rooms_searched, 1) << c.room;
      for (int k = 0; k < share.rooms_searched; ++k) {
        in[static_cast<std::size_t>((first + k) % count)] = 1;
        if (searched + k < count) ++times[static_cast<std::size_t>((first + k) % count)];  // the first round
      }
      EXPECT_EQ(share.next_room, (first + share.rooms_searched) % count) << c.room;
      searched += share.rooms_searched, ++calls;
      const auto want = bruteHypotheses(obs, 0.5, rooms, config, {}, max_count, &in);
      EXPECT_EQ(got.size(), want.size()) << c.room << " share " << calls;
      expectSame(got, want, std::min(got.size(), want.size()), c.room);
    }
    EXPECT_GE(calls, 2) << c.room << ": a budget of 8 poses takes several shares";
    for (int r = 0; r < count; ++r) EXPECT_EQ(times[static_cast<std::size_t>(r)], 1) << c.room << " room " << r;
  }
}
