// scansurf: Draco-compressed surfaces (.drc), with position quantization chosen so that the
// error stays below a bound in input units.
#pragma once

#include <filesystem>
#include <memory>

#include "io/mesh_writers.h"
#include "scansurf/grid.h"
#include "scansurf/outputs.h"
#include "scansurf/result.h"

namespace draco {
class Mesh;
}

namespace scansurf {

// The position quantization bits Draco will use for `mesh` under `options`: Draco quantizes
// the largest extent of the bounding box into 2^bits - 1 steps, so the error is at most
// extent / (2 * (2^bits - 1)).
int quantizationBitsFor(const CompactMesh& mesh, const DracoOptions& options);

// The largest position error of `bits`-bit quantization of `mesh` (input units).
double quantizationError(const CompactMesh& mesh, int bits);

// The mesh as a Draco mesh: one float32 POSITION attribute, points = vertices.
std::unique_ptr<draco::Mesh> toDracoMesh(const CompactMesh& mesh);

// Writes the mesh as a Draco (.drc) file, edgebreaker-coded. Replaced atomically.
// Errors: Errc::Io naming the path, Errc::Internal when Draco refuses the mesh.
Result<void> writeDrc(const std::filesystem::path& path, const CompactMesh& mesh, const DracoOptions& options);

}  // namespace scansurf
