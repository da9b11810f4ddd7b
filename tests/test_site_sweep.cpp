// The robustness sweep: `bimloc sweep --sites ... --methods ...` gives one row per preset and
// method, with the counts of its runs adding up, writes its PNG, and refuses a preset typo.
#include "test_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <filesystem>

namespace bimloc::sim {
namespace {

namespace fs = std::filesystem;

TEST(SiteSweep, OneRowPerPresetAndMethodAndAPlot) {
  const std::string dir = test::tempDir("site-sweep");
  const std::string office = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";
  const auto r = test::runBimloc("sweep '" + office + "' --rooms-per-storey 1 --seeds 1 --duration 4 --sites exact,heavy " +
                                 "--methods pf,pf-no-rooms --plot '" + dir + "/r.png' --json --jobs 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  ASSERT_EQ(out["rows"].size(), 4u);
  const char* order[4][2] = {{"exact", "pf"}, {"exact", "pf-no-rooms"}, {"heavy", "pf"}, {"heavy", "pf-no-rooms"}};
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& row = out["rows"][i];
    EXPECT_EQ(row["site"], order[i][0]);
    EXPECT_EQ(row["method"], order[i][1]);
    EXPECT_EQ(row["runs"], 1);
    EXPECT_LE(row["localized"].get<int>() + row["false_convergences"].get<int>(), 1);
    for (const char* key : {"rate", "median_convergence_s", "p90_convergence_s", "median_ate_m", "losses", "deviation_m"})
      EXPECT_TRUE(row.contains(key)) << key;
  }
  EXPECT_EQ(out["rows"][2]["deviation_m"], 0.2);
  EXPECT_EQ(out["scenarios"].size(), 4u);
  ASSERT_TRUE(fs::exists(dir + "/r.png"));
  EXPECT_GT(fs::file_size(dir + "/r.png"), 2000u);

  const auto bad = test::runBimloc("sweep '" + office + "' --sites exact,constrution --methods pf --duration 4");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("did you mean 'construction'?"), std::string::npos) << bad.err;
}

// --oracle reaches the robustness sweep's runs: each row and each run carry the oracle's fields,
// and the table its columns (it was ignored there before).
TEST(SiteSweep, OracleFieldsInEveryRowAndRun) {
  const std::string office = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";
  const std::string sweep = "sweep '" + office + "' --rooms-per-storey 1 --seeds 1 --duration 3 --sites exact --methods pf --oracle";
  const auto r = test::runBimloc(sweep + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  ASSERT_EQ(out["rows"].size(), 1u);
  for (const char* key : {"decidable", "decidable_localized", "median_decision_lag_s", "median_oracle_seconds", "decidable_robust",
                          "median_decision_lag_robust_s", "p90_decision_ratio_robust", "robust_oracle_cpu_seconds"})
    EXPECT_TRUE(out["rows"][0].contains(key)) << key;
  ASSERT_EQ(out["scenarios"].size(), 1u);
  for (const char* key : {"decidable_at_s", "decidable_robust_at_s", "decision_lag_robust_s", "decision_ratio_robust", "oracle"})
    EXPECT_TRUE(out["scenarios"][0].contains(key)) << key;
  const auto table = test::runBimloc(sweep);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("dec. localized"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("oracle [s/run]"), std::string::npos) << table.out;
}

}  // namespace
}  // namespace bimloc::sim
