// A test hook: BIMLOC_FAULT_AT_RENAME=N kills the process (SIGKILL, nothing cleaned up) at the
// Nth step that moves output into place, so that a test can interrupt a run at each of them
// and check that the output is complete or absent. Unset, it costs one getenv per process.
#pragma once

namespace bimloc::sim {

// One step that moves output into place is about to happen.
void faultPoint();

}  // namespace bimloc::sim
