// scansurf CLI: `scansurf batch INPUT... -o OUT [--workers N] [run options]`. Each input is one
// run of this same program in a child process (all or nothing per input, as any run), N at a
// time; a failing input is recorded and the others go on; a rerun skips the inputs whose
// folder already holds its report (written last). OUT/summary.csv and OUT/batch.json are
// the same files the Python package's scansurf.batch writes.
#include "batch.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "interrupts.h"
#include "options.h"
#include "safe_text.h"
#include "scansurf/outputs.h"

extern char** environ;

namespace scansurf::cli {
namespace fs = std::filesystem;
namespace {

constexpr const char* kUsage =
    "usage: scansurf batch INPUT... -o OUT [--workers N] [-q] [run options]\n"
    "  INPUT: contour sets, or folders of them (their .json, .dcm, .ser and .mod files)\n"
    "  Each input is surfaced into OUT/<name>/ with its report.json; OUT/summary.csv has a row per\n"
    "  structure, OUT/batch.json an entry per input. A rerun skips inputs whose folder is complete.\n"
    "  --workers N: inputs at a time (default: the cores); the run options (scansurf --help) apply to each.\n"
    "  Progress: a line as each input starts and ends, and one naming any stage that runs over 2 s;\n"
    "  -q: only failed inputs.\n";

struct BatchArgs {
  std::vector<std::string> inputs;
  std::string output;
  int workers = 0;
  bool quiet = false;
  std::vector<std::string> runOptions;
};

struct Task {
  std::string input, name;
  fs::path folder;
  std::string status = "done", error;
  double seconds = 0;
  int exitCode = 0;
};

bool isInputFile(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".json" || ext == ".dcm" || ext == ".ser" || ext == ".mod";
}

// The options a batch sets per input itself, or that would make every input write one file.
bool perInputOnly(const std::string& a) {
  for (const char* o : {"--report", "--label-volume", "--dicom-seg", "--preview", "--list-rois", "--list-objects",
                        "--list-overlaps", "--json-progress"})
    if (a == o || a.rfind(std::string(o) + "=", 0) == 0) return true;
  return false;
}

Result<BatchArgs> parseArgs(int argc, char** argv) {
  BatchArgs a;
  int i = 2;
  for (; i < argc && argv[i][0] != '-'; ++i) a.inputs.push_back(argv[i]);
  for (; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if ((arg == "-o" || arg == "--output") && hasValue) {
      a.output = argv[++i];
    } else if (arg == "--workers" && hasValue) {
      const std::string n = argv[++i];
      const bool digits =
          !n.empty() && n.size() < 5 && std::all_of(n.begin(), n.end(), [](unsigned char c) { return std::isdigit(c); });
      a.workers = digits ? std::stoi(n) : 0;
      if (a.workers < 1) return makeError(Errc::InvalidArgument, "--workers '" + n + "' is not a whole number from 1 to 9999");
    } else if (arg == "-q" || arg == "--quiet") {
      a.quiet = true;
    } else if (perInputOnly(arg)) {
      return makeError(Errc::InvalidArgument,
                       arg + " is not available in a batch (each input's report is OUT/<name>/report.json)");
    } else {
      a.runOptions.push_back(arg);
    }
  }
  if (a.inputs.empty()) return makeError(Errc::InvalidArgument, "no INPUT given");
  if (a.output.empty()) return makeError(Errc::InvalidArgument, "-o OUT is required");
  if (a.workers == 0) a.workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return a;
}

// The inputs, folders expanded (sorted), each with a folder name unique ignoring case.
Result<std::vector<Task>> tasksOf(const BatchArgs& a) {
  std::vector<std::string> files;
  std::error_code ec;
  // The batch's own record is no input, when the output is also an input folder.
  const fs::path record = fs::weakly_canonical(fs::path(a.output) / "batch.json", ec);
  for (const std::string& input : a.inputs) {
    if (!fs::is_directory(input, ec)) {
      if (!fs::exists(input, ec)) return makeError(Errc::Io, "cannot read '" + input + "': no such file or folder");
      if (!fs::is_regular_file(input, ec))
        return makeError(Errc::Io, "cannot read '" + input + "': not a regular file or a folder (a pipe or device?)");
      files.push_back(input);
      continue;
    }
    std::vector<std::string> inFolder;
    for (const auto& entry : fs::directory_iterator(input, ec))
      if (entry.is_regular_file(ec) && isInputFile(entry.path()) && fs::weakly_canonical(entry.path(), ec) != record)
        inFolder.push_back(entry.path().string());
    std::sort(inFolder.begin(), inFolder.end());
    files.insert(files.end(), inFolder.begin(), inFolder.end());
  }
  std::vector<Task> tasks;
  std::vector<std::string> used;
  for (const std::string& f : files) {
    const std::string stem = fs::path(f).filename().string().substr(0, fs::path(f).filename().string().find('.'));
    Task t{f, fileStem(stem.empty() ? "input" : stem, used)};
    t.folder = fs::path(a.output) / t.name;
    tasks.push_back(std::move(t));
  }
  return tasks;
}

// The run's arguments are checked once, before any input, as the first run would check them.
bool runOptionsParse(const BatchArgs& a, const Task& first) {
  std::vector<std::string> args{"scansurf", first.input, "-o", first.folder.string()};
  args.insert(args.end(), a.runOptions.begin(), a.runOptions.end());
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  return parseCommandLine(static_cast<int>(argv.size()), argv.data()).run;
}

// The error class of a run's exit code, as the Python package names it (scansurf.InvalidInput...).
std::string categoryOf(int exitCode) {
  static const char* const kNames[] = {"InvalidArgument", "InvalidInput", "IoError",       "NoDevice",        "VulkanError",
                                       "InternalError",   "OutOfMemory",  "ResourceLimit", "DefectiveSurface"};
  if (exitCode >= 2 && exitCode <= 10) return kNames[exitCode - 2];
  return exitCode > 128 ? "Killed by signal " + std::to_string(exitCode - 128) : "Exit " + std::to_string(exitCode);
}

// A child's progress record ({"event": ...} of --json-progress), or a discarded value for a
// plain line (an error printed before the run's progress began).
nlohmann::json recordOf(const std::string& line) {
  return line.starts_with("{") ? nlohmann::json::parse(line, nullptr, false) : nlohmann::json(nlohmann::json::value_t::discarded);
}

// The error a child ended with: its last error record or "scansurf: error: ..." line.
std::string errorOf(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line)) {
    if (line.rfind("scansurf: error: ", 0) == 0) last = line.substr(17);
    const nlohmann::json r = recordOf(line);
    if (r.is_object() && r.value("event", "") == "error" && r.contains("message") && r["message"].is_string())
      last = r["message"].get<std::string>();
  }
  return last.empty() ? "failed without a message" : last;
}

using Clock = std::chrono::steady_clock;

struct Child {
  pid_t pid = -1;
  std::size_t task = 0;
  fs::path log;
  Clock::time_point start;
  // The stage it works on, from its log's progress records.
  std::streamoff logRead = 0;
  std::string stage;
  Clock::time_point stageSince;
  bool stageShown = false;
};

// Reads the records a child appended since the last call; a stage's "begin" makes it current.
void followStages(Child& c) {
  std::ifstream in(c.log, std::ios::binary);
  if (!in.seekg(c.logRead)) return;
  std::string line;
  while (std::getline(in, line)) {
    if (in.eof()) break;  // a line still being written: read it whole next time
    c.logRead += static_cast<std::streamoff>(line.size()) + 1;
    const nlohmann::json r = recordOf(line);
    if (!r.is_object() || r.value("event", "") != "begin" || !r.contains("stage") || !r["stage"].is_string()) continue;
    c.stage = r["stage"].get<std::string>();
    if (const int layers = r.value("layers", 1); layers > 1)
      c.stage += " (surface layer " + std::to_string(r.value("layer", 0) + 1) + " of " + std::to_string(layers) + ")";
    c.stageSince = Clock::now(), c.stageShown = false;
  }
}

// Progress within the inputs: a stage that has run a while is named once, so a long input says
// where it is while short stages and short inputs stay quiet.
void showStages(std::map<pid_t, Child>& running, const std::vector<Task>& tasks, std::size_t done) {
  constexpr auto kWhile = std::chrono::seconds(2);
  for (auto& [pid, c] : running) {
    followStages(c);
    if (c.stage.empty() || c.stageShown || Clock::now() - c.stageSince < kWhile) continue;
    c.stageShown = true;
    std::printf("[%zu/%zu] %s: %s (%.0f s in)\n", done, tasks.size(), printable(tasks[c.task].input).c_str(),
                printable(c.stage).c_str(), std::chrono::duration<double>(Clock::now() - c.start).count());
    std::fflush(stdout);
  }
}

// Starts this program on one input, its stderr into `log`, SCANSURF_THREADS shared out among
// the workers unless the user set it.
Result<Child> spawnRun(const BatchArgs& a, const Task& t, std::size_t index, const std::string& threads) {
  std::vector<std::string> args{
      "scansurf", t.input,          "-o", t.folder.string(), "--report", (t.folder / "report.json").string(),
      "-q",       "--json-progress"};  // stages and the error as records in the log
  args.insert(args.end(), a.runOptions.begin(), a.runOptions.end());
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  if (!std::getenv("SCANSURF_THREADS")) env.push_back("SCANSURF_THREADS=" + threads);
  std::vector<char*> envp;
  for (std::string& s : env) envp.push_back(s.data());
  envp.push_back(nullptr);
  Child c{-1, index, fs::path(a.output) / (".scansurf-batch-" + t.name + ".log"), Clock::now()};
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  // A fresh file of our own: whatever a previous run (or anyone) left at that name, a link
  // above all, is removed rather than followed, and the open refuses anything that appears there.
  std::error_code gone;
  fs::remove(c.log, gone);
  posix_spawn_file_actions_addopen(&files, STDERR_FILENO, c.log.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);  // the watcher thread's blocked signals are not the child's
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  const int failed = posix_spawn(&c.pid, "/proc/self/exe", &files, &attr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  if (failed) return makeError(Errc::Io, "cannot start a run for '" + t.input + "': " + std::strerror(failed));
  return c;
}

// A folder is complete when its report (written last) reads as one: a report cut short or
// damaged since means the input is surfaced again, not skipped with no row.
bool completeFolder(const fs::path& folder) {
  std::ifstream in(folder / "report.json");
  if (!in) return false;
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  return !report.is_discarded() && report.is_object() && report.contains("features") && report["features"].is_array();
}

// A run fails on a folder another run (a second batch into the same output) holds; runs are
// all or nothing, so a folder complete after such a failure was completed by the other run:
// the input is skipped, not failed.
void completedElsewhere(Task& t) {
  if (t.status == "failed" && t.exitCode == 4 && completeFolder(t.folder)) t.status = "skipped", t.error.clear(), t.exitCode = 0;
}

void finish(Task& t, const Child& c, int status, bool quiet, std::size_t done, std::size_t total) {
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - c.start).count();
  t.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (t.exitCode != 0) t.status = "failed", t.error = categoryOf(t.exitCode) + ": " + errorOf(c.log);
  completedElsewhere(t);
  std::error_code ec;
  fs::remove(c.log, ec);
  if (!quiet)
    std::printf("[%zu/%zu] %s: %s (%.1f s)%s%s\n", done, total, t.input.c_str(), t.status.c_str(), t.seconds,
                t.error.empty() ? "" : ": ", printable(t.error).c_str());
  else if (t.exitCode != 0)  // quiet keeps errors: a failed input is one
    std::fprintf(stderr, "scansurf batch: %s failed: %s\n", printable(t.input).c_str(), printable(t.error).c_str());
  std::fflush(stdout);
}

// Runs the tasks not yet complete, `workers` at a time.
// Whether a run failed only because another run (a second batch into the same output) holds
// its folder: the input waits for that run instead of failing.
bool heldElsewhere(int status, const fs::path& log) {
  return WIFEXITED(status) && WEXITSTATUS(status) == 4 && errorOf(log).find("another scansurf run") != std::string::npos;
}

// Runs the tasks not yet complete, `workers` at a time. An input whose folder another run
// holds is tried again once that run has let it go (then usually complete: skipped).
Result<void> runAll(const BatchArgs& a, std::vector<Task>& tasks) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::string threads = std::to_string(std::max(1u, cores / static_cast<unsigned>(a.workers)));
  std::map<pid_t, Child> running;
  std::deque<std::size_t> pending;
  std::set<std::size_t> waiting;  // held by another run: tried again after a pause
  std::size_t done = 0;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (!completeFolder(tasks[i].folder)) {
      pending.push_back(i);
      continue;
    }
    tasks[i].status = "skipped";
    ++done;
    if (!a.quiet) std::printf("[%zu/%zu] %s: skipped (its folder is complete)\n", done, tasks.size(), tasks[i].input.c_str());
  }
  while (true) {
    while (!pending.empty() && running.size() < static_cast<std::size_t>(a.workers)) {
      const std::size_t i = pending.front();
      pending.pop_front();
      if (waiting.erase(i) > 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(250));
        if (completeFolder(tasks[i].folder)) {
          tasks[i].status = "skipped";
          ++done;
          if (!a.quiet)
            std::printf("[%zu/%zu] %s: skipped (another run completed it)\n", done, tasks.size(), tasks[i].input.c_str());
          continue;
        }
      }
      Result<Child> c = spawnRun(a, tasks[i], i, threads);
      if (!c) {  // this input fails; the running ones and the rest go on
        tasks[i].status = "failed", tasks[i].error = "IoError: " + c.error().message, tasks[i].exitCode = 4;
        ++done;
        continue;
      }
      running.emplace(c->pid, *c);
      if (!a.quiet) {  // progress before the first input finishes
        std::printf("[%zu/%zu] %s: started\n", done, tasks.size(), printable(tasks[i].input).c_str());
        std::fflush(stdout);
      }
    }
    if (running.empty()) return {};
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid < 0) return makeError(Errc::Internal, std::string("waitpid: ") + std::strerror(errno));
    if (pid == 0) {  // all still running
      if (!a.quiet) showStages(running, tasks, done);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Child child = it->second;
    running.erase(it);
    if (heldElsewhere(status, child.log)) {
      std::error_code ec;
      fs::remove(child.log, ec);
      waiting.insert(child.task);
      pending.push_back(child.task);
      continue;
    }
    finish(tasks[child.task], child, status, a.quiet, ++done, tasks.size());
  }
}

// Each structure of a finished input from its report; a failed input as one row.
void addRows(std::ostringstream& csv, const Task& t) {
  const auto field = [](const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  const std::string seconds = nlohmann::json(std::round(t.seconds * 1000) / 1000).dump();
  if (t.status == "failed") {
    csv << field(t.input) << ",,,,,,,," << field("failed: " + t.error) << "," << seconds << "\r\n";
    return;
  }
  std::ifstream in(t.folder / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  if (report.is_discarded() || !report.contains("features") || !report["features"].is_array()) return;
  const auto value = [](const nlohmann::json& f, const char* key) { return f.contains(key) ? f[key].dump() : std::string(); };
  const auto volume = [](const nlohmann::json& f, const char* key) {  // 7 significant digits, as Python's ".7g"
    if (!f.contains(key) || !f[key].is_number()) return std::string();
    char text[32];
    std::snprintf(text, sizeof text, "%.7g", f[key].get<double>());
    return std::string(text);
  };
  const std::string unit =
      report.contains("volume_unit") && report["volume_unit"].is_string() ? report["volume_unit"].get<std::string>() : "";
  const bool skipped = t.status == "skipped";
  for (const auto& f : report["features"]) {
    if (!f.is_object()) continue;
    csv << field(t.input) << ","
        << field(f.contains("name") && f["name"].is_string() ? f["name"].get<std::string>() : std::string()) << ","
        << value(f, "label") << "," << field(unit) << "," << volume(f, "contour_volume") << "," << volume(f, "labelled_volume")
        << "," << volume(f, "surface_volume") << "," << value(f, "triangles") << "," << (skipped ? "skipped," : "done,")
        << (skipped ? "" : seconds) << "\r\n";
  }
}

Result<void> writeSummary(const BatchArgs& a, std::vector<Task>& tasks) {
  for (Task& t : tasks) completedElsewhere(t);  // the other run may have finished since
  std::ostringstream csv;
  csv << "input,roi,label,volume_unit,contour_volume,voxel_volume,surface_volume,triangles,status,seconds\r\n";
  nlohmann::ordered_json entries = nlohmann::ordered_json::array();
  for (const Task& t : tasks) {
    addRows(csv, t);
    entries.push_back(
        {{"input", t.input}, {"output", t.folder.string()}, {"status", t.status}, {"error", t.error}, {"seconds", t.seconds}});
  }
  OutputStaging staging;
  // Paths and messages are bytes from the file system and the inputs: invalid UTF-8 is replaced.
  const std::string summary = csv.str(), record = nlohmann::ordered_json{{"inputs", entries}}.dump(
                                                      2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) +
                                                  "\n";
  const auto text = [](const std::string& s) {
    return [&s](const fs::path& p) -> Result<void> {
      std::ofstream out(p, std::ios::binary);
      out << s;
      return out.flush() ? Result<void>{} : makeError(Errc::Io, "cannot write '" + p.string() + "'");
    };
  };
  SCANSURF_TRY(staging.stage(fs::path(a.output) / "summary.csv", text(summary)));
  SCANSURF_TRY(staging.stage(fs::path(a.output) / "batch.json", text(record)));
  return staging.commit().has_value() ? Result<void>{} : makeError(Errc::Io, "cannot write the batch summary in " + a.output);
}

}  // namespace

int runBatch(int argc, char** argv) {
  const auto failWith = [](const Error& e) {
    std::fprintf(stderr, "scansurf batch: error: %s\n", printable(e.message).c_str());
    return e.code == Errc::InvalidArgument ? 2 : static_cast<int>(e.code) + 1;
  };
  if (argc >= 3 && (std::string(argv[2]) == "--help" || std::string(argv[2]) == "-h")) return std::fputs(kUsage, stdout), 0;
  auto args = parseArgs(argc, argv);
  if (!args) return std::fputs(kUsage, stderr), failWith(args.error());
  auto tasks = tasksOf(*args);
  if (!tasks) return failWith(tasks.error());
  if (tasks->empty()) return failWith({Errc::InvalidArgument, "no contour set (.json, .dcm, .ser, .mod) among the inputs"});
  if (!runOptionsParse(*args, tasks->front())) return 2;
  setInterruptMessage("scansurf batch",
                      "the inputs finished so far are kept, and a rerun skips them; those running were not written");
  std::error_code ec;
  fs::create_directories(args->output, ec);
  if (ec) return failWith({Errc::Io, "cannot create '" + args->output + "': " + ec.message()});
  if (auto ran = runAll(*args, *tasks); !ran) return failWith(ran.error());
  if (auto written = writeSummary(*args, *tasks); !written) return failWith(written.error());
  for (const Task& t : *tasks)
    if (t.status == "failed") return t.exitCode;
  return 0;
}

}  // namespace scansurf::cli
