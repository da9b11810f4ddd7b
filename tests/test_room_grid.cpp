// The planner's room grid (sim/base/room_lookup.hpp) against the scan over every room: the same
// room (the first in the storey's order) for every point, on footprints drawn at random
// (overlapping, concave, shared edges, far from the origin), queried on vertices, on edges, just
// outside bounding boxes and anywhere; then on the default world and the shared real plans.
// And the localizer's room box (RoomIndex::mayBeIn) against its roomAt.
#include "test_support.hpp"

#include "pf/room_index.hpp"
#include "sim/base/room_lookup.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace bimloc;

namespace {

// Random rooms: grid rectangles sharing edges, L shapes, and star polygons (concave, any angle).
bim::Storey randomStorey(std::mt19937_64& rng, const Eigen::Vector2d& offset) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  bim::Storey s;
  const int n = 5 + static_cast<int>(u(rng) * 60);
  for (int i = 0; i < n; ++i) {
    bim::Room r;
    const Eigen::Vector2d o = offset + Eigen::Vector2d(std::floor(u(rng) * 12) * 4.0, std::floor(u(rng) * 8) * 4.0);
    const int kind = i % 3;
    if (kind == 0) {  // a rectangle on the 4 m grid: edges shared with its neighbours
      r.footprint = {o, o + Eigen::Vector2d(4, 0), o + Eigen::Vector2d(4, 4), o + Eigen::Vector2d(0, 4)};
    } else if (kind == 1) {  // an L
      const double a = 1 + 5 * u(rng), b = 1 + 5 * u(rng);
      r.footprint = {o, o + Eigen::Vector2d(2 * a, 0), o + Eigen::Vector2d(2 * a, b), o + Eigen::Vector2d(a, b),
                     o + Eigen::Vector2d(a, 2 * b), o + Eigen::Vector2d(0, 2 * b)};
    } else {  // a star: concave, edges at any angle
      const int k = 3 + static_cast<int>(u(rng) * 9);
      for (int j = 0; j < k; ++j) {
        const double t = 2 * M_PI * j / k, rad = 0.5 + 6 * u(rng);
        r.footprint.push_back(o + rad * Eigen::Vector2d(std::cos(t), std::sin(t)));
      }
    }
    r.name = "R" + std::to_string(i);
    s.rooms.push_back(r);
  }
  return s;
}

void expectSameRooms(const bim::Storey& storey, std::mt19937_64& rng, int random_points, const std::string& what) {
  const sim::RoomGrid grid(storey);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  std::vector<Eigen::Vector2d> points;
  for (const auto& r : storey.rooms)
    for (std::size_t i = 0; i < r.footprint.size(); ++i) {
      const Eigen::Vector2d& a = r.footprint[i];
      const Eigen::Vector2d& b = r.footprint[(i + 1) % r.footprint.size()];
      lo = lo.cwiseMin(a), hi = hi.cwiseMax(a);
      // Vertices, edge points, and a hair either side of them: where rounding decides.
      for (const double t : {0.0, 0.5, 0.25})
        for (const double e : {0.0, 1e-12, -1e-12, 1e-7, -1e-7}) {
          const Eigen::Vector2d p = a + t * (b - a);
          points.push_back(p + Eigen::Vector2d(e, 0)), points.push_back(p + Eigen::Vector2d(0, e));
        }
    }
  if (storey.rooms.empty()) lo = hi = Eigen::Vector2d::Zero();
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  for (int k = 0; k < random_points; ++k)
    points.emplace_back(lo.x() + u(rng) * (hi.x() - lo.x() + 1), lo.y() + u(rng) * (hi.y() - lo.y() + 1));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(nan, 0), Eigen::Vector2d(0, nan), Eigen::Vector2d(inf, 0),
                                   Eigen::Vector2d(-inf, -inf), Eigen::Vector2d(1e12, -1e12)})
    points.push_back(p);
  int inside = 0;
  for (const auto& p : points) {
    const bim::Room* expected = sim::roomAt(storey, p);
    ASSERT_EQ(grid.at(p), expected) << what << " at (" << p.x() << ", " << p.y() << ")";
    inside += expected != nullptr;
  }
  if (!storey.rooms.empty()) {
    EXPECT_GT(inside, 0) << what << ": the comparison is not of empty lookups";
  }
}

}  // namespace

TEST(RoomGrid, SameRoomAsTheScanOverEveryRoomOnRandomFootprints) {
  std::mt19937_64 rng(11);
  for (int k = 0; k < 60; ++k) {
    // Near the origin, and far from it (a site's coordinates in metres from a survey point).
    const Eigen::Vector2d offset = k % 2 == 0 ? Eigen::Vector2d(-20, -10) : Eigen::Vector2d(483211.37, 5712893.91);
    expectSameRooms(randomStorey(rng, offset), rng, 3000, "random storey " + std::to_string(k));
  }
  expectSameRooms(bim::Storey{}, rng, 100, "a storey without rooms");
}

TEST(RoomGrid, SameRoomAsTheScanOverEveryRoomOnTheWorldsAndSharedPlans) {
  std::mt19937_64 rng(5);
  const bim::Building office = bim::readIfc(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc");
  for (const auto& s : office.storeys) expectSameRooms(s, rng, 20000, "site_office " + s.name);
  for (const char* file : {"Jesse.1.ifc", "Duplex_A_20110907.ifc", "AC20-FZK-Haus.ifc"}) {
    const std::string plan = test::sharedPlan(file);
    if (plan.empty()) continue;  // ../shared/ifc absent: the random footprints above still ran
    const bim::Building b = bim::readIfc(plan);
    for (const auto& s : b.storeys) expectSameRooms(s, rng, 20000, std::string(file) + " " + s.name);
  }
}

namespace {

// Points spread over a storey's rooms' bounding box and a tenth of it beyond each side.
std::vector<Eigen::Vector2d> pointsOver(const bim::Storey& s, std::mt19937_64& rng, int count) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& r : s.rooms)
    for (const auto& p : r.footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  std::vector<Eigen::Vector2d> points;
  for (int q = 0; q < count; ++q) {
    const double x = lo.x() + u(rng) * (hi.x() - lo.x());
    points.emplace_back(x, lo.y() + u(rng) * (hi.y() - lo.y()));
  }
  return points;
}

}  // namespace

// The localizer's RoomIndex::mayBeIn, the pose hypotheses' quick test: false only where
// roomAt (footprints, then doorways) cannot give that room.
TEST(RoomGrid, TheLocalizersRoomBoxRulesOutOnlyWhatRoomAtRulesOut) {
  std::mt19937_64 rng(21);
  std::vector<bim::Storey> storeys;
  for (int k = 0; k < 20; ++k) storeys.push_back(randomStorey(rng, k % 2 ? Eigen::Vector2d(-3, 7) : Eigen::Vector2d(1e5, -2e5)));
  const bim::Building office = bim::readIfc(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc");
  storeys.push_back(office.storeys.at(0));
  int ruled_out = 0, in_room = 0;
  for (const auto& s : storeys) {
    const pf::detail::RoomIndex index(s, true);
    for (const Eigen::Vector2d& p : pointsOver(s, rng, 20000)) {
      const int room = index.roomAt(p.x(), p.y());
      for (int r = 0; r < static_cast<int>(index.roomCount()); ++r)
        if (!index.mayBeIn(r, p.x(), p.y())) {
          ASSERT_NE(room, r) << "(" << p.x() << ", " << p.y() << ")";
          ++ruled_out;
        }
      in_room += room >= 0;
    }
  }
  EXPECT_GT(ruled_out, 100000);
  EXPECT_GT(in_room, 10000);
}

// The localizer's RoomIndex::roomAt, whose cells far from every footprint edge answer without
// asking the polygons (h28speed8), against the scan over every room (the first room holding
// the point, else the first holding one of the doorway probes, as roomAt defines it): on the
// random footprints (overlapping, concave, far from the origin) and the default world.
TEST(RoomGrid, TheLocalizersRoomAtIsTheScanOverEveryRoom) {
  std::mt19937_64 rng(31);
  std::vector<bim::Storey> storeys;
  for (int k = 0; k < 30; ++k) storeys.push_back(randomStorey(rng, k % 2 ? Eigen::Vector2d(-3, 7) : Eigen::Vector2d(483211.37, 5712893.91)));
  const bim::Building office = bim::readIfc(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc");
  storeys.push_back(office.storeys.at(0));
  const auto scanned = [](const bim::Storey& s, const Eigen::Vector2d& p) {
    const auto index = [&](const Eigen::Vector2d& q) {
      const bim::Room* r = sim::roomAt(s, q);
      return r ? static_cast<int>(r - s.rooms.data()) : -1;
    };
    if (const int r = index(p); r >= 0) return r;
    for (const double step : {0.15, 0.3})
      for (const Eigen::Vector2d& d : {Eigen::Vector2d(1, 0), Eigen::Vector2d(-1, 0), Eigen::Vector2d(0, 1), Eigen::Vector2d(0, -1)})
        if (const int r = index(p + step * d); r >= 0) return r;
    return -1;
  };
  int in_room = 0;
  for (const auto& s : storeys) {
    const pf::detail::RoomIndex index(s, true);
    for (const Eigen::Vector2d& p : pointsOver(s, rng, 20000)) {
      const int room = index.roomAt(p.x(), p.y());
      ASSERT_EQ(room, scanned(s, p)) << "(" << p.x() << ", " << p.y() << ")";
      in_room += room >= 0;
    }
  }
  EXPECT_GT(in_room, 100000);
}
