// Sweeps on a real Slurm (issue 29, section 6): a one-node cluster on localhost (Debian's
// slurm-wlm: slurmctld and slurmd as the current user, tests/slurm/one_node_cluster.sh), a
// 3-shard sweep submitted with deploy/slurm/submit.sh as a user submits it, and the merge
// job's merged.json compared with the unsharded run. Skips, saying why, where the cluster
// cannot start; the daemons are stopped whatever happens.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <sys/wait.h>

namespace fs = std::filesystem;
using bimloc::test::runBimloc;
using bimloc::test::tempDir;

namespace {

std::string repo() { return std::string(BIMLOC_TESTS_DIR) + "/.."; }
std::string clusterScript() { return std::string(BIMLOC_TESTS_DIR) + "/slurm/one_node_cluster.sh"; }

// A shell command's exit status and its stdout and stderr together.
std::pair<int, std::string> shell(const std::string& cmd) {
  FILE* pipe = ::popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string text;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) text.append(buffer, n);
  const int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

// Stops the cluster's daemons when the test ends, passed or failed.
struct Cluster {
  std::string dir;
  ~Cluster() { shell("bash '" + clusterScript() + "' stop '" + dir + "'"); }
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Everything the jobs logged, for a failure's message.
std::string jobLogs(const std::string& out) {
  std::string logs;
  if (!fs::is_directory(out)) return logs;
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().filename().string().rfind("slurm-", 0) == 0) logs += "--- " + e.path().string() + "\n" + slurp(e.path().string());
  return logs;
}

}  // namespace

TEST(Slurm, AOneNodeClusterRunsAShardedSweepIntoTheUnshardedReport) {
  // The cluster's files in a short path of its own (Slurm's socket and spool paths).
  const std::string dir = tempDir("slurm");
  const auto started = shell("bash '" + clusterScript() + "' start '" + dir + "'");
  Cluster cluster{dir};
  if (started.first == 77) GTEST_SKIP() << started.second;
  ASSERT_EQ(started.first, 0) << started.second;
  const std::string env = "SLURM_CONF='" + dir + "/slurm.conf' BIMLOC='" + std::string(BIMLOC_EXE) + "' PATH=$PATH:/usr/sbin ";

  // A tiny sweep: 3 start rooms, one seed, 4 s each; one scenario per shard.
  const std::string sweep = std::string("--plan '") + BIMLOC_WORLDS_DIR +
                            "/site_office.ifc' --all-rooms --rooms R108,W100,S100 --seeds 1 --duration 4";
  const auto whole = runBimloc("run " + sweep + " --json", 300.0);
  ASSERT_FALSE(whole.out.empty()) << whole.err;
  auto unsharded = nlohmann::json::parse(whole.out);
  ASSERT_EQ(unsharded["scenarios"].size(), 3u);

  const std::string out = dir + "/sweep";
  const auto submitted = shell("cd '" + repo() + "' && " + env + "sh deploy/slurm/submit.sh 3 '" + out + "' " + sweep);
  ASSERT_EQ(submitted.first, 0) << submitted.second;
  EXPECT_NE(submitted.second.find("array job "), std::string::npos) << submitted.second;
  // The merge job writes merged.json once the array has ended: wait for it to leave the queue.
  const std::string merge_id = submitted.second.substr(submitted.second.find("merge job ") + 10);
  const int merge = std::stoi(merge_id);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  bool done = false;
  while (!done && std::chrono::steady_clock::now() < deadline) {
    const auto queue = shell(env + "timeout 10 squeue -h -o %i");
    done = queue.first == 0 && queue.second.find(std::to_string(merge)) == std::string::npos;
    if (!done) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  ASSERT_TRUE(done) << "the merge job " << merge << " did not end within 300 s\n" << jobLogs(out);
  ASSERT_TRUE(fs::exists(out + "/merged.json")) << jobLogs(out);
  for (int k = 1; k <= 3; ++k) EXPECT_TRUE(fs::exists(out + "/shard-" + std::to_string(k) + "-of-3.json")) << k;
  auto merged = nlohmann::json::parse(slurp(out + "/merged.json"));
  unsharded["summary"].erase("wall_seconds"), merged["summary"].erase("wall_seconds");
  EXPECT_EQ(merged.dump(), unsharded.dump()) << jobLogs(out);
  // The array's tasks ran on the node as Slurm array tasks, one shard each.
  const std::string logs = jobLogs(out);
  EXPECT_TRUE(fs::exists(out + "/merged.txt"));
  EXPECT_NE(slurp(out + "/merged.txt").find(" of 3 localized"), std::string::npos) << logs;
}
