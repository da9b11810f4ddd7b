// Sharded sweeps: the Slurm array of deploy/slurm (its scripts run locally by a stand-in for
// sbatch; each task runs deploy/run_shard.sh, as the Kubernetes pods do) for N = 3, merged by
// its merge job (`bimloc report merge`), gives exactly the unsharded run's JSON and table;
// bad shard sets are named.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <cstdio>
#include <regex>
#include <sstream>

using bimloc::test::CommandResult;
using bimloc::test::runBimloc;
using bimloc::test::tempDir;

namespace {

// A small sweep: 3 start rooms x 2 seeds of the default world, 8 s each (some converge).
std::string sweep(const std::string& duration = "8") {
  return std::string("--plan '") + BIMLOC_WORLDS_DIR + "/site_office.ifc' --all-rooms --rooms R108,W100,S100 --seeds 2 --duration " +
         duration;
}

std::string repo() { return std::string(BIMLOC_TESTS_DIR) + "/.."; }

// The array task K of N alone, as Slurm's and Kubernetes' tasks run it.
CommandResult shardTask(int k, int n, const std::string& out, const std::string& args) {
  const std::string cmd = "cd '" + repo() + "' && BIMLOC='" + std::string(BIMLOC_EXE) + "' sh deploy/run_shard.sh " +
                          std::to_string(k) + " " + std::to_string(n) + " '" + out + "' " + args + " >'" + out + "/task.log' 2>&1";
  CommandResult r;
  r.exit_code = std::system(cmd.c_str()) == 0 ? 0 : 1;
  return r;
}

// deploy/slurm/submit.sh as a user runs it, with a stand-in for Slurm's sbatch that runs each
// job at once (an array's tasks one after the other, SLURM_ARRAY_TASK_ID set) on this machine:
// the real batch scripts, their real command lines.
int submitToFakeSlurm(int n, const std::string& out, const std::string& args, const std::string& dir) {
  const std::string bin = dir + "/fake-slurm";
  std::filesystem::create_directories(bin);
  std::ofstream(bin + "/sbatch") << R"(#!/bin/sh
array=""
while [ $# -gt 0 ]; do
  case "$1" in
    --array=*) array=${1#--array=}; shift ;;
    --*) shift ;;
    *) break ;;
  esac
done
script=$1
shift
export SLURM_SUBMIT_DIR="$PWD"
if [ -n "$array" ]; then
  i=${array%-*}
  while [ "$i" -le "${array#*-}" ]; do
    SLURM_ARRAY_TASK_ID=$i bash "$script" "$@" >&2 || exit 1
    i=$((i + 1))
  done
else
  bash "$script" "$@" >&2 || exit 1
fi
echo 4242
)";
  std::filesystem::permissions(bin + "/sbatch", std::filesystem::perms::owner_all);
  const std::string cmd = "cd '" + repo() + "' && PATH='" + bin + "':$PATH BIMLOC='" + std::string(BIMLOC_EXE) +
                          "' sh deploy/slurm/submit.sh " + std::to_string(n) + " '" + out + "' " + args + " >'" + dir +
                          "/submit.log' 2>&1";
  return std::system(cmd.c_str());
}

std::string file(int k, int n, const std::string& dir) {
  return "'" + dir + "/shard-" + std::to_string(k) + "-of-" + std::to_string(n) + ".json'";
}

// The summary line's wall-clock time is the only thing that may differ.
std::string withoutWallClock(const std::string& table) {
  return std::regex_replace(table, std::regex(R"(simulated\s+in\s+[0-9.]+\s+s)"), "simulated in - s");
}

}  // namespace

TEST(Shards, ArrayTasksMergeIntoTheUnshardedRun) {
  const std::string dir = tempDir("shards");
  const auto whole = runBimloc("run " + sweep() + " --json");
  ASSERT_FALSE(whole.out.empty()) << whole.err;
  auto unsharded = nlohmann::json::parse(whole.out);
  ASSERT_EQ(unsharded["scenarios"].size(), 6u);
  // The Slurm array (3 tasks) and its merge job: merged.json and merged.txt in the folder.
  ASSERT_EQ(submitToFakeSlurm(3, dir, sweep(), dir), 0) << std::ifstream(dir + "/submit.log").rdbuf();
  auto from_slurm = nlohmann::json::parse(std::ifstream(dir + "/merged.json"));
  // Each shard is every third scenario, from the K-th on.
  const auto second = nlohmann::json::parse(std::ifstream(dir + "/shard-2-of-3.json"));
  EXPECT_EQ(second["shard"]["positions"], nlohmann::json({1, 4}));
  EXPECT_EQ(second["scenarios"][1]["name"], unsharded["scenarios"][4]["name"]);

  // Any order of the files: the unsharded order back.
  const std::string files = file(3, 3, dir) + " " + file(1, 3, dir) + " " + file(2, 3, dir);
  const auto merged = runBimloc("report merge " + files + " --json");
  ASSERT_FALSE(merged.out.empty()) << merged.err;
  EXPECT_EQ(merged.exit_code, whole.exit_code);
  auto m = nlohmann::json::parse(merged.out);
  unsharded["summary"].erase("wall_seconds"), m["summary"].erase("wall_seconds");
  EXPECT_EQ(m.dump(), unsharded.dump());
  from_slurm["summary"].erase("wall_seconds");
  EXPECT_EQ(from_slurm.dump(), unsharded.dump());

  // The table too (the unsharded table from its own run).
  const auto whole_table = runBimloc("run " + sweep());
  const auto merged_table = runBimloc("report merge " + files);
  EXPECT_EQ(withoutWallClock(merged_table.out), withoutWallClock(whole_table.out));
  std::stringstream slurm_table;
  slurm_table << std::ifstream(dir + "/merged.txt").rdbuf();
  EXPECT_EQ(withoutWallClock(slurm_table.str()), withoutWallClock(whole_table.out));

  // Missing, overlapping, foreign shards and bad files are named.
  const auto missing = runBimloc("report merge " + file(1, 3, dir) + " " + file(3, 3, dir));
  EXPECT_EQ(missing.exit_code, 2);  // the shards cannot be used (docs/exit_codes.md)
  EXPECT_NE(missing.err.find("missing shards: 2/3"), std::string::npos) << missing.err;
  const auto twice = runBimloc("report merge " + files + " " + file(1, 3, dir));
  EXPECT_NE(twice.err.find("overlapping shards"), std::string::npos) << twice.err;
  const std::string other = dir + "/other";
  ASSERT_EQ(shardTask(1, 3, (std::filesystem::create_directories(other), other), sweep("5")).exit_code, 0);
  const auto mixed = runBimloc("report merge " + file(1, 3, other) + " " + file(2, 3, dir) + " " + file(3, 3, dir));
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_NE(mixed.err.find("mixed sweeps"), std::string::npos) << mixed.err;
  EXPECT_NE(mixed.err.find(other + "/shard-1-of-3.json"), std::string::npos) << mixed.err;
  std::ofstream(dir + "/bad.json") << "{\"scenarios\": [";
  const auto bad = runBimloc("report merge '" + dir + "/bad.json' " + files);
  EXPECT_NE(bad.err.find(dir + "/bad.json: not valid JSON"), std::string::npos) << bad.err;
  // A number no double holds is the library's out_of_range, not a parse error: named too.
  std::ofstream(dir + "/huge.json") << "{\"scenarios\": [], \"wall_seconds\": 1e99999}";
  const auto huge = runBimloc("report merge '" + dir + "/huge.json' " + files);
  EXPECT_EQ(huge.exit_code, 2);
  EXPECT_NE(huge.err.find(dir + "/huge.json: number overflow"), std::string::npos) << huge.err;
  // A key only the table reads, missing: the shard is named (it failed on the merged report).
  auto lacking = nlohmann::json::parse(std::ifstream(dir + "/shard-2-of-3.json"));
  for (auto& scenario : lacking["scenarios"]) scenario.erase("position_error_m");
  std::ofstream(dir + "/lacking.json") << lacking.dump();
  const auto unreadable = runBimloc("report merge " + file(1, 3, dir) + " '" + dir + "/lacking.json' " + file(3, 3, dir));
  EXPECT_EQ(unreadable.exit_code, 2);
  EXPECT_NE(unreadable.err.find(dir + "/lacking.json: malformed shard report"), std::string::npos) << unreadable.err;
  std::ofstream(dir + "/whole.json") << whole.out;
  const auto plain = runBimloc("report merge '" + dir + "/whole.json'");
  EXPECT_NE(plain.err.find(dir + "/whole.json: not the JSON of a sharded run"), std::string::npos) << plain.err;
}

TEST(Shards, BadShardSyntaxIsAClearError) {
  for (const char* bad : {"0/3", "4/3", "3", "a/b", "1/0", "1/2/3", "2/x"}) {
    const auto r = runBimloc(std::string("run --plan '") + BIMLOC_WORLDS_DIR + "/site_office.ifc' --all-rooms --shard '" + bad + "'");
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("--shard '" + std::string(bad) + "': expected K/N with 1 <= K <= N"), std::string::npos) << r.err;
  }
}

// The Kubernetes manifests cannot run here (no cluster): check that they say one thing. The
// Indexed Job maps JOB_COMPLETION_INDEX (0-based) to shard index + 1 of SHARDS, SHARDS is its
// completions, and the merge job merges that many shards.
TEST(Shards, KubernetesManifestsAgreeOnTheShardCount) {
  const auto read = [](const std::string& name) {
    std::stringstream text;
    text << std::ifstream(repo() + "/deploy/kubernetes/" + name).rdbuf();
    return text.str();
  };
  const std::string job = read("sweep-job.yaml"), merge = read("merge-job.yaml");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(job, m, std::regex(R"(completions:\s*(\d+))")));
  const std::string n = m[1];
  EXPECT_NE(job.find("completionMode: Indexed"), std::string::npos);
  ASSERT_TRUE(std::regex_search(job, m, std::regex(R"k8s(name: SHARDS\s+value:\s*"(\d+)")k8s")));
  EXPECT_EQ(m[1], n);
  EXPECT_NE(job.find(R"k8s(run_shard.sh "$((JOB_COMPLETION_INDEX + 1))" "$SHARDS" /results)k8s"), std::string::npos);
  ASSERT_TRUE(std::regex_search(merge, m, std::regex(R"k8s(merge_shards.sh",\s*"(\d+)",\s*"/results")k8s")));
  EXPECT_EQ(m[1], n);
  // The pods' shell command, run here for every index with a stand-in for the script: the
  // shards 1..N of N, each once.
  ASSERT_TRUE(std::regex_search(job, m, std::regex(R"k8s(- exec (\S*run_shard.sh) ("\$\(\(JOB_COMPLETION_INDEX \+ 1\)\)" "\$SHARDS" /results))k8s")));
  const std::string dir = tempDir("k8s");
  std::ofstream(dir + "/pod.sh") << "echo " << m[2] << "\n";  // the script's arguments, as the pod's shell expands them
  std::string shards;
  for (int i = 0; i < std::stoi(n); ++i) {
    const std::string cmd = "JOB_COMPLETION_INDEX=" + std::to_string(i) + " SHARDS=" + n + " sh '" + dir + "/pod.sh'";
    FILE* p = ::popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    char line[256] = {0};
    if (std::fgets(line, sizeof line, p)) shards += line;
    ::pclose(p);
  }
  std::string expected;
  for (int k = 1; k <= std::stoi(n); ++k) expected += std::to_string(k) + " " + n + " /results\n";
  EXPECT_EQ(shards, expected);
}
