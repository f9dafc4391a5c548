// scansurf_bench: the benchmark driver (issue 6).
//
//   scansurf_bench generate OUTDIR [SET...]    writes OUTDIR/<set>.json and OUTDIR/<set>.dcm (RTSTRUCT)
//                                              for the sets pelvis, head-neck, em-cells
//   scansurf_bench run INPUT.json PIXELS [--repeat N] [--no-smooth] [--interpolate auto|off|N] [--snap F] [--remesh]
//
// `run` times every stage of the method on one input (parse, nesting, grid, scan conversion,
// classification, assembly, smoothing and remeshing when enabled, feature surfaces, writing PLY), reports
// peak resident memory, the label volume and mesh sizes, and the floor: one copy of a buffer
// the size of the label volume. It prints one JSON object on stdout for the table script.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/structure_sets.h"
#include "io/contours_json.h"
#include "io/ply_writer.h"
#include "scansurf/engine.h"
#include "scansurf/process.h"
#include "support/rtstruct_builder.h"

namespace fs = std::filesystem;
using namespace scansurf;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

double peakRssMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

int generate(const fs::path& outDir, std::vector<std::string> names) {
  if (names.empty()) names = bench::structureSetNames();
  fs::create_directories(outDir);
  for (const std::string& name : names) {
    bench::StructureSetSpec spec = bench::makeStructureSet(name);
    if (spec.contours.features.empty()) {
      std::fprintf(stderr, "unknown set %s\n", name.c_str());
      return 2;
    }
    std::size_t contours = 0, points = 0;
    for (const Feature& f : spec.contours.features)
      for (const FeatureSlice& s : f.slices) {
        contours += s.contours.size();
        for (const Contour& c : s.contours) points += c.points.size();
      }
    const fs::path path = outDir / (name + ".json");
    if (auto ok = writeContoursJson(spec.contours, path); !ok) {
      std::fprintf(stderr, "%s\n", ok.error().message.c_str());
      return 4;
    }
    test::TestRtStruct rt;
    for (std::size_t f = 0; f < spec.contours.features.size(); ++f)
      rt.rois.push_back(test::roiFromFeature(spec.contours.features[f], static_cast<int>(f) + 1));
    try {
      test::writeTestRtStruct(rt, outDir / (name + ".dcm"));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 4;
    }
    std::printf("%s: %zu structures, %zu contours, %zu points -> %s\n", name.c_str(), spec.contours.features.size(), contours,
                points, path.c_str());
  }
  return 0;
}

int run(const fs::path& input, int pixels, int repeat, bool smooth, int interpolate, bool remesh, bool simplify, double snap) {
  std::string json = "{";
  auto add = [&](const std::string& key, double value) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4f", value);
    json += (json.size() > 1 ? ", \"" : "\"") + key + "\": " + buf;
  };

  auto t0 = Clock::now();
  auto contours = readContoursJson(input);
  if (!contours) {
    std::fprintf(stderr, "%s\n", contours.error().message.c_str());
    return 3;
  }
  const double parse = seconds(t0, Clock::now());
  auto engine = Engine::create({});
  if (!engine) {
    std::fprintf(stderr, "%s\n", engine.error().message.c_str());
    return 5;
  }

  BuildOptions options = BuildOptions::recommended();  // the command-line tool's defaults, less what was asked
  options.smoothing.enabled = smooth;
  options.smoothing.snap = snap;
  options.interpolation.factor = interpolate;
  options.simplification.enabled = smooth && simplify;
  options.remeshing.enabled = smooth && remesh;
  options.keepLabelVolume = false;  // as the command-line tool: the labels stay on the device
  BuildResult best;
  double bestTotal = 1e30;
  for (int r = 0; r < std::max(1, repeat); ++r) {
    // Square pixels, `pixels` along the longer side, as the Slicer route is given.
    auto probe = makeGrid(*contours, GridOptions{});  // the default grid gives the extent
    if (!probe) {
      std::fprintf(stderr, "%s\n", probe.error().message.c_str());
      return 3;
    }
    const double extent = std::max((probe->nx - 3) * probe->spacingX, (probe->ny - 3) * probe->spacingY);
    options.grid.voxelSize = extent / (pixels - 3);
    auto built = engine->build(*contours, options);
    if (!built) {
      std::fprintf(stderr, "%s\n", built.error().message.c_str());
      return 6;
    }
    double total = 0;
    for (const StageTime& t : built->timings) total += t.seconds;
    if (total < bestTotal) bestTotal = total, best = std::move(built).value();
  }

  const fs::path outDir = fs::temp_directory_path() / ("scansurf-bench-" + std::to_string(::getpid()));
  fs::create_directories(outDir);
  t0 = Clock::now();
  SurfaceCompactor compactor(best.surfaces.mesh);
  for (std::size_t f = 0; f < best.surfaces.features.size(); ++f) {
    auto compact = compactor.compact(best.surfaces.features[f]);
    auto ok = compact ? writeSurfacePly(outDir / ("f" + std::to_string(f) + ".ply"), *compact, static_cast<int>(f))
                      : Result<void>(std::move(compact).takeError());
    if (!ok) {
      std::fprintf(stderr, "%s\n", ok.error().message.c_str());
      return 4;
    }
  }
  const double write = seconds(t0, Clock::now());
  fs::remove_all(outDir);
  const double peakRss = peakRssMiB();  // the run's, before the floor's own buffers below

  // The floor: one copy of a buffer the size of the label volume (best of 5).
  const std::size_t voxels = best.volume.grid.voxelCount();
  const std::size_t volumeBytes = voxels * sizeof(Label);
  const std::vector<Label> source(voxels, 1);
  std::vector<Label> copy(voxels);
  double floor = 1e30;
  for (int r = 0; r < 5; ++r) {
    t0 = Clock::now();
    std::memcpy(copy.data(), source.data(), volumeBytes);
    floor = std::min(floor, seconds(t0, Clock::now()));
  }

  std::size_t featureTriangles = 0;
  for (const FeatureSurface& f : best.surfaces.features) featureTriangles += f.triangleCount();
  const Grid& g = best.volume.grid;
  const std::size_t meshBytes = best.surfaces.mesh.positions.size() * sizeof(float) +
                                best.surfaces.mesh.triangles.size() * sizeof(std::uint32_t) +
                                best.surfaces.mesh.labels.size() * sizeof(Label) + featureTriangles * 3 * sizeof(std::uint32_t);

  add("parse", parse);
  double total = parse + write;
  for (const StageTime& t : best.timings) {
    add(t.stage, t.seconds);
    total += t.seconds;
  }
  add("write", write);
  add("total", total);
  add("floor_copy", floor);
  add("peak_rss_mib", peakRss);
  add("label_volume_mib", static_cast<double>(volumeBytes) / (1 << 20));
  add("mesh_mib", static_cast<double>(meshBytes) / (1 << 20));
  add("nx", g.nx);
  add("ny", g.ny);
  add("nz", g.nz);
  add("voxel_size", g.spacingX);
  add("origin_x", g.originX);
  add("origin_y", g.originY);
  add("structures", static_cast<double>(contours->features.size()));
  add("mesh_triangles", static_cast<double>(best.surfaces.mesh.triangleCount()));
  add("feature_triangles", static_cast<double>(featureTriangles));
  if (const RemeshReport& rr = best.surfaces.remeshing; rr.ran) {
    add("remesh_triangles_before", static_cast<double>(rr.trianglesBefore));
    add("remesh_min_angle_before", rr.anglesBefore.min);
    add("remesh_p5_angle_before", rr.anglesBefore.p5);
    add("remesh_min_angle", rr.anglesAfter.min);
    add("remesh_p5_angle", rr.anglesAfter.p5);
    add("remesh_mean_angle", rr.anglesAfter.mean);
    add("remesh_max_distance", rr.maxDistance);
    add("remesh_chunks", static_cast<double>(rr.chunks));
    add("remesh_bands", static_cast<double>(rr.bands));
  }
  json += ", \"device\": \"" + engine->device().name + "\"}";
  std::printf("%s\n", json.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  scansurf::keepFreedMemoryForReuse();  // as the command-line tool does at start
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() >= 2 && args[0] == "generate") return generate(args[1], {args.begin() + 2, args.end()});
  if (args.size() >= 3 && args[0] == "run") {
    int repeat = 1, interpolate = InterpolationOptions::kAuto;
    bool smooth = true, remesh = false, simplify = true;
    double snap = SmoothingOptions{}.snap;
    for (std::size_t a = 3; a < args.size(); ++a) {
      if (args[a] == "--repeat" && a + 1 < args.size()) repeat = std::stoi(args[++a]);
      if (args[a] == "--no-smooth") smooth = false;
      if (args[a] == "--remesh") remesh = true;
      if (args[a] == "--no-simplify") simplify = false;
      if (args[a] == "--snap" && a + 1 < args.size()) snap = std::stod(args[++a]);
      if (args[a] == "--interpolate" && a + 1 < args.size()) {
        const std::string& v = args[++a];
        interpolate = v == "auto" ? InterpolationOptions::kAuto : v == "off" ? 1 : std::stoi(v);
      }
    }
    return run(args[1], std::stoi(args[2]), repeat, smooth, interpolate, remesh, simplify, snap);
  }
  std::fprintf(stderr,
               "usage: scansurf_bench generate OUTDIR [SET...] | run INPUT.json PIXELS [--repeat N] [--no-smooth] "
               "[--interpolate auto|off|N] [--snap F] [--no-simplify] [--remesh]\n");
  return 2;
}
