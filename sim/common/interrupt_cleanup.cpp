#include "sim/common/interrupt_cleanup.hpp"

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <pthread.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace bimloc::sim {
namespace {

std::recursive_mutex& registryMutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

std::vector<std::string>& registry() {
  static std::vector<std::string> paths;
  return paths;
}

void say(const std::string& text) {
  const ssize_t ignored = ::write(STDERR_FILENO, text.data(), text.size());
  (void)ignored;
}

}  // namespace

void installInterruptCleanup() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);  // inherited by every thread started later
  std::thread([set] {
    int signal = 0;
    while (sigwait(&set, &signal) != 0) {
    }
    std::lock_guard<std::recursive_mutex> lock(registryMutex());
    for (const auto& path : registry()) {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
    say(std::string("bimloc: interrupted by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") +
        (registry().empty() ? "" : ": unfinished output removed") + "\n");
    ::_exit(128 + signal);
  }).detach();
}

void registerForCleanup(const std::string& path) {
  std::lock_guard<std::recursive_mutex> lock(registryMutex());
  registry().push_back(path);
}

void unregisterForCleanup(const std::string& path) {
  std::lock_guard<std::recursive_mutex> lock(registryMutex());
  auto& paths = registry();
  paths.erase(std::remove(paths.begin(), paths.end(), path), paths.end());
}

std::unique_lock<std::recursive_mutex> holdInterrupts() { return std::unique_lock<std::recursive_mutex>(registryMutex()); }

}  // namespace bimloc::sim
