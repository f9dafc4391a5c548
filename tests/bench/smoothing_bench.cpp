// scansurf benchmark: constrained smoothing of a large multi-label mesh (issues 3 and 12).
//
//   scansurf_bench_smoothing [RADIUS_MM]            a sphere of radius R mm (default 81) at 0.5 mm
//                                                   pixels and 1 mm slices, built with the CPU
//                                                   pipeline: over 2 M triangles
//   scansurf_bench_smoothing INPUT.json NX NY       a contour set on an NX x NY grid (as the CLI's
//                                                   --grid NX NY), one partition, built by the
//                                                   Engine on the default Vulkan device
//
// Smooths the raw mesh at 1 thread and at all threads and prints, for each, the wall time, the
// process's CPU time and the sweeps the smoother ran; then how far the two results lie apart
// (they must be equal). Set SCANSURF_SMOOTH_BENCH_REPEAT to repeat each run and keep the best.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <optional>

#include "core/parallel.h"
#include "geometry/extraction/assembly.h"
#include "geometry/extraction/cell_cases.h"
#include "geometry/smoothing/smooth_mesh.h"
#include "io/contours_json.h"
#include "scansurf/engine.h"
#include "scansurf/nesting.h"
#include "support/reference_rasterizer.h"
#include "support/shapes.h"

using namespace scansurf;

namespace {

using Clock = std::chrono::steady_clock;

double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Input {
  ContourSet set;
  Grid grid;
  MultiLabelMesh raw;
};

std::optional<Input> sphere(double radius) {
  Input in;
  in.set = sphereContours(radius, 1.0);
  GridOptions gridOptions;
  gridOptions.voxelSize = 0.5;
  auto grid = makeGrid(in.set, gridOptions);
  if (!grid) {
    std::fprintf(stderr, "%s\n", grid.error().message.c_str());
    return std::nullopt;
  }
  in.grid = *grid;
  const LabelVolume volume = test::referenceScanConvert(in.set, in.grid, computeNesting(in.set).order, 8);
  in.raw = assembleMesh(in.grid, classifyCellsReference(volume));
  std::printf("sphere r %.0f mm, 0.5 mm pixels, 1 mm slices: ", radius);
  return in;
}

std::optional<Input> contourSet(const char* path, int nx, int ny) {
  Input in;
  auto contours = readContoursJson(path);
  if (!contours) {
    std::fprintf(stderr, "%s\n", contours.error().message.c_str());
    return std::nullopt;
  }
  in.set = std::move(contours).value();
  auto engine = Engine::create({});
  if (!engine) {
    std::fprintf(stderr, "%s\n", engine.error().message.c_str());
    return std::nullopt;
  }
  BuildOptions options;
  options.grid.nx = nx;
  options.grid.ny = ny;
  options.overlaps = OverlapMode::Partition;  // one label volume, one grid, one mesh
  auto built = engine->build(in.set, options);
  if (!built) {
    std::fprintf(stderr, "%s\n", built.error().message.c_str());
    return std::nullopt;
  }
  in.grid = built->volume.grid;
  in.raw = std::move(built->surfaces.mesh);
  std::printf("%s, one partition: ", path);
  return in;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Input> in =
      argc > 3 ? contourSet(argv[1], std::atoi(argv[2]), std::atoi(argv[3])) : sphere(argc > 1 ? std::atof(argv[1]) : 81.0);
  if (!in) return 1;
  std::printf("grid %d x %d x %d, %zu vertices, %zu triangles\n", in->grid.nx, in->grid.ny, in->grid.nz, in->raw.vertexCount(),
              in->raw.triangleCount());
  const char* repeatEnv = std::getenv("SCANSURF_SMOOTH_BENCH_REPEAT");
  const int repeat = repeatEnv ? std::max(1, std::atoi(repeatEnv)) : 1;
  SmoothingOptions options;
  options.enabled = true;
  std::vector<float> first;
  for (int threads : {1, 0}) {
    double bestWall = 1e30, bestCpu = 1e30;
    MultiLabelMesh mesh;
    SmoothingReport r;
    for (int k = 0; k < repeat; ++k) {
      mesh = in->raw;
      const auto t = Clock::now();
      const double c = cpuSeconds();
      r = smoothMesh(mesh, in->grid, &in->set, options, threads);
      bestWall = std::min(bestWall, std::chrono::duration<double>(Clock::now() - t).count());
      bestCpu = std::min(bestCpu, cpuSeconds() - c);
    }
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a of the positions' bytes: equal results, equal hashes
    for (float x : mesh.positions) {
      std::uint32_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      for (int k = 0; k < 4; ++k) hash = (hash ^ ((bits >> (8 * k)) & 0xff)) * 1099511628211ull;
    }
    std::printf(
        "smoothing, %d thread(s): %.2f s wall, %.2f s CPU, %d sweeps (%zu sheet, %zu fitted, %zu junction, %zu fixed vertices), "
        "positions %016llx\n",
        threads == 0 ? defaultThreadCount() : threads, bestWall, bestCpu, r.sweeps, r.sheet, r.fitted, r.curve, r.fixed,
        static_cast<unsigned long long>(hash));
    if (first.empty())
      first = mesh.positions;
    else
      std::printf("results at 1 and %d threads %s\n", defaultThreadCount(), first == mesh.positions ? "equal" : "DIFFER");
  }
  return 0;
}
