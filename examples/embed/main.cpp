// Reads a contour set, builds smoothed separating surfaces on a Vulkan device of scansurf's
// own, and writes them as one GLB scene, through nothing but <scansurf/scansurf.h>.
//
//   embed_example CONTOURS(.json|RTSTRUCT) OUT.glb
#include <scansurf/scansurf.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s CONTOURS OUT.glb\n", argv[0]);
    return 2;
  }
  auto contours = scansurf::readContours(argv[1]);  // Result<ContourSet>
  if (!contours) {
    std::fprintf(stderr, "%s\n", contours.error().message.c_str());
    return 3;
  }
  auto engine = scansurf::Engine::create({});  // Result<Engine>
  if (!engine) {
    std::fprintf(stderr, "%s\n", engine.error().message.c_str());
    return 5;
  }
  const auto options = scansurf::BuildOptions::recommended();  // what the command line does by default
  auto built = engine->build(*contours, options);              // Result<BuildResult>
  if (!built) {
    std::fprintf(stderr, "%s\n", built.error().message.c_str());
    return 6;
  }
  std::printf("scansurf %s on %s\n", scansurf::version(), engine->device().name.c_str());
  for (const auto& f : built->surfaces.features) {
    const auto stats = scansurf::computeMeshStats(built->surfaces.mesh.positions, f.triangles);
    std::printf("  %-12s %8zu triangles  volume %10.1f %s3  %s\n",
                contours->features[static_cast<std::size_t>(f.feature)].name.c_str(), f.triangleCount(), stats.volume,
                contours->units.c_str(), stats.closed && stats.oriented ? "closed" : "OPEN");
  }
  if (auto written = scansurf::writeScene(argv[2], *contours, built->surfaces); !written) {
    std::fprintf(stderr, "%s\n", written.error().message.c_str());
    return 4;
  }
  std::printf("wrote %s\n", argv[2]);
  return 0;
}
