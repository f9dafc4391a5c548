// scansurf CLI: progress reports while a run works.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace scansurf::cli {

enum class ProgressMode {
  Terminal,  // a status line on stderr, rewritten per stage, once the run takes over 1 s
  Quiet,     // nothing
  Json,      // one JSON object per line on stderr for every stage, for scripts
};

// Terminal when stderr is a terminal, else Quiet; --json-progress and -q override.
ProgressMode chooseProgressMode(bool quiet, bool json);

class Progress {
 public:
  explicit Progress(ProgressMode mode, std::FILE* out = stderr);
  ~Progress();

  // A stage starts / has finished (seconds: its duration); the terminal line shows the latest.
  void begin(const std::string& stage);
  void done(const std::string& stage, double seconds);
  // The run is over: clears the terminal line; in JSON mode reports the exit code.
  void finish(int exitCode);

 private:
  double elapsed() const;
  void clearLine();

  ProgressMode mode_;
  std::FILE* out_;
  std::chrono::steady_clock::time_point start_;
  bool lineShown_ = false;
  bool finished_ = false;
};

}  // namespace scansurf::cli
