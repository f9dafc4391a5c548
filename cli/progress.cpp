// scansurf CLI: progress while a run works (see progress.h).
#include "progress.h"

#include <unistd.h>

namespace scansurf::cli {

namespace {
constexpr double kQuietSeconds = 1.0;  // short runs print no progress at all

// Stage names are ours (no quotes or control characters), so no JSON escaping is needed.
}  // namespace

ProgressMode chooseProgressMode(bool quiet, bool json) {
  if (json) return ProgressMode::Json;
  if (quiet) return ProgressMode::Quiet;
  return ::isatty(STDERR_FILENO) ? ProgressMode::Terminal : ProgressMode::Quiet;
}

Progress::Progress(ProgressMode mode, std::FILE* out) : mode_(mode), out_(out), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { clearLine(); }

double Progress::elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

void Progress::clearLine() {
  if (lineShown_) std::fputs("\r\033[K", out_), std::fflush(out_);
  lineShown_ = false;
}

void Progress::begin(const std::string& stage) {
  if (mode_ == ProgressMode::Json) {
    std::fprintf(out_, "{\"event\":\"begin\",\"stage\":\"%s\",\"elapsed\":%.3f}\n", stage.c_str(), elapsed());
    std::fflush(out_);
  } else if (mode_ == ProgressMode::Terminal && elapsed() > kQuietSeconds) {
    std::fprintf(out_, "\r\033[Kscansurf: %s... (%.1f s)", stage.c_str(), elapsed());
    std::fflush(out_);
    lineShown_ = true;
  }
}

void Progress::done(const std::string& stage, double seconds) {
  if (mode_ == ProgressMode::Terminal && elapsed() > kQuietSeconds) {
    std::fprintf(out_, "\r\033[Kscansurf: %s done in %.1f s, working... (%.1f s)", stage.c_str(), seconds, elapsed());
    std::fflush(out_);
    lineShown_ = true;
  }
  if (mode_ != ProgressMode::Json) return;
  std::fprintf(out_, "{\"event\":\"done\",\"stage\":\"%s\",\"seconds\":%.3f,\"elapsed\":%.3f}\n", stage.c_str(), seconds,
               elapsed());
  std::fflush(out_);
}

void Progress::finish(int exitCode) {
  if (finished_) return;
  finished_ = true;
  clearLine();
  if (mode_ == ProgressMode::Json) {
    std::fprintf(out_, "{\"event\":\"finish\",\"exit_code\":%d,\"elapsed\":%.3f}\n", exitCode, elapsed());
    std::fflush(out_);
  }
}

}  // namespace scansurf::cli
