// scansurf: separating surfaces (Nielson & Franke, "Computing the separating surface for
// segmented data", IEEE Visualization 1997) extracted from a label volume.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "scansurf/label_volume.h"
#include "scansurf/remesh.h"
#include "scansurf/simplification.h"
#include "scansurf/smoothing.h"

namespace scansurf {

// One mesh holding every separating surface, vertices shared between all of them.
struct MultiLabelMesh {
  std::vector<float> positions;          // x, y, z per vertex, input units
  std::vector<std::uint32_t> triangles;  // 3 vertex indices per triangle
  // 2 labels per triangle, {a, b} with a < b; the triangle's normal (counter-clockwise
  // winding, right-hand rule) points out of a's region into b's.
  std::vector<Label> labels;
  // Per vertex, its exact place on the grid: the barycentre of the lattice edge, face or
  // tetrahedron it lies on, in twelfths of a voxel, packed as x | y << 21 | z << 42 (voxel
  // indices times 12), sorted; empty for meshes not made by assembly or after remeshing.
  // Smoothing uses it to keep each vertex inside its own lattice simplex.
  std::vector<std::uint64_t> keys;

  std::size_t vertexCount() const { return positions.size() / 3; }
  std::size_t triangleCount() const { return triangles.size() / 3; }
};

enum class SurfaceConvention {
  // The surface around everything the feature's contours enclose, nested features included.
  Enclosing,
  // The boundary of the region the feature owns after priority.
  Partition,
};

// A feature's closed surface as triangles of the shared mesh, oriented outward.
struct FeatureSurface {
  int feature = -1;
  std::vector<std::uint32_t> triangles;  // 3 indices into MultiLabelMesh::positions each

  std::size_t triangleCount() const { return triangles.size() / 3; }
};

struct Surfaces {
  MultiLabelMesh mesh;
  SurfaceConvention convention = SurfaceConvention::Enclosing;
  std::vector<FeatureSurface> features;  // one per input feature, in input order
  // What remeshing did (ran = false when it did not run); with several layers, the layers'
  // counts summed, their smallest angles' minimum and their means weighted by triangles.
  RemeshReport remeshing;
  // What simplification did (ran = false when it did not run); with several layers, summed
  // and the largest error.
  SimplificationReport simplification;
  // What the triangle-shape stage did: snapping, quad diagonals, cube fans (ran = false when
  // smoothing did not run).
  TriangleShapeReport triangleShape;
};

// Topological and metric properties of a triangle mesh.
struct MeshStats {
  std::size_t triangles = 0;
  std::size_t vertices = 0;  // vertices referenced by the triangles
  double area = 0;           // input units squared
  double volume = 0;         // signed enclosed volume, input units cubed (positive when outward)
  int components = 0;        // edge-connected components
  int genus = 0;             // sum over components of (2 - χ) / 2; valid when closed
  bool closed = false;       // every edge has exactly two triangles
  bool manifold = false;     // closed and every vertex's triangles form one fan
  bool oriented = false;     // every edge is used once in each direction
};

// Computes the statistics of the triangles (3 indices each) over positions (xyz each).
MeshStats computeMeshStats(std::span<const float> positions, std::span<const std::uint32_t> triangles);

// computeMeshStats of every feature surface, in feature order: the features in parallel on
// `threads` (0 = all), the largest first; the same figures for any thread count.
std::vector<MeshStats> computeFeatureStats(const Surfaces& surfaces, int threads = 0);

}  // namespace scansurf
