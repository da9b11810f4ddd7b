#include "sim/common/fault_injection.hpp"

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <unistd.h>

namespace bimloc::sim {

void faultPoint() {
  static const long target = [] {
    const char* value = std::getenv("BIMLOC_FAULT_AT_RENAME");
    return value ? std::atol(value) : 0L;
  }();
  static std::atomic<long> steps{0};
  if (target > 0 && ++steps == target) ::kill(::getpid(), SIGKILL);
}

}  // namespace bimloc::sim
