// scansurf: the editable non-manifold triangle network that remeshing works on. No half-edges:
// a junction edge has three or more triangles, so each vertex keeps its live triangles and an
// edge's triangles are the ones its two ends share. Every edit is recorded in a Change so that
// an operation can be tried, checked and undone.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/mesh/vec3.h"
#include "geometry/mesh/vertex_roles.h"
#include "scansurf/nesting.h"
#include "scansurf/surfaces.h"

namespace scansurf::remesh {

using glm::cross;
using glm::dot;
// Rounded to float and back: the mesh stores float, and every check runs on what is stored.
inline Vec3 storable(const Vec3& p) { return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])}; }

// Vertex roles (VertexRole, geometry/mesh/vertex_roles.h): a Curve vertex has exactly two junction
// edges, a Plane vertex exactly two in-plane edges of its cross-section polyline.

// One closed feature surface (a feature in one convention) a triangle belongs to, and whether
// the triangle is flipped to face outward in it (geometry/extraction/feature_surfaces.h).
struct SurfaceUse {
  int surface = 0;
  bool flip = false;
};

// The feature surfaces, in both conventions, that each label pair's triangles belong to.
class SurfaceTable {
 public:
  SurfaceTable(const MultiLabelMesh& mesh, const Nesting& nesting);
  const std::vector<SurfaceUse>& usesOf(std::uint32_t pair) const;

 private:
  std::unordered_map<std::uint32_t, std::vector<SurfaceUse>> uses_;
};

// Live triangles in the cells of a uniform grid their bounding boxes touch (broad phase). Cells
// live in an open-addressing table (linear probing on a multiplicative hash): the queries of
// the exact crossing checks are remeshing's most frequent lookup.
class TriangleGrid {
 public:
  explicit TriangleGrid(double cell) : cell_(cell) {}
  void insert(std::uint32_t t, const Vec3& lo, const Vec3& hi);
  void clear();
  // Every live triangle inserted into a cell that [lo, hi] touches, each once. Dead ones are
  // dropped from the cells for good, except `pending`: the open change's removed triangles (a
  // handful), which an undo brings back.
  void query(const Vec3& lo, const Vec3& hi, const std::vector<char>& alive, const std::vector<std::uint32_t>& pending,
             std::vector<std::uint32_t>& out);

 private:
  template <typename F>
  void forCells(const Vec3& lo, const Vec3& hi, F f) const;
  std::vector<std::uint32_t>* find(std::uint64_t key);
  std::vector<std::uint32_t>& findOrAdd(std::uint64_t key);
  std::size_t slotOf(std::uint64_t key) const { return static_cast<std::size_t>((key * 0x9e3779b97f4a7c15ull) >> shift_); }

  double cell_;
  static constexpr std::uint64_t kEmpty = ~0ull;
  std::vector<std::uint64_t> keys_;   // per slot, kEmpty when free
  std::vector<std::uint32_t> lists_;  // per slot, into cells_
  std::vector<std::vector<std::uint32_t>> cells_;
  int shift_ = 64;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t round_ = 0;
};

// Edits since an operation began, for undo.
struct Change {
  std::vector<std::uint32_t> removed;                 // triangles made dead
  std::uint32_t firstAdded = 0;                       // triangles >= this were added
  std::vector<std::pair<std::uint32_t, Vec3>> moved;  // vertex, its old position
  bool addedVertex = false;
};

class Network {
 public:
  // Vertices whose z lies within sliceTolerance of one of planeZ (sorted) are on that contour
  // plane; roles follow from the junction edges and in-plane edges around each vertex.
  // broadPhase = false leaves the grid empty (a network only read, as by ReferenceSurface).
  Network(const MultiLabelMesh& mesh, const std::vector<double>& planeZ, double sliceTolerance, double cell,
          bool broadPhase = true);

  std::vector<Vec3> pos;
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::uint32_t> pair;  // labelPairKey per triangle
  std::vector<char> alive;
  std::vector<std::vector<std::uint32_t>> vtris;  // live triangles per vertex
  std::vector<VertexRole> role;
  std::vector<int> plane;               // contour plane index, or -1
  std::vector<std::uint8_t> junctions;  // junction edges a corner must keep
  std::vector<std::uint8_t> inPlane;    // in-plane edges a corner must keep
  TriangleGrid grid;

  std::uint32_t vertexCount() const { return static_cast<std::uint32_t>(pos.size()); }
  // Makes v a corner that keeps the feature edges it has now: it never moves or goes.
  void pin(std::uint32_t v);
  // The live triangles holding both a and b.
  void edgeTriangles(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out) const;
  // An edge is a junction edge unless it has exactly two triangles of one label pair.
  bool isJunctionEdge(const std::vector<std::uint32_t>& edgeTris) const;
  // Both ends on one contour plane: a piece of that plane's cross-section.
  bool isInPlaneEdge(std::uint32_t a, std::uint32_t b) const { return plane[a] >= 0 && plane[a] == plane[b]; }
  // A feature line's edge: on a junction curve or a cross-section.
  bool isFeatureEdge(std::uint32_t a, std::uint32_t b, const std::vector<std::uint32_t>& edgeTris) const {
    return isJunctionEdge(edgeTris) || isInPlaneEdge(a, b);
  }
  // Distinct neighbours of v, ascending.
  void neighbours(std::uint32_t v, std::vector<std::uint32_t>& out) const;
  Vec3 normal(std::uint32_t t) const;  // area-weighted (twice the area)

  // Edits, each recorded in `change` (begin() first).
  void begin(Change& change) const;
  std::uint32_t addVertex(const Vec3& p, VertexRole r, int planeIndex, Change& change);
  void removeTriangle(std::uint32_t t, Change& change);
  std::uint32_t addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t pairOf, Change& change);
  void move(std::uint32_t v, const Vec3& p, Change& change);
  void undo(Change& change);
  void commit(const Change& change);  // added triangles into the grid

  // Drops dead triangles and rebuilds the grid; triangle ids change, vertex ids stay.
  void compact();
  // The live triangles and the vertices they use (renumbered in vertex order) into mesh;
  // mesh.keys cleared.
  void storeInto(MultiLabelMesh& mesh) const;

 private:
  void insertIntoGrid(std::uint32_t t);
  void assignRoles();
};

// Whether every vertex in `vertices` (with triangles) still has the junction and in-plane
// edges its role allows, each feature surface around it is one consistently oriented fan, and
// no two of its triangles use the same three vertices.
bool topologyHolds(const Network& net, const SurfaceTable& surfaces, const std::vector<std::uint32_t>& vertices);

}  // namespace scansurf::remesh
