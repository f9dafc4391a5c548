// scansurf: planar contours in, separating surfaces out.
//
//   scansurf INPUT.json -o OUTDIR [--voxel-size MM | --grid NX NY] [--convention enclosing|partition]
//
// Exit codes: 0 success; 2 bad command line or option; 3 invalid input file; 4 file I/O
// error; 5 no usable Vulkan device; 6 Vulkan failure; 7 internal error.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "io/atomic_file.h"
#include "io/contours_json.h"
#include "dicom_input.h"
#include "outputs.h"
#include "progress.h"
#include "summary.h"
#include "io/report_json.h"
#include "io/png_writer.h"
#include "scansurf/palette.h"
#include "scansurf/engine.h"

namespace fs = std::filesystem;
using namespace scansurf;

namespace {

int exitCode(Errc code) { return static_cast<int>(code) + 1; }

int fail(const Error& error) {
  if (::isatty(STDERR_FILENO)) std::fputs("\r\033[K", stderr);  // over a progress line
  std::fprintf(stderr, "scansurf: error: %s\n", error.message.c_str());
  return exitCode(error.code);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"scansurf: separating surfaces from planar contours (scanline surfacing on Vulkan)"};
  app.footer(
      "Outputs: OUTDIR/<feature>.ply (one closed surface per feature, outward), OUTDIR/multilabel.ply\n"
      "(every separating surface, each face with its two labels; label = feature index + 1); other formats\n"
      "with --format; -o NAME.glb writes one Draco-compressed glTF scene instead.\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid input, 4 I/O, 5 no Vulkan device, 6 Vulkan failure, 7 internal.\n"
      "Environment: SCANSURF_DEVICE (device index or name), SCANSURF_VALIDATION=1, SCANSURF_THREADS.");
  std::string input;
  std::string outDir;
  double voxelSize = 0;
  std::vector<int> gridSize;
  std::string convention = "enclosing";
  std::string device;
  bool validation = false;
  bool quiet = false;
  int threads = 0;
  app.add_option("input", input, "contour set: JSON (docs/input-format.md) or DICOM RTSTRUCT")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output", outDir, "output directory (created if missing); required unless --list-rois");
  auto* voxelOpt = app.add_option("--voxel-size", voxelSize, "in-plane pixel size, input units (default: 256 pixels along the longer side)")
                       ->check(CLI::PositiveNumber);
  app.add_option("--grid", gridSize, "NX NY: pixels along x and y including the 1-pixel border")
      ->expected(2)
      ->excludes(voxelOpt);
  app.add_option("--convention", convention, "enclosing: each surface around all its contours enclose, nested features included; "
                                              "partition: the boundary of the region each feature owns")
      ->check(CLI::IsMember({"enclosing", "partition"}))
      ->capture_default_str();
  app.add_option("--device", device, "Vulkan device: index or part of its name (default: best; env SCANSURF_DEVICE)");
  app.add_flag("--validation", validation, "enable the Vulkan validation layers");
  app.add_option("--threads", threads, "CPU threads for assembly and smoothing (default: all)")->check(CLI::NonNegativeNumber);
  app.add_flag("-q,--quiet", quiet, "print errors only");
  // Constrained smoothing with contour-faithful vertices (issue 3): on unless --no-smooth.
  SmoothingOptions smoothing;
  bool noSmooth = false, noContourFit = false, noJunctions = false;
  app.add_flag("--no-smooth", noSmooth, "write the raw (staircase) separating surfaces, without smoothing");
  app.add_option("--smooth-iterations", smoothing.iterations, "smoothing sweeps")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--smooth-strength", smoothing.strength, "step of each smoothing sweep, in (0, 1]")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_flag("--no-contour-fit", noContourFit, "do not place contour-plane vertices on the original contours");
  app.add_flag("--no-junction-smoothing", noJunctions, "keep vertices where three or more structures meet in place");
  // DICOM RTSTRUCT input (issue 5).
  std::vector<std::string> roiPatterns;
  bool listRois = false;
  std::string reference;
  app.add_option("--roi", roiPatterns, "RTSTRUCT: surface only the ROIs whose name matches (glob, case-insensitive; repeatable)")
      ->expected(1)
      ->take_all();
  app.add_flag("--list-rois", listRois, "RTSTRUCT: list the file's ROIs and exit");
  app.add_option("--reference", reference, "RTSTRUCT: folder of a CT series; the label volume lies on its voxel grid");
  // Outputs (issue 4): formats, scene, label volume, report, preview.
  std::vector<std::string> formats;
  bool noDraco = false;
  int dracoBits = 0;
  int dracoLevel = 7;
  std::string labelVolume, report, preview, view = "oblique";
  std::vector<unsigned> previewSize;
  bool jsonProgress = false;
  app.add_option("--format", formats, "per-feature formats in OUTDIR: ply (default, with multilabel.ply), drc, obj, stl, "
                                      "glb (one scene OUTDIR/surfaces.glb); comma-separated")
      ->delimiter(',');
  app.add_flag("--no-draco", noDraco, "GLB without KHR_draco_mesh_compression (plain float accessors)");
  app.add_option("--draco-bits", dracoBits, "Draco position quantization bits (default: error below 1/25 voxel)")
      ->check(CLI::Range(1, 30));
  app.add_option("--draco-level", dracoLevel, "Draco compression level, 0 fastest .. 10 smallest")->check(CLI::Range(0, 10))
      ->capture_default_str();
  app.add_option("--label-volume", labelVolume, "write the label volume as NRRD (.nrrd; *.seg.nrrd opens as a Slicer "
                                                "segmentation) plus its label table (.ctbl)");
  app.add_option("--report", report, "write a JSON report: per-feature statistics, parameters, device, timings");
  app.add_option("--preview", preview, "render a picture of the surfaces on the Vulkan device (.png)");
  app.add_option("--view", view, "preview camera")
      ->check(CLI::IsMember({"oblique", "front", "back", "left", "right", "top", "bottom"}))
      ->capture_default_str();
  app.add_option("--preview-size", previewSize, "W H: preview size in pixels (default 960 720)")->expected(2);
  app.add_flag("--json-progress", jsonProgress, "progress as JSON lines on stderr, for scripts");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : exitCode(Errc::InvalidArgument);
  }

  if (listRois) {
    auto listed = cli::printRoiList(input, roiPatterns);
    return listed ? 0 : fail(listed.error());
  }
  if (outDir.empty()) return fail({Errc::InvalidArgument, "-o/--output is required (or use --list-rois)"});

  using Clock = std::chrono::steady_clock;
  auto t0 = Clock::now();
  std::vector<StageTime> timings;
  auto lap = [&](const char* stage) {
    const auto now = Clock::now();
    timings.push_back({stage, std::chrono::duration<double>(now - t0).count()});
    t0 = now;
  };

  // Check every output before the work, so a typo does not cost a whole run. `-o x.glb`
  // writes one GLB scene; otherwise -o is a directory for the per-feature files.
  cli::OutputPlan plan;
  if (fs::path(outDir).extension() == ".glb" || fs::path(outDir).extension() == ".GLB") {
    if (!formats.empty()) return fail({Errc::InvalidArgument, "--format needs an output directory, not the file " + outDir});
    plan.glbFile = outDir;
  } else {
    plan.dir = outDir;
    if (formats.empty()) formats = {"ply"};
    for (const std::string& f : formats) {
      auto format = cli::parseMeshFormat(f);
      if (!format) return fail(format.error());
      plan.formats.push_back(*format);
    }
    plan.sceneName = fs::path(input).stem().string();
  }
  plan.draco = !noDraco;
  plan.dracoOptions.quantizationBits = dracoBits;
  plan.dracoOptions.compressionLevel = dracoLevel;
  plan.labelVolume = labelVolume;
  plan.report = report;
  plan.preview = preview;
  if (auto ok = cli::checkOutputs(plan); !ok) return fail(ok.error());
  cli::Progress progress(cli::chooseProgressMode(quiet, jsonProgress));
  progress.begin("read");

  auto loaded = cli::readInput(input, {roiPatterns, reference});
  if (!loaded) return fail(loaded.error());
  for (const std::string& w : loaded->warnings) std::fprintf(stderr, "scansurf: warning: %s\n", w.c_str());
  if (!quiet)
    for (const std::string& note : loaded->notes) std::printf("%s\n", note.c_str());
  Result<ContourSet> contours = std::move(loaded->contours);
  lap("read");
  progress.done("read", timings.back().seconds);
  progress.begin("device");

  EngineOptions engineOptions;
  engineOptions.device = device;
  engineOptions.validation = validation;
  auto engine = Engine::create(engineOptions);
  if (!engine) return fail(engine.error());
  lap("device");
  progress.done("device", timings.back().seconds);
  const DeviceInfo& info = engine->device();
  if (!quiet) std::printf("device: %s (%s, %s)\n", info.name.c_str(), info.type.c_str(), info.driver.c_str());

  BuildOptions options;
  options.grid.voxelSize = voxelSize;
  if (gridSize.size() == 2) options.grid.nx = gridSize[0], options.grid.ny = gridSize[1];
  options.convention = convention == "partition" ? SurfaceConvention::Partition : SurfaceConvention::Enclosing;
  options.threads = threads;
  options.smoothing = smoothing;
  options.smoothing.enabled = !noSmooth;
  options.smoothing.contourFit = !noContourFit;
  options.smoothing.junctions = !noJunctions;
  options.grid.reference = loaded->reference;
  options.onStage = [&](const std::string& stage, double seconds) { progress.done(stage, seconds); };
  progress.begin("surfaces");
  auto built = engine->build(*contours, options);
  if (!built) return fail(built.error());
  timings.insert(timings.end(), built->timings.begin(), built->timings.end());
  t0 = Clock::now();

  // Each feature's statistics, once, for the report and the summary (when either is wanted).
  std::vector<MeshStats> stats;
  if (!quiet || !report.empty())
    for (const FeatureSurface& f : built->surfaces.features)
      stats.push_back(computeMeshStats(built->surfaces.mesh.positions, f.triangles));

  cli::Staging staging;
  auto perFeature = cli::writeSurfaceOutputs(staging, plan, *contours, built->surfaces, built->volume);
  if (!perFeature) return fail(perFeature.error());
  built->warnings.insert(built->warnings.end(), perFeature->warnings.begin(), perFeature->warnings.end());
  lap("write");
  progress.done("write", timings.back().seconds);
  if (!preview.empty()) {
    progress.begin("preview");
    PreviewOptions previewOptions;
    previewOptions.view = *parseViewPreset(view);
    if (previewSize.size() == 2) previewOptions.width = previewSize[0], previewOptions.height = previewSize[1];
    previewOptions.colors = featureColors(*contours);
    // Features that enclose others are drawn translucent, so that what they hold shows.
    previewOptions.opacity.assign(contours->features.size(), 1.0f);
    for (int parent : built->nesting.parent)
      if (parent >= 0) previewOptions.opacity[static_cast<std::size_t>(parent)] = 0.3f;
    auto picture = engine->renderPreview(built->surfaces, previewOptions);
    if (!picture) return fail(picture.error());
    auto staged = staging.path(preview);
    if (!staged) return fail(staged.error());
    if (auto ok = cli::named(writePng(*staged, picture->width, picture->height, picture->rgba), *staged, preview); !ok)
      return fail(ok.error());
    lap("preview");
    progress.done("preview", timings.back().seconds);
  }
  cli::RunFacts facts{input, &*contours, &*built, &info, options.convention, std::move(stats), timings};
  if (!report.empty()) {
    std::vector<fs::path> outputs = staging.targets();
    outputs.push_back(report);
    const RunReport r = cli::makeRunReport(
        facts,
        {{"convention", cli::conventionName(options.convention)},
         {"voxel_size", voxelSize},
         {"grid_nx", static_cast<double>(options.grid.nx)},
         {"grid_ny", static_cast<double>(options.grid.ny)},
         {"threads", static_cast<double>(threads)},
         {"smoothing", options.smoothing.enabled},
         {"draco", !noDraco},
         {"draco_bits", static_cast<double>(dracoBits)},  // 0: from draco_max_error
         {"draco_max_error", dracoBits ? 0.0 : defaultQuantizationError(built->volume.grid)},
         {"draco_level", static_cast<double>(dracoLevel)},
         {"validation", validation}},
        perFeature->files, outputs);
    auto staged = staging.path(report);
    if (!staged) return fail(staged.error());
    if (auto ok = cli::named(writeReportJson(*staged, r), *staged, report); !ok) return fail(ok.error());
  }
  // With --validation, a validation message means the device's results are suspect: write nothing.
  if (engine->validationMessageCount() > 0)
    return fail({Errc::Vulkan, std::to_string(engine->validationMessageCount()) + " Vulkan validation message(s); see above"});
  auto written = staging.commit();
  if (!written) return fail(written.error());
  progress.finish(0);

  for (const std::string& w : built->warnings) std::fprintf(stderr, "scansurf: warning: %s\n", w.c_str());
  if (quiet) return 0;

  cli::printSummary(facts, *written, outDir);
  return 0;
}
