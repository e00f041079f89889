#pragma once
// Runs independent study tasks (one simulation each) on several threads, printing progress
// on stderr for long sweeps. Each task builds its own Simulation, so nothing is shared but
// the (read-only) Registry.
#include <functional>
#include <string>

namespace springlab::studies {

// Calls task(i) for i in [0, count) on up to `threads` threads (0: all cores). Progress
// "label: done/count" goes to stderr when `label` is not empty. The first exception a task
// throws is rethrown after every thread has finished.
void parallelFor(int count, int threads, const std::function<void(int)>& task, const std::string& label = "");

}  // namespace springlab::studies
