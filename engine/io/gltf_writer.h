// scansurf: every feature surface in one binary glTF 2.0 scene (.glb), written by Draco's own
// glTF encoder (libdraco built with DRACO_TRANSCODER_SUPPORTED), Draco-compressed through
// KHR_draco_mesh_compression by default.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "io/draco_writer.h"
#include "scansurf/contours.h"
#include "scansurf/result.h"

namespace scansurf {

struct GltfFeature {
  std::string name;                   // the node's and mesh's name
  Rgb color{};                        // sRGB; stored as the material's linear baseColorFactor
  const CompactMesh* mesh = nullptr;  // skipped when it has no triangles
  float opacity = 1;                  // below 1: alphaMode BLEND with this alpha
};

struct GlbOptions {
  bool draco = true;  // KHR_draco_mesh_compression; false: plain float32 accessors
  DracoOptions dracoOptions;
  // Gltf: a root node turns the input's patient LPS coordinates in `units` into glTF's y-up
  // metres; Patient: positions as they are, no root transform. Recorded in asset.extras.
  SceneFrame frame = SceneFrame::Gltf;
  std::string units = "mm";
  CoordinateFrame coordinates = CoordinateFrame::PatientLps;  // what the vertices are, as asset.extras says
};

// Writes one node and mesh per feature, each with its own material (baseColorFactor, matte;
// translucent features blended) and smooth per-vertex normals, under a root node that puts the
// scene in glTF's frame (see GlbOptions::frame); asset.generator names scansurf and its version.
// Replaced atomically. Errors: Errc::Io naming the path, Errc::Internal when Draco fails.
Result<void> writeGlb(const std::filesystem::path& path, std::span<const GltfFeature> features, const GlbOptions& options);

// sRGB 8-bit component to linear [0, 1] (glTF colour factors are linear).
double srgbToLinear(std::uint8_t c);

}  // namespace scansurf
