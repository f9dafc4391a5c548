#include "summary.h"

#include <cstdio>


namespace fs = std::filesystem;

namespace scansurf::cli {

const char* conventionName(SurfaceConvention c) { return c == SurfaceConvention::Enclosing ? "enclosing" : "partition"; }

void printSummary(const RunFacts& facts, const std::vector<fs::path>& written, const std::string& outDir) {
  const ContourSet& set = *facts.contours;
  const BuildResult& built = *facts.built;
  const Grid& g = built.volume.grid;
  std::printf("grid: %d x %d x %d voxels (%g x %g %s pixels, %d slices, 1-voxel background border)\n", g.nx, g.ny, g.nz,
              g.spacingX, g.spacingY, set.units.c_str(), g.nz - 2);
  std::printf("nesting order (%s, innermost first):", built.nesting.userOrder ? "from input" : "computed");
  for (int f : built.nesting.order) std::printf(" %s", set.features[static_cast<std::size_t>(f)].name.c_str());
  std::printf("\nsurfaces (%s convention): %zu vertices, %zu triangles in the multi-label mesh\n",
              conventionName(facts.convention), built.surfaces.mesh.vertexCount(), built.surfaces.mesh.triangleCount());
  std::printf("  %-20s %6s %10s %14s %10s %6s %s\n", "feature", "label", "triangles", ("volume " + set.units + "3").c_str(),
              "components", "genus", "closed");
  for (std::size_t f = 0; f < set.features.size(); ++f) {
    const MeshStats& s = facts.stats[f];
    std::printf("  %-20s %6d %10zu %14.1f %10d %6d %s\n", set.features[f].name.c_str(), labelOfFeature(static_cast<int>(f)),
                s.triangles, s.volume, s.components, s.genus, s.closed && s.manifold && s.oriented ? "yes" : "NO");
  }
  double total = 0;
  std::printf("time:");
  for (const StageTime& t : facts.timings) {
    std::printf(" %s %.3f s;", t.stage.c_str(), t.seconds);
    total += t.seconds;
  }
  std::printf(" total %.3f s\nwrote %zu files", total, written.size());
  if (written.size() <= 4)  // e.g. -o x.glb --preview x.png: name them
    for (const fs::path& p : written) std::printf(" %s", p.c_str());
  else
    std::printf(" to %s", outDir.c_str());
  std::printf("\n");
}

}  // namespace scansurf::cli
