// scansurf CLI: progress while a run works (see progress.h).
#include "progress.h"

#include <unistd.h>

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

Progress::Progress(ProgressMode mode, std::FILE* out) : mode_(mode), out_(out), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  clearLine();
  if (gActive == this) gActive = nullptr;
}

double Progress::elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

void Progress::clearLine() {
  if (lineShown_) std::fputs("\r\033[K", out_), std::fflush(out_);
  lineShown_ = false;
}

void Progress::line(const std::string& text) {
  if (mode_ != ProgressMode::Terminal || elapsed() <= kQuietSeconds) return;
  std::fprintf(out_, "\r\033[Kscansurf: %s (%.1f s)", text.c_str(), elapsed());
  std::fflush(out_);
  lineShown_ = true;
}

void Progress::record(const std::string& json) {
  std::fprintf(out_, "%s\n", json.c_str());
  std::fflush(out_);
}

void Progress::begin(const std::string& stage, const StagePlace& place) {
  if (mode_ == ProgressMode::Json) return record(stageJson("begin", stage, place, elapsed()).dump());
  line(stage + placeText(place) + "...");
}

void Progress::done(const std::string& stage, double seconds, const StagePlace& place) {
  if (mode_ == ProgressMode::Json) {
    nlohmann::ordered_json j = stageJson("done", stage, place, elapsed());
    j["seconds"] = std::round(seconds * 1000) / 1000;
    return record(j.dump());
  }
  char took[32];
  std::snprintf(took, sizeof took, " done in %.1f s", seconds);
  line(stage + placeText(place) + took + ", working...");
}

// Invalid UTF-8 in a message (a Latin-1 ROI name) is replaced, never a broken record.
void Progress::message(const char* kind, const std::string& text) {
  if (mode_ == ProgressMode::Json) {
    return record(nlohmann::ordered_json{{"event", kind}, {"message", text}}.dump(
        -1, ' ', false, nlohmann::ordered_json::error_handler_t::replace));
  }
  clearLine();
  std::fprintf(out_, "scansurf: %s: %s\n", kind, printable(text).c_str());
}

void Progress::warning(const std::string& text) { message("warning", text); }
void Progress::error(const std::string& text) { message("error", text); }

void Progress::finish(int exitCode) {
  if (finished_) return;
  finished_ = true;
  clearLine();
  if (mode_ == ProgressMode::Json) {
    record(nlohmann::ordered_json{{"event", "finish"}, {"exit_code", exitCode}, {"elapsed", std::round(elapsed() * 1000) / 1000}}
               .dump());
  }
}

}  // namespace scansurf::cli
