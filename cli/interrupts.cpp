// scansurf CLI: interrupts leave nothing behind (see interrupts.h).
#include "interrupts.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <mutex>
#include <thread>

namespace scansurf::cli {
namespace {

std::mutex gMutex;                  // held while a commit moves files
OutputStaging* gStaging = nullptr;  // the run's staged outputs, if any
const char* gProgram = "scansurf";
const char* gMessage = "no output was written or replaced";

sigset_t interruptSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  return set;
}

[[noreturn]] void watch() {
  const sigset_t set = interruptSignals();
  int signal = 0;
  while (sigwait(&set, &signal) != 0) {
  }
  std::lock_guard lock(gMutex);
  if (gStaging) gStaging->discard();
  std::fprintf(stderr, "\n%s: interrupted (signal %d): %s\n", gProgram, signal, gMessage);
  std::fflush(stderr);
  ::_exit(128 + signal);
}

}  // namespace

void installInterruptHandling() {
  ::signal(SIGXFSZ, SIG_IGN);
  // A reader that closes our output (scansurf ... | head) must not kill the run mid-way: a
  // write to it fails with EPIPE instead, which the summary's prints ignore.
  ::signal(SIGPIPE, SIG_IGN);
  const sigset_t set = interruptSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);  // inherited by every thread created after this
  std::thread(watch).detach();
}

void setInterruptMessage(const char* program, const char* message) {
  std::lock_guard lock(gMutex);
  gProgram = program;
  gMessage = message;
}

InterruptScope::InterruptScope(OutputStaging& staging) : staging_(staging) {
  std::lock_guard lock(gMutex);
  gStaging = &staging_;
}

InterruptScope::~InterruptScope() {
  std::lock_guard lock(gMutex);
  gStaging = nullptr;
}

Result<std::vector<std::filesystem::path>> InterruptScope::commit() {
  std::lock_guard lock(gMutex);
  return staging_.commit();
}

}  // namespace scansurf::cli
