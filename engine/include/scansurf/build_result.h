// scansurf: what a build gives back: the surfaces, the label volume, the overlap analysis,
// the figures of each stage and its time. Engine::build (engine.h) makes it; the writers
// (outputs.h, report.h) read it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scansurf/audit.h"
#include "scansurf/contours.h"
#include "scansurf/interpolation.h"
#include "scansurf/label_volume.h"
#include "scansurf/nesting.h"
#include "scansurf/overlaps.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// The time one stage took.
struct StageTime {
  std::string stage;
  double seconds = 0;
};

// What interpolation did (BuildOptions::interpolation).
struct InterpolationSummary {
  int planeLayers = 0;               // layers of the grid (contour planes and padding)
  int surfacedLayers = 0;            // layers of the volume that was surfaced: planeLayers when off
  int minFactor = 1, maxFactor = 1;  // layers per gap, the gaps' smallest and largest
  CapShape caps = CapShape::Round;
  bool used() const { return surfacedLayers > planeLayers; }
};

struct BuildResult {
  Nesting nesting;
  // The label volume of the contour planes as scan conversion made it, incidental overlaps
  // split (OverlapTolerance): the single partition, or with several layers the volume of
  // layer 0 (OverlapReport::features[f].layer says which features it holds). With interpolation the surfaces come from a volume
  // with more layers (interpolation says how many), which is not kept. Without BuildOptions::keepLabelVolume, only its grid
  // (labels empty, unless interpolation or the partition mode needed them).
  LabelVolume volume;
  InterpolationSummary interpolation;
  // Every feature's surface; with several layers the layers' meshes side by side in one mesh
  // (vertices shared within a layer only).
  Surfaces surfaces;
  // Volumes three ways, overlapping and touching pairs, layers, and (Partition) volume losses.
  OverlapReport overlaps;
  // The device's sub-pixel precision of scan conversion (bits), with which the writers
  // rasterize each feature's own mask on the CPU exactly as the device did.
  int subPixelBits = 8;
  int threads = 1;       // CPU threads the run used (BuildOptions::threads, 0 resolved)
  double gapFactor = 0;  // GridOptions::gapFactor as the build used it (the writers' masks follow it)
  // The budget check: estimated peak host memory, and the limit it was held to (bytes).
  std::uint64_t estimatedMemory = 0;
  std::uint64_t memoryLimit = 0;
  // Each feature's statistics and what they were held to (scansurf/audit.h); its findings are
  // among the warnings too.
  SurfaceAudit audit;
  std::vector<std::string> warnings;  // e.g. contours too small to cover a pixel centre
  std::vector<StageTime> timings;
};

}  // namespace scansurf
