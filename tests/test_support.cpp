#include "test_support.hpp"

#include <array>
#include <cstdlib>
#include <vector>
#include <chrono>
#include <csignal>
#include <thread>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace bimloc::test {
namespace fs = std::filesystem;

std::string sharedPlan(const std::string& file_name) {
  const fs::path p = fs::path(BIMLOC_SHARED_IFC_DIR) / file_name;
  return fs::exists(p) ? p.string() : std::string();
}

namespace {
// The folders a test process made, removed when it ends (ctest runs each test in a process of
// its own): a test run leaves nothing behind in the temp folder. BIMLOC_KEEP_TEST_DIRS=1 keeps
// them, to look at what a failing test wrote.
struct TempDirs {
  std::vector<fs::path> made;
  ~TempDirs() {
    if (std::getenv("BIMLOC_KEEP_TEST_DIRS")) return;
    std::error_code ec;
    for (const auto& p : made) fs::remove_all(p, ec);
  }
};
}  // namespace

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string commandOutput(const std::string& command) {
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    std::array<char, 4096> buf;
    for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), p)) > 0;) out.append(buf.data(), n);
    pclose(p);
  }
  return out;
}

std::string tempDir(const std::string& tag) {
  static TempDirs dirs;
  static int counter = 0;
  const fs::path p = fs::temp_directory_path() /
                     ("bimloc-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(p);
  fs::create_directories(p);
  dirs.made.push_back(p);
  return p.string();
}

CommandResult runBimloc(const std::string& args) { return runBimloc(args, 0.0); }

CommandResult runBimloc(const std::string& args, double timeout_s) { return runCommand(BIMLOC_EXE, args, timeout_s); }

CommandResult runCommand(const std::string& program, const std::string& args, double timeout_s) {
  const std::string dir = tempDir("cmd");
  const std::string out = dir + "/out.txt", err = dir + "/err.txt";
  // exec: the shell becomes the program, so that a signal that ends it is seen here, not as 128 + N.
  const std::string cmd = "exec '" + program + "' " + args + " >'" + out + "' 2>'" + err + "' </dev/null";
  CommandResult r;
  const pid_t child = ::fork();
  if (child == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  while (::waitpid(child, &status, timeout_s > 0 ? WNOHANG : 0) == 0) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  const auto slurp = [](const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove_all(dir);
  return r;
}

}  // namespace bimloc::test
