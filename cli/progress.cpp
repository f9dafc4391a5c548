// scansurf CLI: progress while a run works (see progress.h).
#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "safe_text.h"

namespace scansurf::cli {

namespace {
constexpr double kQuietSeconds = 1.0;  // short runs print no progress at all
Progress* gActive = nullptr;

std::string placeText(const StagePlace& place) {
  return place.layer >= 0 ? " (layer " + std::to_string(place.layer + 1) + " of " + std::to_string(place.layers) + ")" : "";
}

nlohmann::ordered_json stageJson(const char* event, const std::string& stage, const StagePlace& place, double elapsed) {
  nlohmann::ordered_json j{{"event", event}, {"stage", stage}};
  if (place.within) j["within"] = place.within;
  if (place.layer >= 0) j["layer"] = place.layer, j["layers"] = place.layers;
  j["elapsed"] = std::round(elapsed * 1000) / 1000;
  return j;
}
}  // namespace

Progress* activeProgress() { return gActive; }
void setActiveProgress(Progress* progress) { gActive = progress; }

ProgressMode chooseProgressMode(bool quiet, bool json) {
  if (json) return ProgressMode::Json;
  if (quiet) return ProgressMode::Quiet;
  return ::isatty(STDERR_FILENO) ? ProgressMode::Terminal : ProgressMode::Quiet;
}

Progress::Progress(ProgressMode mode, std::FILE* out)
    : mode_(mode), out_(out), start_(std::chrono::steady_clock::now()), stageStart_(start_) {
  if (mode_ == ProgressMode::Terminal) ticker_ = std::thread([this] { tick(); });
}

Progress::~Progress() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  clearLine();
  if (gActive == this) gActive = nullptr;
}

double Progress::elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

void Progress::clearLine() {
  if (lineShown_) std::fputs("\r\033[K", out_), std::fflush(out_);
  lineShown_ = false;
}

void Progress::plan(int stages) {
  const std::lock_guard<std::mutex> lock(mutex_);
  stepsPlanned_ = std::max(stepsPlanned_, stages);
}

// A stage begins: the line's new text.
void Progress::show(const std::string& text) {
  if (mode_ != ProgressMode::Terminal) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  text_ = text;
  stageStart_ = std::chrono::steady_clock::now();
  draw();
}

// Called with mutex_ held.
void Progress::draw() {
  if (finished_ || text_.empty() || elapsed() <= kQuietSeconds) return;
  const double inStage = std::chrono::duration<double>(std::chrono::steady_clock::now() - stageStart_).count();
  const int planned = std::max(stepsPlanned_, stepsDone_ + 1);
  std::fprintf(out_, "\r\033[Kscansurf: [%d/%d] %s %.1f s (%.1f s since the start)", std::min(stepsDone_ + 1, planned), planned,
               text_.c_str(), inStage, elapsed());
  std::fflush(out_);
  lineShown_ = true;
}

// The ticker: the line keeps its times current during a long stage.
void Progress::tick() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, std::chrono::milliseconds(250));
    if (!stop_) draw();
  }
}

void Progress::record(const std::string& json) {
  std::fprintf(out_, "%s\n", json.c_str());
  std::fflush(out_);
}

void Progress::begin(const std::string& stage, const StagePlace& place) {
  if (mode_ == ProgressMode::Json) return record(stageJson("begin", stage, place, elapsed()).dump());
  show(stage + placeText(place));
}

void Progress::done(const std::string& stage, double seconds, const StagePlace& place) {
  if (mode_ == ProgressMode::Json) {
    nlohmann::ordered_json j = stageJson("done", stage, place, elapsed());
    j["seconds"] = std::round(seconds * 1000) / 1000;
    return record(j.dump());
  }
  if (mode_ != ProgressMode::Terminal || stage == "surfaces") return;  // "surfaces" holds the engine's stages
  const std::lock_guard<std::mutex> lock(mutex_);
  ++stepsDone_;  // the line stays until the next stage begins
}

// Invalid UTF-8 in a message (a Latin-1 ROI name) is replaced, never a broken record.
void Progress::message(const char* kind, const std::string& text) {
  if (mode_ == ProgressMode::Json) {
    return record(nlohmann::ordered_json{{"event", kind}, {"message", text}}.dump(
        -1, ' ', false, nlohmann::ordered_json::error_handler_t::replace));
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  clearLine();
  std::fprintf(out_, "scansurf: %s: %s\n", kind, printable(text).c_str());
}

void Progress::warning(const std::string& text) { message("warning", text); }
void Progress::error(const std::string& text) { message("error", text); }

void Progress::finish(int exitCode) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  clearLine();
  if (mode_ == ProgressMode::Json) {
    record(nlohmann::ordered_json{{"event", "finish"}, {"exit_code", exitCode}, {"elapsed", std::round(elapsed() * 1000) / 1000}}
               .dump());
  }
}

}  // namespace scansurf::cli
