// The error plot of a run: a known series must land on the pixels the plot's own axes give
// for it (the axes themselves checked against their edges and decades), the states shaded,
// the convergence line where it converged, and the PNG written atomically, byte for byte
// the same for the same input.
#include "render_fixtures.hpp"
#include "test_support.hpp"

#include "sim/render/error_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace bimloc;
using test::expectColour;
using test::pixelAt;
using test::rgbBytes;
namespace fs = std::filesystem;

namespace {

using S = sim::ErrorPlotState;

// 20 s at 10 Hz: 0.5 m / 20 deg off while searching, then 0.02 m / 0.3 deg. Declared
// converged at 11 s, lost from 15 to 17 s.
sim::ErrorPlotData knownSeries() {
  sim::ErrorPlotData d;
  d.title = "known series";
  d.convergence_time_s = 11.0;
  for (int i = 0; i <= 200; ++i) {
    const double t = 0.1 * i;
    const S state = t < 11 - 1e-9 ? S::Searching : (t >= 15 - 1e-9 && t < 17 - 1e-9) ? S::Lost : S::Tracking;
    d.samples.push_back({t, t < 10 - 1e-9 ? 0.5 : 0.02, t < 10 - 1e-9 ? 20.0 : 0.3, state});
  }
  return d;
}

const sim::ErrorPlotOptions kOptions{900, 600};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(ErrorPlot, TheAxesSpanTheRunAndWholeDecadesOfTheErrors) {
  const sim::ErrorPlotLayout l = sim::errorPlotLayout(knownSeries(), kOptions);
  EXPECT_DOUBLE_EQ(l.position.value_min, 0.01);  // 0.02 .. 0.5 m
  EXPECT_DOUBLE_EQ(l.position.value_max, 1.0);
  EXPECT_DOUBLE_EQ(l.yaw.value_min, 0.1);  // 0.3 .. 20 deg
  EXPECT_DOUBLE_EQ(l.yaw.value_max, 100.0);
  for (const sim::ErrorPlotPanel* p : {&l.position, &l.yaw}) {
    EXPECT_DOUBLE_EQ(p->time_min, 0.0);
    EXPECT_NEAR(p->time_max, 20.0, 1e-9);
    // Corners: (0, bottom decade) bottom left, (20 s, top decade) top right.
    EXPECT_NEAR((p->toPixel(0, p->value_min) - Eigen::Vector2d(p->x0, p->y1)).norm(), 0, 1e-9);
    EXPECT_NEAR((p->toPixel(20, p->value_max) - Eigen::Vector2d(p->x1, p->y0)).norm(), 0, 1e-9);
    // Linear in time, logarithmic in error: 5 s is a quarter across, each decade as tall.
    EXPECT_NEAR(p->toPixel(5, 1).x(), p->x0 + 0.25 * (p->x1 - p->x0), 1e-9);
    const double decade = (p->y1 - p->y0) / std::log10(p->value_max / p->value_min);
    EXPECT_NEAR(p->toPixel(0, 10 * p->value_min).y(), p->y1 - decade, 1e-9);
    EXPECT_NEAR(p->toPixel(0, p->value_min / 100).y(), p->y1, 1e-9);  // below the axis: on its edge
  }
  EXPECT_LT(l.position.y1, l.yaw.y0);  // position above yaw, apart
  EXPECT_GT(l.position.y1 - l.position.y0, 0.25 * kOptions.height_px);
  ASSERT_GE(l.time_ticks.size(), 3u);
  EXPECT_DOUBLE_EQ(l.time_ticks.front(), 0.0);
}

TEST(ErrorPlot, TheCurvesStatesAndConvergenceAreWhereTheAxesPutThem) {
  const sim::ErrorPlotData data = knownSeries();
  const sim::ErrorPlotLayout l = sim::errorPlotLayout(data, kOptions);
  const sim::Image image = sim::renderErrorPlotImage(data, kOptions);
  ASSERT_EQ(image.width, 900);
  ASSERT_EQ(image.height, 600);
  const auto position = rgbBytes(sim::kErrorPlotPositionRgb), yaw = rgbBytes(sim::kErrorPlotYawRgb);
  for (const double t : {1.0, 4.3, 8.0}) {
    expectColour(pixelAt(image, l.position.toPixel(t, 0.5)), position, "0.5 m at t=" + std::to_string(t));
    expectColour(pixelAt(image, l.yaw.toPixel(t, 20)), yaw, "20 deg at t=" + std::to_string(t));
  }
  for (const double t : {12.0, 16.0, 19.5}) {
    expectColour(pixelAt(image, l.position.toPixel(t, 0.02)), position, "0.02 m at t=" + std::to_string(t));
    expectColour(pixelAt(image, l.yaw.toPixel(t, 0.3)), yaw, "0.3 deg at t=" + std::to_string(t));
  }
  // Off the curve: the state's shade (values between grid lines, times off the ticks).
  const struct {
    double t;
    std::uint32_t shade;
  } shades[] = {{3.5, sim::kErrorPlotSearchingRgb}, {12.5, sim::kErrorPlotTrackingRgb},
                {16.5, sim::kErrorPlotLostRgb}, {18.5, sim::kErrorPlotTrackingRgb}};
  for (const auto& s : shades) {
    expectColour(pixelAt(image, l.position.toPixel(s.t, 0.15)), rgbBytes(s.shade), "shade at t=" + std::to_string(s.t));
    expectColour(pixelAt(image, l.yaw.toPixel(s.t, 3.5)), rgbBytes(s.shade), "yaw shade at t=" + std::to_string(s.t));
  }
  // The convergence line at 11 s, in both panels; the old error is not there any more.
  for (const sim::ErrorPlotPanel* p : {&l.position, &l.yaw}) {
    const double mid = std::sqrt(p->value_min * p->value_max) * 1.3;
    expectColour(pixelAt(image, p->toPixel(11.0, mid)), rgbBytes(sim::kErrorPlotConvergenceRgb), "convergence line");
  }
  expectColour(pixelAt(image, l.position.toPixel(12.0, 0.5)), rgbBytes(sim::kErrorPlotTrackingRgb), "no 0.5 m after 10 s");
  // A tick below the time axis at each labelled time, none between.
  const double below = l.yaw.y1 + 0.4 * l.pad + 1;  // half way down the ticks
  const test::Rgb tick = pixelAt(image, {l.yaw.toPixel(l.time_ticks[1], 1).x(), below});
  EXPECT_LT(tick.r, 120) << "tick at " << l.time_ticks[1] << " s";
  const double between = 0.5 * (l.time_ticks[1] + l.time_ticks[2]);
  EXPECT_GT(pixelAt(image, {l.yaw.toPixel(between, 1).x(), below}).r, 240);
}

TEST(ErrorPlot, WrittenAtomicallyAndTheSameBytesForTheSameInput) {
  const std::string dir = test::tempDir("error-plot");
  sim::renderErrorPlot(knownSeries(), dir + "/a.png", kOptions);
  sim::renderErrorPlot(knownSeries(), dir + "/b.png", kOptions);
  const std::string a = slurp(dir + "/a.png");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_EQ(a, slurp(dir + "/b.png"));
  EXPECT_TRUE(test::readPng(dir + "/a.png").rgb == sim::renderErrorPlotImage(knownSeries(), kOptions).rgb);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 2u) << "a temporary file was left behind";
  // A folder that does not exist: an error naming the path, and nothing written.
  const std::string missing = dir + "/missing/errors.png";
  try {
    sim::renderErrorPlot(knownSeries(), missing, kOptions);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir + "/missing"));
  EXPECT_THROW(sim::renderErrorPlot(knownSeries(), dir + "/tiny.png", {50, 50}), std::runtime_error);
  EXPECT_FALSE(fs::exists(dir + "/tiny.png"));
}

TEST(ErrorPlot, EmptyAndNonFiniteSeriesStillDraw) {
  sim::ErrorPlotData empty;
  EXPECT_EQ(sim::renderErrorPlotImage(empty, {300, 200}).width, 300);
  sim::ErrorPlotData odd = knownSeries();
  odd.samples[5].position_m = std::nan("");
  odd.samples[6].yaw_deg = std::numeric_limits<double>::infinity();  // drawn on the top edge
  odd.samples[7].position_m = 0;                                      // on the bottom edge
  odd.convergence_time_s.reset();
  const sim::ErrorPlotLayout l = sim::errorPlotLayout(odd, kOptions);
  EXPECT_DOUBLE_EQ(l.position.value_min, 0.01);
  const sim::Image image = sim::renderErrorPlotImage(odd, kOptions);
  expectColour(pixelAt(image, l.position.toPixel(12.0, 0.02)), rgbBytes(sim::kErrorPlotPositionRgb), "0.02 m");
}
