// Snapshots of the particle filter: rendered off-screen (OSMesa), checked pixel by pixel
// against the plan, and written as PNG files read back by libpng.
#include "render_fixtures.hpp"
#include "test_support.hpp"

#include "sim/render/colormap.hpp"
#include "sim/render/snapshot.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <set>
#include <thread>

using namespace bimloc;
namespace fs = std::filesystem;

namespace {

const bim::Building& plan(const std::string& name) { return test::renderPlan(name); }
const bim::Storey& office() { return test::officeStorey(); }

sim::SnapshotScene officeScene() {
  sim::SnapshotScene scene;
  scene.storey = &office();
  scene.title = "site_office, test";
  scene.phase = "convergence";
  scene.time_s = 12.34;
  return scene;
}

using test::expectColour;
using test::pixelAt;
using test::readPng;
using test::Rgb;

bool wallDark(const Rgb& c) { return c.r < 90 && c.g < 90 && c.b < 90; }

// A point in the room's lower third: inside the room, well away from its name at the centre.
Eigen::Vector2d awayFromLabel(const bim::Room& room) {
  double lo = room.centre.y(), hi = lo;
  for (const auto& p : room.footprint) lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
  return {room.centre.x(), lo + 0.25 * (hi - lo)};
}

// Particles like the filter's over one run on the office: spread over every room, then in
// clusters at the same spot of each identical office, then around the true pose.
std::vector<sim::SnapshotParticle> phaseParticles(int phase, const Eigen::Vector3d& truth) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<sim::SnapshotParticle> out;
  for (int i = 0; i < 2000; ++i) {
    if (phase == 0) {
      const bim::Room& room = office().rooms[i % office().rooms.size()];
      Eigen::Vector2d lo = room.footprint[0], hi = lo;
      for (const auto& p : room.footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      out.push_back({lo.x() + u(rng) * (hi.x() - lo.x()), lo.y() + u(rng) * (hi.y() - lo.y()), 2 * M_PI * u(rng),
                     1.0 / 2000});
    } else if (phase == 1) {
      const bim::Room& room = *office().findRoom("R10" + std::to_string(1 + i % 8));  // the identical offices
      const Eigen::Vector2d offset = truth.head<2>() - office().findRoom("R101")->centre;
      const double dx = 0.35 * n(rng), dy = 0.35 * n(rng);
      const double likely = i % 8 == 0 || i % 8 == 5 ? 1.0 : 0.45;  // R101 and R106 lead
      const double w = likely * std::exp(-0.5 * (dx * dx + dy * dy) / (0.35 * 0.35));
      out.push_back({room.centre.x() + offset.x() + dx, room.centre.y() + offset.y() + dy, truth.z() + 0.3 * n(rng), w});
    } else {
      const double dx = 0.15 * n(rng), dy = 0.15 * n(rng);
      out.push_back({truth.x() + dx, truth.y() + dy, truth.z() + 0.05 * n(rng),
                     std::exp(-0.5 * (dx * dx + dy * dy) / (0.2 * 0.2))});
    }
  }
  return out;
}

}  // namespace

TEST(Render, TheImageIsNotBlank) {
  const sim::SnapshotOptions options{640, 480, 1.0};
  const sim::Image image = sim::renderSnapshotImage(officeScene(), options);
  ASSERT_EQ(image.width, 640);
  ASSERT_EQ(image.height, 480);
  ASSERT_EQ(image.rgb.size(), 640u * 480 * 3);
  std::set<int> colours;
  std::size_t not_white = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    colours.insert(image.rgb[i] << 16 | image.rgb[i + 1] << 8 | image.rgb[i + 2]);
    not_white += image.rgb[i] != 255 || image.rgb[i + 1] != 255 || image.rgb[i + 2] != 255;
  }
  EXPECT_GT(colours.size(), 50u);                      // walls, rooms, legend's colour bar, text
  EXPECT_GT(not_white, image.rgb.size() / 3 / 4);      // the plan fills much of the image
}

TEST(Render, WallsAreDrawnWhereThePlanPutsThem) {
  const sim::SnapshotScene scene = officeScene();
  const sim::SnapshotOptions options;
  const sim::Image image = sim::renderSnapshotImage(scene, options);
  ASSERT_GE(office().walls.size(), 12u);
  for (const auto& wall : office().walls)
    for (const double f : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      const Eigen::Vector3d p = wall.start + f * (wall.end - wall.start);
      EXPECT_TRUE(wallDark(pixelAt(image, sim::worldToPixel(scene, options, p.x(), p.y()))))
          << "wall " << wall.name << " at " << f << " of its axis";
    }
  for (const auto& room : office().rooms) {
    const Eigen::Vector2d p = awayFromLabel(room);
    const Rgb c = pixelAt(image, sim::worldToPixel(scene, options, p.x(), p.y()));
    EXPECT_FALSE(wallDark(c)) << "room " << room.name;
    EXPECT_GT(c.r, 200) << "room " << room.name << ": a light floor";
  }
  // Just outside the outer walls (in the margin): background, not wall.
  const Eigen::Vector2d outside = sim::worldToPixel(scene, options, -0.7, 6.0);
  EXPECT_FALSE(wallDark(pixelAt(image, outside)));
}

TEST(Render, EveryProjectWorldHasItsWallsDrawn) {
  const std::string dir = test::tempDir("render-worlds");
  for (const std::string name : {"site_office", "apartment", "two_storey"}) {
    const bim::Building& building = plan(name);
    for (std::size_t s = 0; s < building.storeys.size(); ++s) {
      sim::SnapshotScene scene;
      scene.storey = &building.storeys[s];
      scene.title = name + ", " + scene.storey->name;
      const sim::SnapshotOptions options{900, 700, 0.5};
      const sim::Image image = sim::renderSnapshotImage(scene, options);
      for (const auto& wall : scene.storey->walls) {
        const Eigen::Vector3d mid = 0.5 * (wall.start + wall.end);
        EXPECT_TRUE(wallDark(pixelAt(image, sim::worldToPixel(scene, options, mid.x(), mid.y()))))
            << name << " storey " << s << " wall " << wall.name;
      }
      sim::renderSnapshot(scene, dir + "/" + name + "_" + std::to_string(s) + ".png", options);
    }
  }
}

TEST(Render, TheRealPlansRenderWithTheirWalls) {
  const std::string dir = test::tempDir("render-shared");
  for (const std::string file : {"AC20-FZK-Haus.ifc", "Duplex_A_20110907.ifc", "ExampleHOM.ifc"}) {
    BIMLOC_REQUIRE_SHARED(path, file);
    const sim::World world = sim::World::fromPlan(path);
    for (std::size_t s = 0; s < world.storeyCount(); ++s) {
      sim::SnapshotScene scene;
      scene.storey = &world.building().storeys[s];
      if (scene.storey->walls.empty()) continue;
      scene.title = file + ", " + scene.storey->name;
      const sim::SnapshotOptions options;
      const sim::Image image = sim::renderSnapshotImage(scene, options);
      const double px_per_m =
          (sim::worldToPixel(scene, options, 1, 0) - sim::worldToPixel(scene, options, 0, 0)).norm();
      for (const auto& wall : scene.storey->walls) {
        if (wall.approximated || wall.thickness_m * px_per_m < 3) continue;  // no straight box, or a hairline
        const Eigen::Vector3d mid = 0.5 * (wall.start + wall.end);
        EXPECT_TRUE(wallDark(pixelAt(image, sim::worldToPixel(scene, options, mid.x(), mid.y()))))
            << file << " storey " << s << " wall " << wall.name;
      }
      sim::renderSnapshot(scene, dir + "/" + file + "_" + std::to_string(s) + ".png", options);
    }
  }
}

TEST(Render, SmallAndLargeImagesKeepThePlanInPlace) {
  const std::string dir = test::tempDir("render-sizes");
  sim::SnapshotScene scene = officeScene();
  const Eigen::Vector3d truth(2.6, 1.7, 0.8);
  scene.particles = phaseParticles(1, truth);
  scene.truth = truth;
  for (const auto& [w, h] : {std::pair{400, 300}, std::pair{700, 1000}, std::pair{2400, 1600}}) {
    const sim::SnapshotOptions options{w, h, 1.0};
    const sim::Image image = sim::renderSnapshotImage(scene, options);
    ASSERT_EQ(image.width, w);
    ASSERT_EQ(image.height, h);
    const bim::Wall& outer = office().walls.front();
    const Eigen::Vector3d mid = 0.5 * (outer.start + outer.end);
    EXPECT_TRUE(wallDark(pixelAt(image, sim::worldToPixel(scene, options, mid.x(), mid.y())))) << w << "x" << h;
    sim::renderSnapshot(scene, dir + "/" + std::to_string(w) + "x" + std::to_string(h) + ".png", options);
  }
}

TEST(Render, ParticlesAppearWherePlacedInTheirWeightColour) {
  sim::SnapshotScene scene = officeScene();
  const sim::SnapshotOptions options;
  const Eigen::Vector2d heavy = awayFromLabel(*office().findRoom("R101"));
  const Eigen::Vector2d light = awayFromLabel(*office().findRoom("R103"));
  const sim::Image before = sim::renderSnapshotImage(scene, options);
  scene.particles = {{heavy.x(), heavy.y(), 0.5, 3.0}, {light.x(), light.y(), -2.0, 1.0}};
  const sim::Image after = sim::renderSnapshotImage(scene, options);
  const Eigen::Vector2d heavy_px = sim::worldToPixel(scene, options, heavy.x(), heavy.y());
  const Eigen::Vector2d light_px = sim::worldToPixel(scene, options, light.x(), light.y());
  expectColour(pixelAt(after, heavy_px), sim::render::viridis(1.0), "the heaviest particle");
  expectColour(pixelAt(after, light_px), sim::render::viridis(0.0), "the lightest particle");
  EXPECT_GT(pixelAt(before, heavy_px).r, 200);  // it was the room's floor before
  // Elsewhere, nothing changed on the plan (the legend's weight labels did).
  const Eigen::Vector2d far = sim::worldToPixel(scene, options, 14.0, 10.0);
  EXPECT_EQ(pixelAt(before, far).r, pixelAt(after, far).r);
}

TEST(Render, ThePngIsWrittenAndReadsBack) {
  sim::SnapshotScene scene = officeScene();
  const Eigen::Vector3d truth(2.6, 1.7, 0.8);
  scene.truth = truth;
  scene.estimate = Eigen::Vector3d(2.8, 1.5, 0.9);
  scene.particles = phaseParticles(2, truth);
  const sim::SnapshotOptions options{800, 600, 1.0};
  const std::string dir = test::tempDir("render");
  const std::string path = dir + "/converged.png";
  sim::renderSnapshot(scene, path, options);
  const sim::Image back = readPng(path);
  EXPECT_EQ(back.width, 800);
  EXPECT_EQ(back.height, 600);
  const sim::Image direct = sim::renderSnapshotImage(scene, options);
  EXPECT_TRUE(back.rgb == direct.rgb) << "the PNG holds other pixels than the image rendered in memory";
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u) << "a temporary file was left next to the PNG";
}

TEST(Render, AFailedWriteThrowsNamingThePathAndLeavesNoFile) {
  const std::string dir = test::tempDir("render-fail");
  const std::string path = dir + "/missing/snapshot.png";
  try {
    sim::renderSnapshot(officeScene(), path, {320, 240, 1.0});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir + "/missing"));
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_THROW(sim::renderSnapshot(officeScene(), dir + "/tiny.png", {10, 10, 1.0}), std::runtime_error);
  EXPECT_THROW(sim::renderSnapshotImage(officeScene(), {640, 480, -1.0}), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Render, WorksFromOtherThreadsAndGivesTheSameImage) {
  const sim::SnapshotOptions options{400, 300, 0.5};
  const sim::Image here = sim::renderSnapshotImage(officeScene(), options);
  sim::Image there[2];
  std::thread a([&] { there[0] = sim::renderSnapshotImage(officeScene(), options); });
  std::thread b([&] { there[1] = sim::renderSnapshotImage(officeScene(), options); });
  a.join();
  b.join();
  EXPECT_TRUE(there[0].rgb == here.rgb);
  EXPECT_TRUE(there[1].rgb == here.rgb);
}

TEST(Render, ThePhasesOfARunAreWrittenAndABareSceneFitsItsParticles) {
  const Eigen::Vector3d truth(2.6, 1.7, 0.8);
  const std::string dir = test::tempDir("render-phases");
  const char* phases[] = {"initialization", "clustering", "convergence"};
  for (int phase = 0; phase < 3; ++phase) {
    sim::SnapshotScene scene = officeScene();
    scene.phase = phases[phase];
    scene.time_s = 4.0 * phase;
    scene.title = std::string("R101, seed 3: ") + phases[phase];
    scene.particles = phaseParticles(phase, truth);
    scene.truth = truth;
    if (phase > 0) scene.estimate = Eigen::Vector3d(phase == 1 ? 14.9 : 2.7, phase == 1 ? 9.0 : 1.6, truth.z() + 0.05);
    scene.legend_extra = {{"seed", "3"}, {"scenario", "office_loop"}, {"world", "site_office"}};
    const std::string path = dir + "/" + std::to_string(phase) + "_" + phases[phase] + ".png";
    sim::renderSnapshot(scene, path);
    EXPECT_EQ(readPng(path).width, 1200);
  }
  // No storey: the view fits the particles and poses instead of an empty default.
  sim::SnapshotScene bare;
  bare.particles = phaseParticles(2, truth);
  bare.truth = truth;
  const sim::SnapshotOptions options{400, 300, 0.2};
  const sim::Image image = sim::renderSnapshotImage(bare, options);
  expectColour(pixelAt(image, sim::worldToPixel(bare, options, truth.x(), truth.y())),
               {0x1a, 0x96, 0x41}, "the true pose's marker (green)");
}
