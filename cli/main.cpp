// scansurf: planar contours in, separating surfaces out.
//
//   scansurf INPUT.json -o OUTDIR [--voxel-size MM | --grid NX NY] [--convention enclosing|partition]
//
// Exit codes: 0 success; 2 bad command line or option; 3 invalid input file; 4 file I/O
// error; 5 no usable Vulkan device; 6 Vulkan failure; 7 internal error.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "io/atomic_file.h"
#include "io/contours_json.h"
#include "dicom_input.h"
#include "outputs.h"
#include "scansurf/engine.h"

namespace fs = std::filesystem;
using namespace scansurf;

namespace {

int exitCode(Errc code) { return static_cast<int>(code) + 1; }

int fail(const Error& error) {
  std::fprintf(stderr, "scansurf: error: %s\n", error.message.c_str());
  return exitCode(error.code);
}

const char* conventionName(SurfaceConvention c) { return c == SurfaceConvention::Enclosing ? "enclosing" : "partition"; }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"scansurf: separating surfaces from planar contours (scanline surfacing on Vulkan)"};
  app.footer(
      "Outputs: OUTDIR/<feature>.ply (one closed surface per feature, outward), OUTDIR/multilabel.ply\n"
      "(every separating surface, each face with its two labels; label = feature index + 1).\n"
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
  app.add_option("--threads", threads, "CPU threads for assembly (default: all)")->check(CLI::NonNegativeNumber);
  app.add_flag("-q,--quiet", quiet, "print errors only");
  // DICOM RTSTRUCT input (issue 5).
  std::vector<std::string> roiPatterns;
  bool listRois = false;
  std::string reference;
  app.add_option("--roi", roiPatterns, "RTSTRUCT: surface only the ROIs whose name matches (glob, case-insensitive; repeatable)")
      ->expected(1)
      ->take_all();
  app.add_flag("--list-rois", listRois, "RTSTRUCT: list the file's ROIs and exit");
  app.add_option("--reference", reference, "RTSTRUCT: folder of a CT series; the label volume lies on its voxel grid");
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

  // Check the output before the work, so a typo does not cost a whole run.
  if (auto ok = ensureWritableDirectory(outDir); !ok) return fail(ok.error());

  auto loaded = cli::readInput(input, {roiPatterns, reference});
  if (!loaded) return fail(loaded.error());
  for (const std::string& w : loaded->warnings) std::fprintf(stderr, "scansurf: warning: %s\n", w.c_str());
  if (!quiet)
    for (const std::string& note : loaded->notes) std::printf("%s\n", note.c_str());
  Result<ContourSet> contours = std::move(loaded->contours);
  lap("read");

  EngineOptions engineOptions;
  engineOptions.device = device;
  engineOptions.validation = validation;
  auto engine = Engine::create(engineOptions);
  if (!engine) return fail(engine.error());
  lap("device");
  const DeviceInfo& info = engine->device();
  if (!quiet) std::printf("device: %s (%s, %s)\n", info.name.c_str(), info.type.c_str(), info.driver.c_str());

  BuildOptions options;
  options.grid.voxelSize = voxelSize;
  if (gridSize.size() == 2) options.grid.nx = gridSize[0], options.grid.ny = gridSize[1];
  options.convention = convention == "partition" ? SurfaceConvention::Partition : SurfaceConvention::Enclosing;
  options.threads = threads;
  options.grid.reference = loaded->reference;
  auto built = engine->build(*contours, options);
  if (!built) return fail(built.error());
  timings.insert(timings.end(), built->timings.begin(), built->timings.end());
  t0 = Clock::now();

  auto written = cli::writeOutputs(outDir, *contours, built->surfaces);
  if (!written) return fail(written.error());
  lap("write");

  if (engine->validationMessageCount() > 0)
    return fail({Errc::Vulkan, std::to_string(engine->validationMessageCount()) + " Vulkan validation message(s); see above"});
  for (const std::string& w : built->warnings) std::fprintf(stderr, "scansurf: warning: %s\n", w.c_str());
  if (quiet) return 0;

  const Grid& g = built->volume.grid;
  const ContourSet& set = *contours;
  std::printf("grid: %d x %d x %d voxels (%g x %g %s pixels, %d slices, 1-voxel background border)\n", g.nx, g.ny, g.nz,
              g.spacingX, g.spacingY, set.units.c_str(), g.nz - 2);
  std::printf("nesting order (%s, innermost first):", built->nesting.userOrder ? "from input" : "computed");
  for (int f : built->nesting.order) std::printf(" %s", set.features[static_cast<std::size_t>(f)].name.c_str());
  std::printf("\nsurfaces (%s convention): %zu vertices, %zu triangles in the multi-label mesh\n", conventionName(options.convention),
              built->surfaces.mesh.vertexCount(), built->surfaces.mesh.triangleCount());
  std::printf("  %-20s %6s %10s %14s %10s %6s %s\n", "feature", "label", "triangles", ("volume " + set.units + "3").c_str(),
              "components", "genus", "closed");
  for (std::size_t f = 0; f < set.features.size(); ++f) {
    const MeshStats s = computeMeshStats(built->surfaces.mesh.positions, built->surfaces.features[f].triangles);
    std::printf("  %-20s %6d %10zu %14.1f %10d %6d %s\n", set.features[f].name.c_str(), labelOfFeature(static_cast<int>(f)),
                s.triangles, s.volume, s.components, s.genus, s.closed && s.manifold && s.oriented ? "yes" : "NO");
  }
  double total = 0;
  std::printf("time:");
  for (const StageTime& t : timings) {
    std::printf(" %s %.3f s;", t.stage.c_str(), t.seconds);
    total += t.seconds;
  }
  std::printf(" total %.3f s\nwrote %zu files to %s\n", total, written->size(), outDir.c_str());
  return 0;
}
