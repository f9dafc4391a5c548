// scansurf: writes the bundled example inputs from the shape generators.
// Usage: scansurf_make_examples OUTDIR [SLICE_MM]
//   writes OUTDIR/phantom.json, or with a slice spacing other than 2.5 mm the same shapes
//   sliced at it as OUTDIR/phantom-<SLICE_MM>mm.json (docs' interpolation pictures).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <filesystem>

#include "io/contours_json.h"
#include "support/shapes.h"

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::fprintf(stderr, "usage: %s OUTDIR [SLICE_MM]\n", argv[0]);
    return 2;
  }
  const double spacing = argc == 3 ? std::atof(argv[2]) : 2.5;
  if (!(spacing > 0.1 && spacing < 50)) {
    std::fprintf(stderr, "slice spacing must be between 0.1 and 50 mm\n");
    return 2;
  }
  std::string name = "phantom.json";
  if (argc == 3) name = std::string("phantom-").append(argv[2]).append("mm.json");
  const std::filesystem::path dir = argv[1];
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  scansurf::ContourSet phantom = scansurf::phantomContours(spacing);
  phantom.source = name;
  const auto written = scansurf::writeContoursJson(phantom, dir / name);
  if (!written) {
    std::fprintf(stderr, "%s\n", written.error().message.c_str());
    return 1;
  }
  std::printf("wrote %s\n", (dir / name).string().c_str());
  return 0;
}
