// scansurf CLI: progress reports while a run works, and the run's warnings and errors.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace scansurf::cli {

enum class ProgressMode {
  Terminal,  // a status line on stderr, rewritten per stage, once the run takes over 1 s
  Quiet,     // nothing
  Json,      // one JSON object per line on stderr for every event, for scripts
};

// Terminal when stderr is a terminal, else Quiet; --json-progress and -q override.
ProgressMode chooseProgressMode(bool quiet, bool json);

// Where a stage sits: inside another (the engine's stages within "surfaces") and, in a build
// of several surface layers, which layer.
struct StagePlace {
  const char* within = nullptr;
  int layer = -1, layers = 1;
};

class Progress {
 public:
  explicit Progress(ProgressMode mode, std::FILE* out = stderr);
  ~Progress();

  // A stage starts / has finished (seconds: its duration). JSON: {"event":"begin"|"done",
  // "stage", "within", "layer", "layers", "seconds", "elapsed"}. The terminal line shows the
  // stage, its layer ("layer 2 of 3") and the time since the start.
  void begin(const std::string& stage, const StagePlace& place = {});
  void done(const std::string& stage, double seconds, const StagePlace& place = {});
  // A warning or the error that ends the run: a JSON record ({"event":"warning"|"error",
  // "message"}) in JSON mode, else the plain "scansurf: warning: ..." line.
  void warning(const std::string& message);
  void error(const std::string& message);
  // The run is over: clears the terminal line; in JSON mode reports the exit code.
  void finish(int exitCode);

 private:
  double elapsed() const;
  void clearLine();
  void line(const std::string& text);
  void record(const std::string& json);
  void message(const char* kind, const std::string& text);

  ProgressMode mode_;
  std::FILE* out_;
  std::chrono::steady_clock::time_point start_;
  bool lineShown_ = false;
  bool finished_ = false;
};

// The run's one Progress, for the messages of code that has none at hand (fail, warnings);
// null outside a run (plain lines then).
Progress* activeProgress();
void setActiveProgress(Progress* progress);

}  // namespace scansurf::cli
