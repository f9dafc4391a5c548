// scansurf: planar contours in, separating surfaces out. A thin layer over the library
// (scansurf/scansurf.h): parse, read, build, write, summarize.
//
//   scansurf INPUT -o OUTDIR|NAME.glb [options]     (scansurf --help lists them)
//
// Exit codes: 0 success; 2 bad command line or option; 3 invalid input file; 4 file I/O
// error; 5 no usable Vulkan device; 6 Vulkan failure; 7 internal error; 8 out of memory;
// 9 resource limit (refused before the work: more memory needed than allowed); 10 a defective
// surface (open, not manifold or not oriented: nothing written unless --keep-defective).
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <string>

#include "batch.h"
#include "interrupts.h"
#include "options.h"
#include "progress.h"
#include "roi_list.h"
#include "safe_text.h"
#include "scansurf/scansurf.h"
#include "summary.h"

namespace fs = std::filesystem;
using namespace scansurf;

namespace {

int exitCode(Errc code) { return static_cast<int>(code) + 1; }

// The library names a refused option by its BuildOptions field and a selection or setting in
// its own words; a command-line user reads the flag that set it.
std::string inFlags(std::string message) {
  static constexpr std::pair<const char*, const char*> kFlags[] = {
      {"option remeshing.edgeLength ", "option --edge-length "},
      {"option simplification.tolerance ", "option --simplify-tolerance "},
      {"option simplification.edgeLength ", "option --simplify-edge-length "},
      {"option smoothing.strength ", "option --smooth-strength "},
      {"option smoothing.iterations ", "option --smooth-iterations "},
      {"option threads ", "option --threads "},
      {"option grid.gapFactor ", "option --long-gap "},
      {"option grid.nx ", "option --grid (NX) "},
      {"option grid.ny ", "option --grid (NY) "},
      {"option interpolation.factor ", "option --interpolate "}};
  for (const auto& [field, flag] : kFlags)
    if (message.rfind(field, 0) == 0) return flag + message.substr(std::char_traits<char>::length(field));
  static constexpr std::pair<const char*, const char*> kPhrases[] = {
      {"the ROI pattern \"", "--roi \""},
      {"the object pattern \"", "--object \""},
      {"with an ROI pattern", "with --roi"},
      {"with an object pattern", "with --object"},
      {"turn interpolation off", "use --interpolate off"},
      {"BuildOptions::audit.keepDefective keeps", "--keep-defective writes"},
      {"(GridOptions::gapFactor)", "(--long-gap)"},
      {"(a reference series)", "(--reference CT_DIR)"},
      {"(the reference is the folder of a CT series)", "(--reference takes the folder of a CT series)"}};
  for (const auto& [phrase, flag] : kPhrases)
    if (const auto at = message.find(phrase); at != std::string::npos)
      message.replace(at, std::char_traits<char>::length(phrase), flag);
  return message;
}

// A warning's kind: the message less the input's path, names in quotes and numbers, so that
// "contour 3 of slice z=12.5 covers no pixel centre" and its 400 siblings are one kind.
std::string warningKind(const std::string& message) {
  std::string kind;
  bool quoted = false;
  for (std::size_t i = message.find(": ") == std::string::npos ? 0 : message.find(": "); i < message.size(); ++i) {
    const char c = message[i];
    if (c == '"') quoted = !quoted;
    if (quoted || c == '"') continue;
    if (std::isdigit(static_cast<unsigned char>(c))) {  // a number, with its fraction and exponent
      while (i + 1 < message.size() && (std::isalnum(static_cast<unsigned char>(message[i + 1])) || message[i + 1] == '.')) ++i;
      kind += '#';
      continue;
    }
    kind += c;
  }
  return kind;
}

// The warnings on the terminal, at most kShownPerKind of each kind, the last of them followed
// by a count of the rest; every one is in the report.
void printWarnings(cli::Progress& progress, const std::vector<std::string>& warnings, bool report) {
  constexpr std::size_t kShownPerKind = 3;
  std::vector<std::string> kinds;
  kinds.reserve(warnings.size());
  for (const std::string& w : warnings) kinds.push_back(warningKind(w));
  std::map<std::string, std::pair<std::size_t, std::size_t>> counts;  // kind: in all, shown
  for (const std::string& k : kinds) ++counts[k].first;
  for (std::size_t i = 0; i < warnings.size(); ++i) {
    auto& [total, shown] = counts[kinds[i]];
    if (shown == kShownPerKind) continue;
    progress.warning(inFlags(warnings[i]));
    if (++shown == kShownPerKind && total > kShownPerKind)
      progress.warning(std::to_string(total - kShownPerKind) + " more warnings like this one (" + std::to_string(total) +
                       " in all; " + (report ? "every one is in the report)" : "--report FILE lists every one)"));
  }
}

int fail(const Error& error) {
  if (cli::Progress* progress = cli::activeProgress()) {
    progress->error(inFlags(error.message));
    progress->finish(exitCode(error.code));
    return exitCode(error.code);
  }
  if (::isatty(STDERR_FILENO)) std::fputs("\r\033[K", stderr);  // over a progress line
  std::fprintf(stderr, "scansurf: error: %s\n", cli::printable(inFlags(error.message)).c_str());
  return exitCode(error.code);
}

// No output may replace the input it is made from (a --report naming the input file would
// overwrite the contours with the report).
Result<void> refuseInputAsOutput(const OutputPlan& plan, const cli::CliOptions& o) {
  std::error_code ec;
  const std::pair<const char*, fs::path> targets[] = {
      {"-o", plan.glbFile},          {"-o", plan.meshFile},       {"-o", plan.dir},
      {"--report", plan.report},     {"--preview", plan.preview}, {"--label-volume", plan.labelVolume},
      {"--dicom-seg", plan.dicomSeg}};
  for (const auto& [option, target] : targets)
    if (!target.empty() && fs::exists(target, ec) && fs::equivalent(target, o.input, ec))
      return makeError(Errc::InvalidArgument,
                       std::string(option) + " '" + target.string() + "' is the input file " + o.input + "; choose another path");
  return {};
}

// The outputs of the command line: `-o x.glb` writes one GLB scene, `-o x.stl` (.ply, .vtp, .obj,
// .drc) one file with every structure; otherwise -o is a directory for the per-feature files.
Result<OutputPlan> planOutputs(const cli::CliOptions& o) {
  OutputPlan plan;
  const std::string ext = fs::path(o.output).extension().string();
  if (ext == ".glb" || ext == ".GLB") {
    if (!o.formats.empty())
      return makeError(Errc::InvalidArgument, "--format needs an output directory, not the file " + o.output);
    plan.glbFile = o.output;
  } else if (const auto named = parseMeshFormat(ext); named && !ext.empty() && *named != MeshFormat::SegVtm) {
    // NAME.ply, .vtp, .stl, .obj, .drc: every structure in that one file.
    if (!o.formats.empty())
      return makeError(Errc::InvalidArgument, "--format needs an output directory, not the file " + o.output);
    plan.meshFile = o.output;
  } else {
    plan.dir = o.output;
    for (const std::string& f : o.formats.empty() ? std::vector<std::string>{"ply"} : o.formats) {
      SCANSURF_ASSIGN_OR_RETURN(const MeshFormat format, parseMeshFormat(f));
      plan.formats.push_back(format);
    }
    plan.sceneName = fs::path(o.input).stem().string();
  }
  plan.scene = o.scene;
  plan.labelVolume = o.labelVolume;
  plan.dicomSeg = o.dicomSeg;
  plan.referenceSeries = o.read.referenceSeries;
  if (!o.dicomSeg.empty() && !plan.referenceSeries.empty() && (o.build.grid.voxelSize > 0 || o.build.grid.nx > 0))
    return makeError(Errc::InvalidArgument,
                     "--dicom-seg writes the label volume on the --reference CT's grid; "
                     "leave out --voxel-size and --grid");
  plan.report = o.report;
  plan.preview = o.preview;
  SCANSURF_TRY(checkOutputs(plan));
  SCANSURF_TRY(refuseInputAsOutput(plan, o));
  return plan;
}

// The stages a run will have, for the progress line's "k/n": the CLI's own and, per surface
// layer, the engine's (grid, nesting and the overlap analysis once).
int plannedStages(const cli::CliOptions& o, int layers) {
  const BuildOptions& b = o.build;
  const int cli = 3 + !o.preview.empty();  // read, device, write; preview
  const int perLayer =
      4 + (b.interpolation.factor != 1) + 2 * b.smoothing.enabled + b.simplification.enabled + b.remeshing.enabled;
  return cli + 4 + layers * perLayer;  // grid, nesting, overlap analysis and audit once
}

// Stage times of the CLI's own steps, beside the engine's.
class Laps {
 public:
  Laps(cli::Progress& progress, const cli::CliOptions& o) : progress_(progress), options_(o) {
    progress_.plan(plannedStages(o, 1));
  }
  void begin(const char* stage) { progress_.begin(stage); }
  void lap(const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    timings.push_back({stage, std::chrono::duration<double>(now - start_).count()});
    progress_.done(stage, timings.back().seconds);
    start_ = now;
  }
  // A stage of the engine's, within "surfaces" (progress only; add() records them after the build).
  void report(const BuildOptions::StageEvent& e) {
    const cli::StagePlace place{"surfaces", e.layer, e.layers};
    if (e.layers > 1) progress_.plan(plannedStages(options_, e.layers));
    if (e.done)
      progress_.done(e.stage, e.seconds, place);
    else
      progress_.begin(e.stage, place);
  }
  // The engine's stages, recorded; "surfaces", which holds them, is done.
  void add(const char* stage, const std::vector<StageTime>& stages) {
    timings.insert(timings.end(), stages.begin(), stages.end());
    const auto now = std::chrono::steady_clock::now();
    progress_.done(stage, std::chrono::duration<double>(now - start_).count());
    start_ = now;
  }
  void warn(const std::string& message) { progress_.warning(message); }
  std::vector<StageTime> timings;

 private:
  cli::Progress& progress_;
  const cli::CliOptions& options_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Features that enclose others are drawn translucent (displayOpacity), so that what they hold shows.
Result<void> stagePreview(Engine& engine, const cli::CliOptions& o, const ContourSet& contours, const BuildResult& built,
                          OutputStaging& staging) {
  PreviewOptions options;
  options.view = *parseViewPreset(o.view);
  if (o.previewSize.size() == 2) options.width = o.previewSize[0], options.height = o.previewSize[1];
  options.colors = featureColors(contours);
  options.opacity = displayOpacity(built.nesting);
  options.memoryLimit = o.build.memoryLimit;
  SCANSURF_ASSIGN_OR_RETURN(const PreviewImage picture, engine.renderPreview(built.surfaces, options));
  return staging.stage(o.preview, [&](const fs::path& p) { return writePreview(p, picture); });
}

struct Built {
  Engine engine;
  BuildResult result;
};

Result<Built> buildSurfaces(const cli::CliOptions& o, const ContourSet& contours, Laps& laps) {
  laps.begin("device");
  SCANSURF_ASSIGN_OR_RETURN(Engine engine, Engine::create(o.engine));
  laps.lap("device");
  const DeviceInfo& info = engine.device();
  if (!o.quiet) std::printf("device: %s (%s, %s)\n", info.name.c_str(), info.type.c_str(), info.driver.c_str());
  BuildOptions options = o.build;
  options.keepLabelVolume = false;  // the outputs rasterize their own label volumes (runVolumes)
  options.onStageEvent = [&](const BuildOptions::StageEvent& e) { laps.report(e); };
  laps.begin("surfaces");
  SCANSURF_ASSIGN_OR_RETURN(BuildResult built, engine.build(contours, options));
  laps.add("surfaces", built.timings);
  return Built{std::move(engine), std::move(built)};
}

// --list-overlaps: the overlap analysis of the run these options would make, without surfacing.
int listOverlaps(const cli::CliOptions& o) {
  auto contours = readContours(o.input, o.read);
  if (!contours) return fail(contours.error());
  for (const std::string& w : contours->warnings) std::fprintf(stderr, "scansurf: warning: %s\n", cli::printable(w).c_str());
  auto engine = Engine::create(o.engine);
  if (!engine) return fail(engine.error());
  auto report = engine->analyzeOverlaps(*contours, o.build);
  if (!report) return fail(report.error());
  auto grid = makeGrid(*contours, o.build.grid);
  if (!grid) return fail(grid.error());
  cli::printOverlapList(*contours, *report, incidentalDepthLimit(o.build.overlapTolerance, *grid));
  return 0;
}

// What the report is made from.
struct ReportInputs {
  const ContourSet& contours;
  const BuildResult& result;
  const DeviceInfo& device;
  const std::vector<std::vector<fs::path>>& files;
  const std::vector<StageTime>& timings;
  const std::string& started;
  const VolumeUnit& volumeUnit;
};

Result<void> stageReport(OutputStaging& staging, const cli::CliOptions& o, const ReportInputs& in) {
  std::vector<fs::path> outputs = staging.targets();
  outputs.push_back(o.report);
  const RunSettings settings{o.build, o.scene, o.read.referenceSeries, o.engine.validation};
  ReportContext context{o.input, runParameters(settings, in.result), in.timings, in.files, outputs};
  context.commandLine = o.commandLine;
  context.started = in.started;
  context.volumeUnit = in.volumeUnit;
  const RunReport report = makeReport(in.contours, in.result, in.device, std::move(context));
  return staging.stage(o.report, [&](const fs::path& p) { return writeReport(p, report); });
}

int run(const cli::CliOptions& o) {
  if (o.listOverlaps) return listOverlaps(o);
  if (o.listRois) {
    auto listed = cli::printRoiList(o.input, o.read.roiPatterns);
    return listed ? 0 : fail(listed.error());
  }
  if (o.listObjects) {
    auto listed = cli::printObjectList(o.input, o.read.objectPatterns);
    return listed ? 0 : fail(listed.error());
  }
  if (o.output.empty())
    return fail({Errc::InvalidArgument, "-o/--output is required (or use --list-rois, --list-objects or --list-overlaps)"});
  // Every output is checked before the work, so a typo does not cost a whole run.
  auto plan = planOutputs(o);
  if (!plan) return fail(plan.error());
  // One run at a time into one place, decided now rather than after the work; from here on an
  // interrupt discards what is staged and the run locks.
  OutputStaging staging;
  cli::InterruptScope interruptible(staging);
  for (const fs::path& dir : outputDirectories(*plan))
    if (auto locked = staging.lock(dir); !locked) return fail(locked.error());
  const std::string started = utcTimestamp();
  cli::Progress progress(cli::chooseProgressMode(o.quiet, o.jsonProgress));
  cli::setActiveProgress(&progress);
  Laps laps(progress, o);

  laps.begin("read");
  auto contours = readContours(o.input, o.read);
  if (!contours) return fail(contours.error());
  printWarnings(progress, contours->warnings, !o.report.empty());
  if (!o.quiet)
    for (const std::string& note : contours->notes) std::printf("%s\n", cli::printable(note).c_str());
  laps.lap("read");
  const auto volumeUnit = volumeUnitFor(o.volumeUnit, contours->units);
  if (!volumeUnit) return fail({volumeUnit.error().code, "--volume-unit: " + volumeUnit.error().message});

  auto built = buildSurfaces(o, *contours, laps);
  if (!built && built.error().code == Errc::ResourceLimit)
    return fail({Errc::ResourceLimit, built.error().message + "; choose a coarser --voxel-size or --grid, or set --max-memory"});
  if (!built) return fail(built.error());
  BuildResult& result = built->result;

  plan->scene.opacity = displayOpacity(result.nesting);
  laps.begin("write");
  auto files = stageSurfaceOutputs(staging, *plan, *contours, result);
  if (!files) return fail(files.error());
  result.warnings.insert(result.warnings.end(), files->warnings.begin(), files->warnings.end());
  laps.lap("write");
  if (!o.preview.empty()) {
    laps.begin("preview");
    if (auto ok = stagePreview(built->engine, o, *contours, result, staging); !ok) return fail(ok.error());
    laps.lap("preview");
  }
  if (!o.report.empty()) {
    const ReportInputs inputs{*contours, result, built->engine.device(), files->files, laps.timings, started, *volumeUnit};
    if (auto ok = stageReport(staging, o, inputs); !ok) return fail(ok.error());
  }
  // With --validation, a validation message means the device's results are suspect: write nothing.
  if (const auto messages = built->engine.validationMessageCount(); messages > 0)
    return fail({Errc::Vulkan, std::to_string(messages) + " Vulkan validation message(s); see above"});
  auto written = interruptible.commit();
  if (!written) return fail(written.error());
  std::fflush(stdout);  // warnings after what was already printed
  printWarnings(progress, result.warnings, !o.report.empty());
  const bool defective = result.audit.defective();
  progress.finish(defective ? exitCode(Errc::DefectiveSurface) : 0);
  if (!o.quiet)
    cli::printSummary({o.input, &*contours, &result, o.build.convention, result.audit.stats, laps.timings, *volumeUnit}, *written,
                      o.output);
  if (defective)
    return fail({Errc::DefectiveSurface, "a surface is defective (see the warnings above); written as --keep-defective asks"});
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  cli::installInterruptHandling();
  scansurf::keepFreedMemoryForReuse();  // a batch run: stages reuse freed pages (scansurf/process.h)
  // Nothing may escape as an abort: whatever is left over is an internal error, exit 7.
  try {
    if (argc > 1 && std::string(argv[1]) == "batch") return cli::runBatch(argc, argv);
    const cli::ParsedCommandLine parsed = cli::parseCommandLine(argc, argv);
    return parsed.run ? run(parsed.options) : parsed.exitCode;
  } catch (const std::bad_alloc&) {
    return fail({Errc::OutOfMemory, "out of memory"});
  } catch (const std::exception& e) {
    return fail({Errc::Internal, std::string("unexpected failure: ") + e.what()});
  } catch (...) {
    return fail({Errc::Internal, "unexpected failure"});
  }
}
