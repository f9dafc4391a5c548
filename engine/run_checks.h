// scansurf: what a run is refused for before any work: options out of their range (one
// policy: refused with Errc::InvalidArgument naming the option, never clamped) and a memory
// budget the run would exceed (Errc::ResourceLimit, before anything large is allocated).
#pragma once

#include <string>

#include "scansurf/build_result.h"
#include "scansurf/device.h"
#include "scansurf/engine.h"

namespace scansurf {

// "256 x 172 x 42 voxels".
std::string describeGrid(const Grid& grid);

// Every option that needs no grid to judge.
Result<void> checkOptions(const BuildOptions& options);

// The remeshing edge length against the grid's scale (RemeshOptions::kLeastVoxels..kMostVoxels).
Result<void> checkEdgeLength(const RemeshOptions& remeshing, const Grid& grid);

// The estimated host and device memory (estimateFootprint) against options.memoryLimit (or
// the memory available) and the device's memory; records the estimate and limit in `out`.
Result<void> checkMemoryBudget(const ContourSet& contours, const Grid& grid, int surfacedLayers, const BuildOptions& options,
                               const DeviceInfo& device, BuildResult& out);

}  // namespace scansurf
