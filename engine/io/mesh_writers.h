// scansurf: one feature's surface as a standalone mesh, and the plain mesh formats people open
// directly (Wavefront OBJ, binary STL), written with Draco's own encoders.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/compact_mesh.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// Wavefront OBJ: `v x y z` (6 decimals, in `units`, named in the header comment; empty: "the
// input's units") and `f a b c` wound outward; `name`
// becomes the object name. Replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeObj(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name,
                      const std::string& units = {});

// Binary STL: one facet per triangle with its unit normal, float32 input units (STL has no
// unit field: viewers usually assume mm). Replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeStl(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& units = {});

}  // namespace scansurf
