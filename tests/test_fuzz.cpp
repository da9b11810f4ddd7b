// The fuzz test of issue 10: a seeded mutator (fuzz_mutator.hpp) damages the shared plans, a
// scenario and a small dataset, and every case goes through the real binary. Whatever the
// damage: no signal, no timeout; a refusal is exit 1 with a message naming the file and no
// output left; an extraction that succeeds on a plan that lost a wall, a room or a storey, or
// whose text holds a known inconsistency (a duplicate id, a dangling or self reference, a
// non-finite number), says so in a warning the clean plan does not have. The truth is the
// clean input's own result and the damage the mutator reports. Counts go to stdout.
#include "fuzz_mutator.hpp"
#include "plan_mutation.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

namespace fs = std::filesystem;
using namespace bimloc::test;

namespace {

constexpr double kTimeoutS = 60.0;

std::uint32_t seed(std::uint32_t offset) { return fuzzSeed(20261123u + offset, offset); }

struct Tally {
  int cases = 0, accepted = 0, refused = 0, warned = 0;
  bool counts_warnings = false;  // plans only: the others have no warnings to compare
  void print(const std::string& what) const {
    std::cout << "fuzz " << what << ": " << cases << " cases, " << refused << " refused, " << accepted
              << " accepted";
    if (counts_warnings) std::cout << " (" << warned << " of them with a new warning)";
    std::cout << std::endl;
  }
};

// Hidden or unexpected entries beside the output.
void expectNoOutput(const std::string& dir, const std::string& out, const std::set<std::string>& inputs,
                    const std::string& trace) {
  EXPECT_FALSE(fs::exists(out)) << trace << ": output left after a failure";
  for (const auto& e : fs::directory_iterator(dir))
    if (!inputs.count(e.path().filename().string())) ADD_FAILURE() << trace << ": left " << e.path();
}

// The common contract of every case; returns whether the input was refused. `refused_code`:
// the exit status of a refusal (1; `localize`: 2, its 1 is a run that did not localize).
bool checkRun(const CommandResult& r, const std::string& names, const std::string& trace, int refused_code = 1) {
  EXPECT_FALSE(r.timed_out) << trace;
  EXPECT_EQ(r.signal, 0) << trace << ": killed by signal " << r.signal;
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == refused_code)
      << trace << ": exit " << r.exit_code << ": " << r.err;
  if (r.exit_code == refused_code && !r.err.empty()) {
    EXPECT_NE(r.err.find(names), std::string::npos) << trace << ": the message must name " << names << ": " << r.err;
  }
  return r.exit_code == refused_code;
}

struct Baseline {
  int walls = 0, rooms = 0, storeys = 0;
  std::set<std::string> warnings;
};

// Line n (1-based) of a text.
std::string lineOf(const std::string& text, std::size_t n) {
  std::size_t at = 0;
  for (std::size_t k = 1; k < n && at != std::string::npos; ++k) at = text.find('\n', at) + 1;
  if (at == std::string::npos || at >= text.size()) return {};
  return text.substr(at, text.find('\n', at) - at);
}

Baseline baselineOf(const nlohmann::json& doc) {
  Baseline b;
  for (const auto& s : doc.value("storeys", nlohmann::json::array())) {
    b.walls += s.value("walls", 0);
    b.rooms += s.value("rooms", 0);
    ++b.storeys;
  }
  for (const auto& w : doc.value("warnings", nlohmann::json::array())) b.warnings.insert(w.get<std::string>());
  return b;
}

// `count` cases over the plans in turn, each a damage of one plan, extracted with --out.
void fuzzPlans(const std::vector<std::string>& names, int count, std::uint32_t seed, const std::string& label) {
  if (sharedPlan(names[0]).empty()) GTEST_SKIP() << "../shared/ifc not found";
  std::map<std::string, std::pair<std::string, Baseline>> plans;  // name -> (text, clean result)
  Mutator mutator(seed);
  Tally tally;
  tally.counts_warnings = true;
  const std::string dir = tempDir("fuzz-ifc");
  const std::string input = dir + "/case.ifc", out = dir + "/out";
  for (int i = 0; i < count; ++i) {
    const std::string& name = names[static_cast<std::size_t>(i) % names.size()];
    if (!plans.count(name)) plans[name] = {slurp(sharedPlan(name)), baselineOf(extractJson(sharedPlan(name)))};
    const auto& [text, clean] = plans[name];
    const Mutation m = mutator.step(text);
    const std::string trace = "case " + std::to_string(i) + ": " + name + ", " + damageName(m.damage) + " " + m.where;
    writeFile(dir, "case.ifc", m.text);
    const auto r = runBimloc("extract '" + input + "' --out '" + out + "' --json", kTimeoutS);
    ++tally.cases;
    if (checkRun(r, input, trace)) {
      ++tally.refused;
      EXPECT_FALSE(r.err.empty()) << trace;
      expectNoOutput(dir, out, {"case.ifc"}, trace);
      continue;
    }
    ++tally.accepted;
    EXPECT_TRUE(fs::exists(out + "/building.json")) << trace;
    fs::remove_all(out);
    nlohmann::json doc;
    try {
      doc = nlohmann::json::parse(r.out);
    } catch (const std::exception& e) {
      ADD_FAILURE() << trace << ": " << e.what();
      continue;
    }
    const Baseline now = baselineOf(doc);
    bool warned = false;
    for (const auto& w : now.warnings) warned |= !clean.warnings.count(w);
    tally.warned += warned;
    const bool lost = now.walls < clean.walls || now.rooms < clean.rooms || now.storeys < clean.storeys;
    EXPECT_TRUE(warned || !lost) << trace << ": lost an element without a warning (walls " << now.walls << "/"
                                 << clean.walls << ", rooms " << now.rooms << "/" << clean.rooms << ")";
    const bool inconsistent = m.damage == Damage::kDuplication || m.damage == Damage::kDanglingRef ||
                              m.damage == Damage::kSelfRef || m.damage == Damage::kNonFinite;
    EXPECT_TRUE(warned || !inconsistent) << trace << ": an inconsistency accepted without a warning";
  }
  tally.print(label);
}

}  // namespace

// Two small plans take most of the cases; the large ones (0.3-1 s each) a few each.
TEST(Fuzz, DamagedSmallPlansNeverCrashAndNeverLoseAnElementSilently) {
  fuzzPlans({"revit_quantities.ifc", "example.ifc"}, fuzzCases(220), seed(0), "small IFC plans");
}

TEST(Fuzz, DamagedLargePlansNeverCrashAndNeverLoseAnElementSilently) {
  fuzzPlans({"AC20-FZK-Haus.ifc", "Duplex_A_20110907.ifc", "ExampleHOM.ifc", "SampleHouse4.ifc", "AC11-FZK-Haus-IFC.ifc",
             "AC90R1-Jasmin-Sun-105-2x3.ifc", "Jesse.1.ifc"},
            fuzzCases(21), seed(3), "large IFC plans");
}

TEST(Fuzz, DamagedScenariosNeverCrashAndLeaveNoOutput) {
  const std::string dir = tempDir("fuzz-scenario");
  const std::string clean = std::string("name: fuzz\nworld: ") + BIMLOC_WORLDS_DIR + "/site_office.ifc\n" +
                            "start: {room: R101, yaw_deg: 90}\nmotion: {type: tour, rooms: [C100]}\n"
                            "duration_s: 0.5\nsensor: {rpm: 600, range_noise_sigma_m: 0.008}\n"
                            "odometry: {preset: legged}\nlocalizer: {particles: 500}\nseed: 5\n";
  Mutator mutator(seed(1));
  Tally tally;
  const std::string input = dir + "/case.yaml", out = dir + "/out";
  for (int i = 0; i < fuzzCases(40); ++i) {
    const Mutation m = mutator.lines(clean, true);
    const std::string trace = "case " + std::to_string(i) + ": " + damageName(m.damage) + " " + m.where;
    writeFile(dir, "case.yaml", m.text);
    const auto r = runBimloc("simulate '" + input + "' --out '" + out + "' --quiet", kTimeoutS);
    ++tally.cases;
    if (checkRun(r, input, trace)) {
      ++tally.refused;
      expectNoOutput(dir, out, {"case.yaml"}, trace);
      continue;
    }
    ++tally.accepted;
    // A number that is no number has no meaning in a scenario: never run with it.
    EXPECT_NE(m.damage, Damage::kNonFinite) << trace << ": accepted";
    EXPECT_TRUE(fs::exists(out + "/metadata.json")) << trace;
    fs::remove_all(out);
  }
  tally.print("scenarios");
}

TEST(Fuzz, DamagedDatasetsNeverCrashAndAreRefusedByName) {
  const std::string root = tempDir("fuzz-dataset");
  writeFile(root, "s.yaml", std::string("name: fuzz\nworld: ") + BIMLOC_WORLDS_DIR +
                                "/site_office.ifc\nstart: {room: R101, yaw_deg: 90}\nmotion: {type: tour, rooms: [C100]}\n"
                                "duration_s: 1\nodometry: {preset: legged}\nseed: 5\n");
  ASSERT_EQ(runBimloc("simulate '" + root + "/s.yaml' --out '" + root + "/clean' --quiet").exit_code, 0);
  const std::vector<std::string> files{"metadata.json", "clouds/index.csv", "odometry.tum", "ground_truth.tum",
                                       "clouds/000004.pcd"};
  Mutator mutator(seed(2));
  Tally tally;
  for (int i = 0; i < fuzzCases(40); ++i) {
    const std::string& file = files[mutator.below(files.size())];
    const std::string dir = root + "/case" + std::to_string(i);
    fs::copy(root + "/clean", dir, fs::copy_options::recursive | fs::copy_options::create_hard_links);
    const std::string text = slurp(dir + "/" + file);
    const bool pcd = file.size() > 4 && file.substr(file.size() - 4) == ".pcd";
    const Mutation m = mutator.lines(text, false, pcd ? 11 : 1000000);
    fs::remove(dir + "/" + file);  // a hard link: the clean dataset keeps its copy
    writeFile(dir, file, m.text);
    const std::string trace = "case " + std::to_string(i) + ": " + file + ", " + damageName(m.damage) + " " + m.where;
    const auto r = runBimloc("localize '" + dir + "' --plan '" + BIMLOC_WORLDS_DIR + "/site_office.ifc'", kTimeoutS);
    ++tally.cases;
    // Damage that leaves no usable dataset, by what the format says: a data row repeated
    // (stamps must increase), a number that is no number, a cut inside the JSON or the PCD.
    const std::size_t line = m.where.rfind("line ", 0) == 0 ? std::stoul(m.where.substr(5)) : 0;
    const bool comment = line > 0 && lineOf(text, line).rfind("#", 0) == 0;
    const bool data_row = line > 1 && !comment;
    // A TUM line that is no pose (a number not finite) is dropped and counted, not refused
    // (issue 29 §5: odometry problems are warned with counts): the warning names the dataset.
    const bool tum = file.size() > 4 && file.compare(file.size() - 4, 4, ".tum") == 0;
    const bool must_warn = m.damage == Damage::kNonFinite && !comment && tum;
    const bool must_fail =
        (m.damage == Damage::kNonFinite && !comment && !tum) ||
        (m.damage == Damage::kDuplication && !pcd && file != "metadata.json" && data_row) ||
        (m.damage == Damage::kTruncation && (pcd || file == "metadata.json") && m.text.size() + 1 < text.size());
    if (checkRun(r, dir + "/", trace, 2)) {
      ++tally.refused;
    } else {
      ++tally.accepted;
      EXPECT_FALSE(must_fail) << trace << ": a dataset that cannot be used was accepted";
    }
    if (must_fail) {
      EXPECT_NE(r.err.find(dir + "/"), std::string::npos) << trace << ": " << r.err;
    }
    if (must_warn && r.exit_code != 2) {
      EXPECT_NE(r.err.find(dir), std::string::npos) << trace << ": " << r.err;
      EXPECT_NE(r.err.find("dropped"), std::string::npos) << trace << ": " << r.err;
    }
    fs::remove_all(dir);
  }
  tally.print("datasets");
}

// A scenario's world may be a folder `extract --out` wrote: a damaged building.json or storey
// mesh (a truncated PLY crashed assimp) is refused by name, never a crash.
TEST(Fuzz, DamagedExtractFoldersNeverCrashAndAreRefusedByName) {
  const std::string root = tempDir("fuzz-world");
  ASSERT_EQ(runBimloc(std::string("extract '") + BIMLOC_WORLDS_DIR + "/site_office.ifc' --out '" + root + "/clean'").exit_code, 0);
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(root + "/clean")) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  Mutator mutator(seed(4));
  Tally tally;
  for (int i = 0; i < fuzzCases(20); ++i) {
    const std::string& file = files[mutator.below(files.size())];
    const std::string dir = root + "/case" + std::to_string(i);
    fs::create_directories(dir);
    fs::copy(root + "/clean", dir + "/world", fs::copy_options::recursive | fs::copy_options::create_hard_links);
    const std::string path = dir + "/world/" + file;
    const std::string text = slurp(path);
    const bool ply = file.find(".ply") != std::string::npos;
    const Mutation m = mutator.lines(text, false, ply ? 12 : 1000000);
    fs::remove(path);  // a hard link: the clean folder keeps its copy
    writeFile(dir + "/world", file, m.text);
    writeFile(dir, "s.yaml", "name: fuzz\nworld: " + dir + "/world\nstart: {room: R101}\nduration_s: 0.3\nseed: 5\n");
    const std::string trace = "case " + std::to_string(i) + ": " + file + ", " + damageName(m.damage) + " " + m.where;
    const auto r = runBimloc("simulate '" + dir + "/s.yaml' --out '" + dir + "/out' --quiet", kTimeoutS);
    ++tally.cases;
    if (checkRun(r, dir + "/world/", trace)) {
      ++tally.refused;
      expectNoOutput(dir, dir + "/out", {"world", "s.yaml"}, trace);
      // A mesh cut short has faces that point nowhere: never a usable world.
    } else {
      ++tally.accepted;
      EXPECT_FALSE(ply && m.damage == Damage::kTruncation && m.text.size() + 1 < text.size()) << trace << ": accepted";
    }
    fs::remove_all(dir);
  }
  tally.print("extract folders as worlds");
}
