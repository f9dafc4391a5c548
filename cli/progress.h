// scansurf CLI: progress reports while a run works, and the run's warnings and errors.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace scansurf::cli {

enum class ProgressMode {
  // A status line on stderr once the run takes over 1 s, redrawn 4 times a second: the step
  // (k of the steps planned), the stage, its layer, its time and the time since the start.
  Terminal,
  Quiet,  // nothing
  Json,   // one JSON object per line on stderr for every event, for scripts
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

  // How many stages the run will have (the terminal line's "k/n"); may grow as the run learns
  // more (its surface layers).
  void plan(int stages);
  // A stage starts / has finished (seconds: its duration). JSON: {"event":"begin"|"done",
  // "stage", "within", "layer", "layers", "seconds", "elapsed"}. The terminal line shows the
  // step, the stage, its layer ("layer 2 of 3") and the times. A stage that holds others
  // (place.within of theirs) is not a step of its own.
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
  void show(const std::string& text);
  void draw();
  void tick();
  void record(const std::string& json);
  void message(const char* kind, const std::string& text);

  ProgressMode mode_;
  std::FILE* out_;
  std::chrono::steady_clock::time_point start_;
  bool lineShown_ = false;
  bool finished_ = false;
  // The terminal line's state, redrawn by the ticker thread (Terminal mode only).
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string text_;
  std::chrono::steady_clock::time_point stageStart_;
  int stepsDone_ = 0, stepsPlanned_ = 0;
  bool stop_ = false;
  std::thread ticker_;
};

// The run's one Progress, for the messages of code that has none at hand (fail, warnings);
// null outside a run (plain lines then).
Progress* activeProgress();
void setActiveProgress(Progress* progress);

}  // namespace scansurf::cli
