// scansurf benchmark: constrained smoothing of a large multi-label mesh (issue 3).
// Builds a sphere of radius R mm (default 81) at 0.5 mm pixels and 1 mm slices with the CPU
// pipeline (reference scan conversion and classification, then assembly), over 2 M
// triangles, and prints the smoothing time at 1 thread and at all threads.
//
//   scansurf_bench_smoothing [RADIUS_MM]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/parallel.h"
#include "geometry/assembly.h"
#include "geometry/cell_cases.h"
#include "geometry/smoothing.h"
#include "scansurf/nesting.h"
#include "support/reference_rasterizer.h"
#include "support/shapes.h"

using namespace scansurf;

int main(int argc, char** argv) {
  const double radius = argc > 1 ? std::atof(argv[1]) : 81.0;
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); };
  const ContourSet set = sphereContours(radius, 1.0);
  GridOptions gridOptions;
  gridOptions.voxelSize = 0.5;
  auto grid = makeGrid(set, gridOptions);
  if (!grid) {
    std::fprintf(stderr, "%s\n", grid.error().message.c_str());
    return 1;
  }
  auto t = Clock::now();
  const LabelVolume volume = test::referenceScanConvert(set, *grid, computeNesting(set).order, 8);
  const MultiLabelMesh raw = assembleMesh(*grid, classifyCellsReference(volume));
  std::printf("sphere r %.0f mm, 0.5 mm pixels, 1 mm slices: grid %d x %d x %d, %zu vertices, %zu triangles (built in %.1f s)\n",
              radius, grid->nx, grid->ny, grid->nz, raw.vertexCount(), raw.triangleCount(), seconds(t));
  SmoothingOptions options;
  options.enabled = true;
  for (int threads : {1, 0}) {
    MultiLabelMesh mesh = raw;
    t = Clock::now();
    const SmoothingReport r = smoothMesh(mesh, *grid, &set, options, threads);
    const double s = seconds(t);
    double sum = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
      sum += std::abs(std::hypot(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]) - radius);
    std::printf("smoothing, %d thread(s), %d sweeps: %.2f s (%zu sheet, %zu fitted, %zu junction, %zu fixed vertices; "
                "mean vertex distance to the sphere %.4f mm)\n",
                threads == 0 ? defaultThreadCount() : threads, options.iterations, s, r.sheet, r.fitted, r.curve, r.fixed,
                sum / static_cast<double>(mesh.vertexCount()));
  }
  return 0;
}
