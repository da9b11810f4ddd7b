// `bimloc compare`: each method's column is what `bimloc run --method M` gives for the same
// scenario (the same inputs, one scorer), N.L. for a method that never converges, the
// documented JSON, the same output whatever --jobs, figures that decode, clear errors; and the
// bar chart's bars where its own frame says they are, in the colours it says.
#include "render_fixtures.hpp"
#include "test_support.hpp"

#include "sim/render/compare_plots.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using bimloc::test::runBimloc;
using bimloc::test::tempDir;

namespace {

const std::string kOfficePlan = std::string("--plan '") + BIMLOC_WORLDS_DIR + "/site_office.ifc'";
const std::string kOffice = kOfficePlan + " --storey 'Ground floor'";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json parse(const bimloc::test::CommandResult& r) {
  EXPECT_EQ(r.exit_code, 0) << r.err;
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\n" << r.out << r.err;
    return nlohmann::json::object();
  }
}

}  // namespace

// S100, seed 1 converges after about 6 s with both (the filter is the same until then).
TEST(Compare, EachMethodGetsWhatRunGivesForTheSameScenario) {
  const std::string common = kOffice + " --duration 10";
  const auto compared = parse(runBimloc("compare " + common + " --rooms S100 --methods sgraph,pf --json"));
  // The documented object.
  for (const char* key : {"format", "version", "plan", "storey", "site", "duration_s", "seeds", "methods", "rooms",
                          "summary", "errors", "timing"})
    EXPECT_TRUE(compared.contains(key)) << key;
  EXPECT_EQ(compared["format"], "bimloc.compare");
  EXPECT_EQ(compared["methods"], nlohmann::json({"sgraph", "pf"}));
  ASSERT_EQ(compared["rooms"].size(), 1u);
  EXPECT_EQ(compared["rooms"][0]["room"], "S100");
  ASSERT_EQ(compared["rooms"][0]["runs"].size(), 1u);
  const auto& run = compared["rooms"][0]["runs"][0];
  EXPECT_EQ(run["seed"], 1);
  EXPECT_TRUE(run["error"].is_null());
  for (const char* method : {"sgraph", "pf"}) {
    SCOPED_TRACE(method);
    const auto single = parse(runBimloc("run " + common + " --all-rooms --rooms S100 --method " + method + " --json"));
    ASSERT_EQ(single["scenarios"].size(), 1u);
    const auto& want = single["scenarios"][0];
    const auto& got = run["methods"][method];
    for (const char* key : {"converged", "convergence_time_s", "false_convergence", "ate_m", "rpe_m_per_m", "map_rmse_m",
                            "position_error_m", "yaw_error_deg", "found_room", "true_room", "losses", "warnings"})
      EXPECT_EQ(got[key].dump(), want[key].dump()) << key;  // bit for bit: the same doubles
    EXPECT_TRUE(got["converged"]) << "the test wants a run that localizes";
    const auto& s = compared["summary"][method];
    EXPECT_EQ(s["runs"], 1);
    EXPECT_EQ(s["localized"], single["summary"]["localized"]);
    EXPECT_EQ(s["median_convergence_s"].dump(), single["summary"]["median_convergence_s"].dump());
    EXPECT_EQ(s["median_ate_m"].dump(), single["summary"]["median_ate_m"].dump());
    EXPECT_TRUE(compared["timing"]["localizer_seconds"].contains(method));
  }
}

// A filter that can never be sure enough (its particles would have to gather within a
// micrometre) never converges: N.L. in both tables, nothing to take a median of, and no error.
// (The same runs converge after about 6 s with the defaults.)
TEST(Compare, AMethodThatNeverConvergesIsMarkedNotLocalized) {
  const std::string dir = tempDir("compare");
  std::ofstream(dir + "/never.yaml") << "pf: {converged_position_m: 0.000001, converged_updates: 1000}\n";
  const auto r = runBimloc("compare " + kOffice + " --rooms S100 --seeds 2 --methods pf,pf-no-rooms --duration 8 --config '" +
                           dir + "/never.yaml'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // Every cell of both tables: one N.L. per seed; the summary counts none localized.
  const auto count = [](const std::string& line, const std::string& what) {
    int n = 0;
    for (std::size_t at = line.find(what); at != std::string::npos; at = line.find(what, at + 1)) ++n;
    return n;
  };
  std::istringstream lines(r.out);
  int marked_rows = 0, summary_rows = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("S100 ", 0) == 0) {
      EXPECT_EQ(count(line, "N.L. / N.L."), 2) << line;
      ++marked_rows;
    }
    if (line.rfind("pf ", 0) == 0 || line.rfind("pf-no-rooms ", 0) == 0) {  // the table per method
      EXPECT_EQ(count(line, " 0/2 "), 1) << line;
      EXPECT_EQ(count(line, "*"), 0) << "nothing localized, nothing best: " << line;
      ++summary_rows;
    }
  }
  EXPECT_EQ(marked_rows, 2) << r.out;
  EXPECT_EQ(summary_rows, 2) << r.out;
  EXPECT_NE(r.out.find("No method localized"), std::string::npos) << r.out;
  const auto j = parse(runBimloc("compare " + kOffice + " --rooms S100 --methods pf --duration 8 --json --config '" + dir +
                                 "/never.yaml'"));
  const auto& m = j["rooms"][0]["runs"][0]["methods"]["pf"];
  EXPECT_FALSE(m["converged"]);
  EXPECT_TRUE(m["convergence_time_s"].is_null());
  EXPECT_TRUE(m["ate_m"].is_null());
  EXPECT_EQ(j["summary"]["pf"]["localized"], 0);
  EXPECT_TRUE(j["summary"]["pf"]["median_convergence_s"].is_null());
}

TEST(Compare, JobsDoNotChangeTheOutputAndTheFiguresDecode) {
  const std::string dir = tempDir("compare");
  const std::string args = "compare " + kOffice + " --rooms R108,S100 --methods pf,pf-no-rooms --duration 8 --json";
  const auto one = runBimloc(args + " --jobs 1 --out '" + dir + "/one'");
  const auto two = runBimloc(args + " --jobs 2 --out '" + dir + "/two'");
  auto j1 = parse(one), j2 = parse(two);
  j1.erase("timing"), j2.erase("timing");  // the wall clock, and only it, differs
  EXPECT_EQ(j1.dump(), j2.dump());
  EXPECT_EQ(j1["rooms"].size(), 2u);
  // compare.json is the printed object.
  auto file = nlohmann::json::parse(slurp(dir + "/one/compare.json"));
  file.erase("timing");
  EXPECT_EQ(file.dump(), j1.dump());
  for (const char* png : {"convergence_times.png", "errors_over_time.png"}) {
    SCOPED_TRACE(png);
    EXPECT_EQ(slurp(dir + "/one/" + png), slurp(dir + "/two/" + png));
    const bimloc::sim::Image image = bimloc::test::readPng(dir + "/one/" + png);
    EXPECT_EQ(image.width, 1200);
    EXPECT_EQ(image.height, 700);
    EXPECT_LT(fs::file_size(dir + "/one/" + png), 200u * 1024);  // small files
  }
  // Nothing but the output in the folder: no staging leftovers beside it.
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename().string()[0] == '.';
  EXPECT_EQ(entries, 0u);
}

TEST(Compare, BadInputGetsAClearErrorAndNoOutput) {
  const std::string dir = tempDir("compare");
  const auto expectError = [](const std::string& args, const std::string& says) {
    const auto r = runBimloc("compare " + args, 60);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(r.signal, 0) << args;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << args << "\n" << r.out;
  };
  expectError(kOffice + " --all-rooms --methods sgraph,foo", "foo");
  expectError(kOffice + " --all-rooms --methods pf,pf", "'pf' given twice");
  expectError(kOffice + " --rooms NOPE", "no start room 'NOPE'");
  expectError(kOffice, "give --all-rooms or --rooms");
  expectError(kOfficePlan + " --storey Attic --all-rooms", "Attic");
  expectError("--plan '" + dir + "/missing.ifc' --all-rooms", dir + "/missing.ifc");
  // A folder of something else is not overwritten, and is refused before any run.
  fs::create_directories(dir + "/mine");
  std::ofstream(dir + "/mine/notes.txt") << "keep me\n";
  expectError(kOffice + " --all-rooms --out '" + dir + "/mine'", "is not an earlier bimloc.compare output");
  EXPECT_EQ(slurp(dir + "/mine/notes.txt"), "keep me\n");
}

// The bar chart against its own frame: each bar from the value's row down to the axis in its
// series' colour, a bar without value pale (a quarter of the colour over white) up to the top,
// a flagged one framed in red; white above a bar.
TEST(CompareFigures, BarsStandWhereTheFrameSaysInTheirColours) {
  using bimloc::sim::BarChartData;
  BarChartData data;
  data.title = "bars";
  data.value_label = "value";
  data.series = {"a", "b"};
  data.value_max = 20;
  data.groups = {{"g1", {{0, 10.0, false}, {1, std::nullopt, false}}}, {"g2", {{0, 5.0, true}, {1, 20.0, false}}}};
  const bimloc::sim::Image image = bimloc::sim::renderBarChartImage(data);
  const bimloc::sim::BarChartFrame f = bimloc::sim::barChartFrame(data);
  const auto at = [&](std::size_t g, std::size_t b, double value) {
    const auto [l, r] = f.barSpan(data, g, b);
    return bimloc::test::pixelAt(image, {0.5 * (l + r), f.rowOf(value)});
  };
  const auto rgb = [](std::uint32_t c) { return bimloc::test::rgbBytes(c); };
  bimloc::test::expectColour(at(0, 0, 7.5), rgb(bimloc::sim::seriesRgb(0)), "g1 a, inside");
  bimloc::test::expectColour(at(0, 0, 17.5), {255, 255, 255}, "g1 a, above");
  const auto b = rgb(bimloc::sim::seriesRgb(1));
  std::array<std::uint8_t, 3> pale{};
  for (int c = 0; c < 3; ++c) pale[c] = static_cast<std::uint8_t>(std::lround(0.25 * b[c] + 0.75 * 255));
  bimloc::test::expectColour(at(0, 1, 12.5), pale, "g1 b, not localized");
  bimloc::test::expectColour(at(1, 1, 17.5), b, "g2 b, full height");
  bimloc::test::expectColour(at(1, 0, 2.5), rgb(bimloc::sim::seriesRgb(0)), "g2 a, inside");
  const auto [left, right] = f.barSpan(data, 1, 0);
  bimloc::test::expectColour(bimloc::test::pixelAt(image, {left + 1.0, f.rowOf(2.5)}), rgb(bimloc::sim::kBarFlagRgb),
                             "g2 a, its frame");
  EXPECT_LT(right - left, (f.x1 - f.x0) / 2);
}
