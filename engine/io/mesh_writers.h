// scansurf: one feature's surface as a standalone mesh, and the plain mesh formats people open
// directly (Wavefront OBJ, binary STL), written with Draco's own encoders.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/mesh/compact_mesh.h"
#include "scansurf/contours.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// A Wavefront material: the feature's colour as diffuse colour, in its own .mtl file.
struct ObjMaterial {
  std::string library;  // the .mtl file's name, beside the .obj
  std::string name;     // no white space
  Rgb color{};
};

// Wavefront OBJ: `v x y z` (6 decimals, in `units`, named in the header comment; empty: "the
// input's units"), `vn` area-weighted vertex normals and `f a//a b//b c//c` wound outward;
// `name` becomes the object name; with a material, `mtllib` and `usemtl` name it. Replaced
// atomically. Errors: Errc::Io naming the path.
Result<void> writeObj(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name,
                      const std::string& units = {}, const ObjMaterial* material = nullptr);
// The material file: `newmtl`, `Kd` (the colour, 0..1), `Ka` and `Ks` dark, `d 1`, `illum 2`.
Result<void> writeMtl(const std::filesystem::path& path, const ObjMaterial& material);

// Binary STL: one facet per triangle with its unit normal, float32 input units (STL has no
// unit field: viewers usually assume mm). Replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeStl(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& units = {});

}  // namespace scansurf
