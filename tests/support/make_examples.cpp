// scansurf: writes the bundled example inputs from the shape generators.
// Usage: scansurf_make_examples OUTDIR   (writes OUTDIR/phantom.json)
#include <cstdio>
#include <filesystem>

#include "io/contours_json.h"
#include "support/shapes.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  scansurf::ContourSet phantom = scansurf::phantomContours();
  phantom.source = "phantom.json";
  const auto written = scansurf::writeContoursJson(phantom, dir / "phantom.json");
  if (!written) {
    std::fprintf(stderr, "%s\n", written.error().message.c_str());
    return 1;
  }
  std::printf("wrote %s\n", (dir / "phantom.json").string().c_str());
  return 0;
}
