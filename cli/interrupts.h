// scansurf CLI: SIGINT, SIGTERM and SIGHUP leave nothing behind. They are blocked in every
// thread and taken by one watcher thread, which discards the run's staged outputs (waiting
// for a commit in progress to finish, so files are never half replaced), says so and exits
// with 128 + the signal. SIGXFSZ is ignored, so a file-size limit is an ordinary write error.
#pragma once

#include "scansurf/outputs.h"

namespace scansurf::cli {

// Call first in main, before any thread exists (Vulkan drivers start their own).
void installInterruptHandling();

// What an interrupt says after "interrupted (signal N): " (a string that lives as long as the
// process); by default that no output was written or replaced.
void setInterruptMessage(const char* program, const char* message);

// While alive, an interrupt discards `staging`; commit under it (Commit) so an interrupt
// waits for the moves to finish.
class InterruptScope {
 public:
  explicit InterruptScope(OutputStaging& staging);
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

  // staging.commit() with interrupts held off until it returns.
  Result<std::vector<std::filesystem::path>> commit();

 private:
  OutputStaging& staging_;
};

}  // namespace scansurf::cli
