#include "summary.h"

#include <cstdio>

#include "scansurf/palette.h"

namespace fs = std::filesystem;

namespace scansurf::cli {

const char* conventionName(SurfaceConvention c) { return c == SurfaceConvention::Enclosing ? "enclosing" : "partition"; }

RunReport makeRunReport(const RunFacts& facts,
                        std::vector<std::pair<std::string, std::variant<bool, double, std::string>>> parameters,
                        const std::vector<std::vector<fs::path>>& files, const std::vector<fs::path>& outputs) {
  const ContourSet& contours = *facts.contours;
  const BuildResult& built = *facts.built;
  RunReport r;
  r.input = facts.input;
  r.units = contours.units;
  r.parameters = std::move(parameters);
  r.deviceName = facts.device->name, r.deviceType = facts.device->type, r.driver = facts.device->driver;
  r.grid = built.volume.grid;
  for (int f : built.nesting.order) r.nestingOrder.push_back(contours.features[static_cast<std::size_t>(f)].name);
  r.userOrder = built.nesting.userOrder;
  r.meshVertices = built.surfaces.mesh.vertexCount();
  r.meshTriangles = built.surfaces.mesh.triangleCount();
  const std::vector<Rgb> colors = featureColors(contours);
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    ReportFeature rf{contours.features[f].name, labelOfFeature(static_cast<int>(f)), colors[f], facts.stats[f], {}};
    for (const fs::path& p : files[f]) rf.files.push_back(p.string());
    r.features.push_back(std::move(rf));
  }
  for (const StageTime& t : facts.timings) r.timings.emplace_back(t.stage, t.seconds);
  for (const fs::path& p : outputs) r.outputs.push_back(p.string());
  r.warnings = built.warnings;
  return r;
}

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
