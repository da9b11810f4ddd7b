// Output folders under construction are removed when the process is interrupted. SIGINT and
// SIGTERM are taken by one thread (sigwait), not by a handler: removing a folder tree is not
// async-signal-safe, and a commit in progress must end, whole, before anything is removed.
#pragma once

#include <mutex>
#include <string>

namespace bimloc::sim {

// Call first thing in main, before any other thread starts: blocks SIGINT and SIGTERM in every
// thread and starts the one that waits for them. On either it removes the registered folders
// and exits with 128 + the signal (130, 143).
void installInterruptCleanup();

// A folder to remove on an interrupt, until it is unregistered.
void registerForCleanup(const std::string& path);
void unregisterForCleanup(const std::string& path);

// Held across a commit: an interrupt waits until the commit has ended.
std::unique_lock<std::recursive_mutex> holdInterrupts();

}  // namespace bimloc::sim
