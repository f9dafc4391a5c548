// scansurf: writes the bundled example inputs from the shape generators.
// Usage: scansurf_make_examples OUTDIR [SLICE_MM | drawn-pelvis | drawn-pelvis-ptv]
//   writes OUTDIR/phantom.json, or with a slice spacing other than 2.5 mm the same shapes
//   sliced at it as OUTDIR/phantom-<SLICE_MM>mm.json (docs' interpolation pictures), or the
//   independently drawn prostate and rectum in BODY (support/drawn_shapes.h), with a PTV over
//   both for drawn-pelvis-ptv (docs' overlap pictures).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "io/contours_json.h"
#include "support/drawn_shapes.h"
#include "support/shapes.h"

// Writes the set as DIR/<its source>; 0 on success.
static int write(const scansurf::ContourSet& set, const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const auto written = scansurf::writeContoursJson(set, dir / set.source);
  if (!written) {
    std::fprintf(stderr, "%s\n", written.error().message.c_str());
    return 1;
  }
  std::printf("wrote %s\n", (dir / set.source).string().c_str());
  return 0;
}

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::fprintf(stderr, "usage: %s OUTDIR [SLICE_MM]\n", argv[0]);
    return 2;
  }
  const std::string what = argc == 3 ? argv[2] : "";
  if (what == "drawn-pelvis" || what == "drawn-pelvis-ptv") {
    scansurf::DrawnPelvisOptions options;
    options.planningVolume = what == "drawn-pelvis-ptv";
    scansurf::ContourSet drawn = scansurf::drawnPelvisContours(options);
    scansurf::roundCoordinates(drawn, 0.01);
    drawn.source = what + ".json";
    return write(drawn, argv[1]);
  }
  const double spacing = argc == 3 ? std::atof(argv[2]) : 2.5;
  if (!(spacing > 0.1 && spacing < 50)) {
    std::fprintf(stderr, "slice spacing must be between 0.1 and 50 mm\n");
    return 2;
  }
  std::string name = "phantom.json";
  if (argc == 3) name = std::string("phantom-").append(argv[2]).append("mm.json");
  scansurf::ContourSet phantom = scansurf::phantomContours(spacing);
  phantom.source = name;
  return write(phantom, argv[1]);
}
