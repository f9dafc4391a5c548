// scansurf: separating surfaces from planar contours, on Vulkan. The one header an
// application includes (scansurf/vulkan_interop.h adds the Vulkan interop for embedding).
//
//   auto contours = scansurf::readContours("contours.json");   // Result<ContourSet>
//   auto engine = scansurf::Engine::create({});                 // Result<Engine>
//   auto options = scansurf::BuildOptions::recommended();      // the command line's defaults
//   auto built = engine->build(*contours, options);             // Result<BuildResult>
//   scansurf::writeScene("surfaces.glb", *contours, built->surfaces);
//
// Nothing throws across this API: every fallible call returns Result<T> (scansurf/result.h).
#pragma once

#include "scansurf/audit.h"
#include "scansurf/build_result.h"
#include "scansurf/contours.h"
#include "scansurf/device.h"
#include "scansurf/engine.h"
#include "scansurf/grid.h"
#include "scansurf/input.h"
#include "scansurf/interpolation.h"
#include "scansurf/label_volume.h"
#include "scansurf/nesting.h"
#include "scansurf/outputs.h"
#include "scansurf/overlaps.h"
#include "scansurf/palette.h"
#include "scansurf/preview.h"
#include "scansurf/process.h"
#include "scansurf/remesh.h"
#include "scansurf/report.h"
#include "scansurf/result.h"
#include "scansurf/simplification.h"
#include "scansurf/smoothing.h"
#include "scansurf/surfaces.h"
#include "scansurf/version.h"
