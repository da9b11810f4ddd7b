// Shared helpers of the test suite: where the data is, and running the bimloc binary.
#pragma once

#include <string>

namespace bimloc::test {

// Path of a shared real plan, or "" when ../shared/ifc is absent (the test then skips).
std::string sharedPlan(const std::string& file_name);

// A fresh empty directory under the system's temporary directory.
std::string tempDir(const std::string& tag);

struct CommandResult {
  int exit_code = -1;  // -1 when a signal ended it
  int signal = 0;      // the signal that ended it, or 0
  bool timed_out = false;  // killed by runBimloc after its time limit
  std::string out;
  std::string err;
};
// The whole content of a file ("" when it cannot be read).
std::string readFile(const std::string& path);

// The standard output of a shell command (an independent tool: python3, sqlite3...).
std::string commandOutput(const std::string& command);

// Runs `program` (a path, quoted here) with the given argument string (shell-quoted by the
// caller), killed with SIGKILL after `timeout_s` seconds when positive (then timed_out is set).
CommandResult runCommand(const std::string& program, const std::string& args, double timeout_s);
// Runs the bimloc binary with the given argument string (shell-quoted by the caller).
CommandResult runBimloc(const std::string& args);
// The same, killed with SIGKILL after `timeout_s` seconds (then timed_out is set).
CommandResult runBimloc(const std::string& args, double timeout_s);

}  // namespace bimloc::test

// Skips the current test with a message when a shared plan is missing.
#define BIMLOC_REQUIRE_SHARED(var, file)                                                    \
  const std::string var = ::bimloc::test::sharedPlan(file);                                 \
  if (var.empty()) GTEST_SKIP() << "../shared/ifc not found: skipping the test on " << file
