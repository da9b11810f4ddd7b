// All-or-nothing output of `extract --out` and `simulate --out` (issue 10, items 4-6): killed at
// every step that moves output into place (BIMLOC_FAULT_AT_RENAME), interrupted by SIGINT and
// SIGTERM, pointed at a folder of other files. The truth is a clean run's files and bytes: the
// final folder holds exactly those of one complete run, or is absent, and no staging is left.
#include "plan_mutation.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace bimloc::test;

namespace {

using Files = std::map<std::string, std::string>;  // relative path -> bytes

Files filesOf(const std::string& dir) {
  Files files;
  if (!fs::exists(dir)) return files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = slurp(e.path().string());
  return files;
}

// Hidden entries beside the output: staging folders, temporary files.
std::vector<std::string> leftovers(const std::string& parent) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(parent))
    if (e.path().filename().string()[0] == '.') names.push_back(e.path().filename().string());
  return names;
}

std::string scenario(const std::string& dir, double duration_s) {
  const std::string path = dir + "/s" + std::to_string(static_cast<int>(duration_s)) + ".yaml";
  std::ofstream(path) << "name: short tour\nworld: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                      << "start: {room: R101, yaw_deg: 90}\nmotion: {type: tour, rooms: [C100]}\n"
                      << "duration_s: " << duration_s << "\nodometry: {preset: legged}\nseed: 5\n";
  return path;
}

struct FaultAt {
  explicit FaultAt(int step) { ::setenv("BIMLOC_FAULT_AT_RENAME", std::to_string(step).c_str(), 1); }
  ~FaultAt() { ::unsetenv("BIMLOC_FAULT_AT_RENAME"); }
};

// Puts `files` in `dir` (absent when there are none).
void restore(const std::string& dir, const Files& files) {
  fs::remove_all(dir);
  for (const auto& [name, bytes] : files) {
    fs::create_directories(fs::path(dir) / fs::path(name).parent_path());
    writeFile(dir, name, bytes);
  }
}

// Kills `command` (whose output folder is OUT) at step 1, 2, ... until a run gets through.
// Before each run the folder holds `before` (nothing, or an earlier output); after a kill it
// must hold `before` or `after` exactly; the run that gets through leaves `after` and no
// staging (it removed those of the killed runs). Returns the number of steps.
int killAtEveryStep(const std::string& command, const std::string& out, const Files& before, const Files& after) {
  for (int step = 1; step < 50; ++step) {
    restore(out, before);
    CommandResult r;
    {
      FaultAt fault(step);
      r = runBimloc(command);
    }
    const Files now = filesOf(out);
    EXPECT_TRUE(now == before || now == after) << "killed at step " << step << ": a partial folder of "
                                               << now.size() << " files";
    if (r.exit_code == 0) {
      EXPECT_EQ(now, after);
      EXPECT_EQ(leftovers(fs::path(out).parent_path().string()), std::vector<std::string>{}) << step;
      return step - 1;
    }
    EXPECT_EQ(r.signal, SIGKILL) << "step " << step << " was not killed: " << r.err;
  }
  ADD_FAILURE() << "never got through";
  return -1;
}

}  // namespace

TEST(OutputCommit, ExtractKilledAtEveryRenameLeavesAWholeOutputOrNone) {
  BIMLOC_REQUIRE_SHARED(plan, "revit_quantities.ifc");
  const std::string other = sharedPlan("example.ifc");
  const std::string dir = tempDir("commit");
  const std::string out = dir + "/out/plan";
  ASSERT_EQ(runBimloc("extract '" + other + "' --out '" + dir + "/old'").exit_code, 0);
  ASSERT_EQ(runBimloc("extract '" + plan + "' --out '" + dir + "/new'").exit_code, 0);
  const Files old_files = filesOf(dir + "/old"), new_files = filesOf(dir + "/new");
  ASSERT_GE(new_files.size(), 3u);
  const std::string command = "extract '" + plan + "' --out '" + out + "'";
  EXPECT_GE(killAtEveryStep(command, out, {}, new_files), 4);  // 3 files, 1 folder
  // Over an earlier extraction of another plan: replaced whole, never mixed (issue 10, item 6).
  EXPECT_GE(killAtEveryStep(command, out, old_files, new_files), 5);  // and the old one removed
}

TEST(OutputCommit, SimulateKilledAtEveryRenameLeavesAWholeDatasetOrNone) {
  const std::string dir = tempDir("commit");
  const std::string scenario_path = scenario(dir, 1.0);
  ASSERT_EQ(runBimloc("simulate '" + scenario_path + "' --out '" + dir + "/new' --quiet").exit_code, 0);
  const Files new_files = filesOf(dir + "/new");
  ASSERT_GE(new_files.size(), 14u);
  const std::string out = dir + "/out/data";
  const std::string command = "simulate '" + scenario_path + "' --out '" + out + "' --quiet";
  EXPECT_GE(killAtEveryStep(command, out, {}, new_files), 3);
  Files old_files = new_files;
  old_files.erase("clouds/000009.pcd");  // an earlier, shorter dataset
  old_files["metadata.json"] = R"({"format": "bimloc.dataset", "version": 1})";
  EXPECT_GE(killAtEveryStep(command, out, old_files, new_files), 4);
}

TEST(OutputCommit, AFolderOfOtherFilesIsRefusedByBothCommands) {
  BIMLOC_REQUIRE_SHARED(plan, "revit_quantities.ifc");
  const std::string dir = tempDir("commit");
  writeFile(dir, "notes.txt", "mine\n");
  for (const std::string& command : {"extract '" + plan + "' --out '" + dir + "'",
                                     "simulate '" + scenario(tempDir("commit"), 1.0) + "' --out '" + dir + "'"}) {
    const auto r = runBimloc(command);
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_NE(r.err.find(dir + ": already exists and is not an earlier"), std::string::npos) << r.err;
    EXPECT_EQ(filesOf(dir), (Files{{"notes.txt", "mine\n"}}));
  }
}

// A staging folder left by a process that is gone (SIGKILL) is removed by the next run of the
// same output; one of a process that still runs (this test) is not.
TEST(OutputCommit, StaleStagingOfADeadProcessIsRemovedByTheNextRun) {
  BIMLOC_REQUIRE_SHARED(plan, "revit_quantities.ifc");
  const std::string dir = tempDir("commit");
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string stale = dir + "/.plan.staging-" + std::to_string(dead) + "-abcdef";
  const std::string alive = dir + "/.plan.staging-" + std::to_string(::getpid()) + "-abcdef";
  const std::string other = dir + "/.other.staging-" + std::to_string(dead) + "-abcdef";
  for (const auto& d : {stale, alive, other}) writeFile((fs::create_directories(d), d), "building.json", "{}");
  ASSERT_EQ(runBimloc("extract '" + plan + "' --out '" + dir + "/plan'").exit_code, 0);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(alive));
  EXPECT_TRUE(fs::exists(other));  // another output's: not this run's business
}

// SIGINT and SIGTERM during a long simulation: exit 130 and 143, nothing left behind.
TEST(OutputCommit, SigintAndSigtermRemoveTheStagingFolderAndExit130And143) {
  const std::string dir = tempDir("commit");
  const std::string scenario_path = scenario(dir, 60.0);
  for (const int signal : {SIGINT, SIGTERM}) {
    const std::string out = dir + "/out";
    const pid_t child = ::fork();
    if (child == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1);
      ::dup2(null, 2);
      ::execl(BIMLOC_EXE, BIMLOC_EXE, "simulate", scenario_path.c_str(), "--out", out.c_str(), "--quiet", nullptr);
      ::_exit(127);
    }
    // Wait for the staging folder (the world is loaded, turns are being cast), then interrupt.
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (leftovers(dir).empty() && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(leftovers(dir).size(), 1u);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    ::kill(child, signal);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal);
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
  }
}
