// The S-Graph layer of the snapshots: keyframe path, matched plan walls (at their estimated
// place), new planes and room nodes, each found at the pixels of its own world coordinates.
#include "render_fixtures.hpp"

#include "sim/render/layers.hpp"
#include "sim/render/snapshot.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace bimloc;
using test::expectColour;
using test::officeStorey;
using test::pixelAt;

namespace {

std::array<std::uint8_t, 3> bytes(const sim::render::Colour& c) {
  return {static_cast<std::uint8_t>(std::lround(c.r * 255)), static_cast<std::uint8_t>(std::lround(c.g * 255)),
          static_cast<std::uint8_t>(std::lround(c.b * 255))};
}

const bim::Wall& wallNamed(const std::string& name) {
  for (const auto& w : officeStorey().walls)
    if (w.name == name) return w;
  throw std::runtime_error("no wall " + name);
}

// In the rooms' lower parts, away from their names (drawn at the centres).
const std::vector<Eigen::Vector3d> kKeyframes = {{1.0, 1.2, 0}, {1.6, 1.2, 0}, {2.2, 1.3, 0.1}, {2.8, 1.8, 0.6}};
const Eigen::Vector2d kPlaneStart(9.4, 1.2), kPlaneEnd(11.0, 1.2);  // in R103
const Eigen::Vector2d kRoomNode(6.12, 8.4), kRoomWallPoint(7.12, 8.4);  // in R106
constexpr double kShift = 0.4;  // PART-S drawn where the graph would put it, 0.4 m off the plan

sim::SnapshotScene graphScene() {
  sim::SnapshotScene scene;
  scene.storey = &officeStorey();
  scene.title = "site_office, graph";
  scene.phase = "end";
  sim::SnapshotGraph g;
  g.keyframes = kKeyframes;
  const bim::Wall& part = wallNamed("PART-S");
  const Eigen::Vector2d e = part.faces[0].plane.n.head<2>().normalized();
  g.matched_walls.push_back({part.start.head<2>() + kShift * e, part.end.head<2>() + kShift * e, part.thickness_m});
  const bim::Wall& west = wallNamed("EXT-W");
  g.matched_walls.push_back({west.start.head<2>(), west.end.head<2>(), west.thickness_m});
  g.new_planes.push_back({kPlaneStart, kPlaneEnd, 0.0});
  g.rooms.push_back({kRoomNode, {kRoomWallPoint}});
  scene.graph = g;
  return scene;
}

}  // namespace

TEST(RenderGraph, KeyframesAreOnTheirPathInThePathColour) {
  const sim::SnapshotScene scene = graphScene();
  const sim::SnapshotOptions options;
  const sim::Image image = sim::renderSnapshotImage(scene, options);
  const auto want = bytes(sim::render::keyframeColour());
  for (std::size_t i = 0; i < kKeyframes.size(); ++i) {
    const Eigen::Vector3d& k = kKeyframes[i];
    expectColour(pixelAt(image, sim::worldToPixel(scene, options, k.x(), k.y())), want, "keyframe " + std::to_string(i));
    if (i == 0) continue;
    const Eigen::Vector3d mid = 0.5 * (k + kKeyframes[i - 1]);  // the path between two keyframes
    expectColour(pixelAt(image, sim::worldToPixel(scene, options, mid.x(), mid.y())), want, "path before keyframe " + std::to_string(i));
  }
  // Beside the path (30 cm off it): the room's floor, not the path.
  const Eigen::Vector2d beside = sim::worldToPixel(scene, options, 1.3, 1.5);
  EXPECT_GT(pixelAt(image, beside).r, 200);
}

TEST(RenderGraph, ANewPlaneIsItsSegmentInItsColour) {
  const sim::SnapshotScene scene = graphScene();
  const sim::SnapshotOptions options;
  const sim::Image image = sim::renderSnapshotImage(scene, options);
  const auto want = bytes(sim::render::newPlaneColour());
  for (const double f : {0.05, 0.25, 0.5, 0.75, 0.95}) {
    const Eigen::Vector2d p = kPlaneStart + f * (kPlaneEnd - kPlaneStart);
    expectColour(pixelAt(image, sim::worldToPixel(scene, options, p.x(), p.y())), want, "new plane at " + std::to_string(f));
  }
  // Past its ends and 30 cm beside it: the floor.
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(kPlaneEnd.x() + 0.3, 1.2), Eigen::Vector2d(10.2, 1.5)})
    EXPECT_GT(pixelAt(image, sim::worldToPixel(scene, options, p.x(), p.y())).r, 200) << p.transpose();
  // Without the graph, nothing of it is drawn.
  sim::SnapshotScene bare = scene;
  bare.graph.reset();
  const sim::Image plain = sim::renderSnapshotImage(bare, options);
  const Eigen::Vector2d mid = 0.5 * (kPlaneStart + kPlaneEnd);
  EXPECT_GT(pixelAt(plain, sim::worldToPixel(bare, options, mid.x(), mid.y())).b, 200);
}

TEST(RenderGraph, MatchedWallsAreHighlightedAtTheirEstimatedPlace) {
  const sim::SnapshotScene scene = graphScene();
  const sim::SnapshotOptions options;
  const sim::Image image = sim::renderSnapshotImage(scene, options);
  const auto want = bytes(sim::render::matchedWallColour());
  const bim::Wall& part = wallNamed("PART-S");
  const Eigen::Vector2d e = part.faces[0].plane.n.head<2>().normalized();
  for (const double f : {0.2, 0.5, 0.8}) {
    const Eigen::Vector2d on_plan = (part.start + f * (part.end - part.start)).head<2>();
    const Eigen::Vector2d moved = on_plan + kShift * e;
    expectColour(pixelAt(image, sim::worldToPixel(scene, options, moved.x(), moved.y())), want, "PART-S moved");
    const test::Rgb plan = pixelAt(image, sim::worldToPixel(scene, options, on_plan.x(), on_plan.y()));
    EXPECT_TRUE(plan.r < 90 && plan.g < 90 && plan.b < 90) << "PART-S on the plan stays dark at " << f;
  }
  const bim::Wall& west = wallNamed("EXT-W");
  const Eigen::Vector3d mid = 0.5 * (west.start + west.end);
  expectColour(pixelAt(image, sim::worldToPixel(scene, options, mid.x(), mid.y())), want, "EXT-W, not moved");
}

TEST(RenderGraph, ARoomNodeAndItsEdgeToAWall) {
  const sim::SnapshotScene scene = graphScene();
  const sim::SnapshotOptions options;
  const sim::Image image = sim::renderSnapshotImage(scene, options);
  const auto want = bytes(sim::render::roomNodeColour());
  for (const double f : {0.5, 0.8, 1.0}) {
    const Eigen::Vector2d p = kRoomNode + f * (kRoomWallPoint - kRoomNode);
    expectColour(pixelAt(image, sim::worldToPixel(scene, options, p.x(), p.y())), want, "room edge at " + std::to_string(f));
  }
  EXPECT_GT(pixelAt(image, sim::worldToPixel(scene, options, 6.62, 8.8)).r, 200);  // beside the edge
  // The node is a ring around its centre (the room's name stays legible inside): going left
  // from the centre, away from the edge, the white middle, then the ring's colour.
  const Eigen::Vector2d centre = sim::worldToPixel(scene, options, kRoomNode.x(), kRoomNode.y());
  EXPECT_GT(pixelAt(image, centre).g, 200);
  int ring = 0;
  for (int dx = 1; dx <= 16; ++dx) {
    const test::Rgb c = pixelAt(image, centre - Eigen::Vector2d(dx, 0));
    ring += std::abs(c.r - want[0]) <= 10 && std::abs(c.g - want[1]) <= 10 && std::abs(c.b - want[2]) <= 10;
  }
  EXPECT_GE(ring, 2) << "no ring of the room node's colour left of its centre";
}

TEST(RenderGraph, WithoutAPlanTheViewFitsTheKeyframes) {
  sim::SnapshotScene scene;
  scene.graph = sim::SnapshotGraph{};
  scene.graph->keyframes = {{-40, 3, 0}, {-30, 3, 0}, {-30, 13, 1.5}};
  const sim::SnapshotOptions options{500, 400, 1.0};
  const sim::Image image = sim::renderSnapshotImage(scene, options);
  for (const auto& k : scene.graph->keyframes)
    expectColour(pixelAt(image, sim::worldToPixel(scene, options, k.x(), k.y())), bytes(sim::render::keyframeColour()),
                 "keyframe");
}
