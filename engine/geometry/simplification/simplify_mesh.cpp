// scansurf: verified simplification (see simplify_mesh.h). The collapses are quadric-error
// half-edge collapses (Garland & Heckbert, "Surface simplification using quadric error
// metrics", SIGGRAPH 1997; geometry/simplification/edge_collapse.h); what this file adds is the cut into
// patches that keeps every feature line, and the checks that decide whether a patch's result
// is kept. Why patches keep the guarantees: every vertex a patch shares with another stays, so
// no other patch's surroundings change; collapses only merge vertices onto their neighbours, so
// the triangles stay inside the tier between the patch's cuts. Per patch, the same border,
// Euler characteristic and components and a manifold, oriented result mean the same topology;
// the exact crossing test against every triangle near a new one (afterwards, over the whole
// mesh) keeps the surfaces from crossing.
// Not meshoptimizer's meshopt_simplify (Debian 12 ships 0.18): it cannot keep chosen vertices
// (only the whole border) nor let a caller refuse a collapse, and its results fail these checks
// in about half the patches (degenerate and turned triangles, folds onto the contour planes).
#include "geometry/simplification/simplify_mesh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <iterator>
#include <numeric>

#include "core/parallel.h"
#include "geometry/mesh/crossing_search.h"
#include "geometry/mesh/vertex_roles.h"
#include "geometry/remesh/remesh_mesh.h"  // computeAngleFigures
#include "geometry/simplification/edge_collapse.h"
#include "geometry/simplification/patch_checks.h"

namespace scansurf {
namespace {

// A patch: triangles order[first, first + count) of one key (tier << 48 | tile << 32 | label pair).
struct Patch {
  std::uint64_t key = 0;
  std::size_t first = 0, count = 0;
};

// A patch's outcome: its triangles (mesh vertex ids), or empty when it stays as it was.
struct PatchResult {
  std::vector<std::uint32_t> triangles;
  std::vector<char> changed;         // per triangle: not one of the patch's as it was
  std::vector<std::uint64_t> joins;  // edges between two shared vertices that it did not have (a << 32 | b, a < b)
  bool refused = false;
};

// Per cell layer (between grid layers k and k + 1), its tier: a new one at every contour layer
// and after kTierLayers layers without one.
std::vector<std::uint32_t> tiersOfLayers(const Grid& grid, const std::vector<bool>& contourLayers) {
  std::vector<std::uint32_t> tier(static_cast<std::size_t>(std::max(grid.nz - 1, 1)), 0);
  std::uint32_t current = 0;
  int since = 0;
  for (std::size_t k = 0; k < tier.size(); ++k) {
    const bool contour = k < contourLayers.size() && contourLayers[k];
    if (k > 0 && (contour || since == kTierLayers)) ++current, since = 0;
    tier[k] = current, ++since;
  }
  return tier;
}

// The cell layer holding a triangle whose lowest z is `z`: the last layer at or below it.
std::size_t cellLayerOf(const Grid& grid, float z, double tolerance) {
  const auto it = std::upper_bound(grid.layerZ.begin(), grid.layerZ.end(), static_cast<double>(z) + tolerance);
  const auto k = static_cast<std::ptrdiff_t>(it - grid.layerZ.begin()) - 1;
  return static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(k, 0, std::max(grid.nz - 2, 0)));
}

// Per vertex, the contour plane it lies on (its layer), or -1.
std::vector<int> planesOfVertices(const MultiLabelMesh& mesh, const Grid& grid, const std::vector<bool>& contourLayers,
                                  double tolerance, int threads) {
  std::vector<int> plane(mesh.vertexCount(), -1);
  parallelChunks(plane.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const int k = layerOfZ(grid, mesh.positions[3 * v + 2], tolerance);
      if (k >= 0 && static_cast<std::size_t>(k) < contourLayers.size() && contourLayers[static_cast<std::size_t>(k)])
        plane[v] = k;
    }
  });
  return plane;
}

// How many patches a worker takes at a time.
constexpr std::size_t kPatchesATurn = 16;

// A patch key: tier << 48 | tile << 32 | label pair.
constexpr std::uint64_t kField = 0xffff;

// The two labels of a patch key's label pair (labelPairKey).
std::array<Label, 2> labelsOfKey(std::uint64_t key) {
  return {static_cast<Label>(key & kField), static_cast<Label>(key >> 16 & kField)};
}

std::vector<std::uint64_t> patchKeys(const MultiLabelMesh& mesh, const Grid& grid, const std::vector<bool>& contourLayers,
                                     double tolerance, int threads) {
  const std::vector<std::uint32_t> tier = tiersOfLayers(grid, contourLayers);
  const auto tilesX = static_cast<std::uint64_t>((grid.nx + kTilePixels - 1) / kTilePixels);
  std::vector<std::uint64_t> keys(mesh.triangleCount());
  parallelChunks(keys.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      const std::uint32_t* tri = &mesh.triangles[3 * t];
      const std::uint64_t pair = labelPairKey(mesh.labels[2 * t], mesh.labels[2 * t + 1]);
      const float* p = &mesh.positions[3 * std::size_t{tri[0]}];
      float z = p[2];
      for (int c = 1; c < 3; ++c) z = std::min(z, mesh.positions[3 * std::size_t{tri[c]} + 2]);
      const std::uint64_t s = tier[cellLayerOf(grid, z, tolerance)] % kField;
      const auto tx = static_cast<std::uint64_t>(std::max(0.0, (p[0] - grid.originX) / grid.spacingX / kTilePixels));
      const auto ty = static_cast<std::uint64_t>(std::max(0.0, (p[1] - grid.originY) / grid.spacingY / kTilePixels));
      keys[t] = s << 48 | ((ty * tilesX + tx) % kField) << 32 | pair;
    }
  });
  return keys;
}

// Triangle ids sorted by key (ties by id), and the patches as runs of one key.
std::vector<Patch> groupPatches(const std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& order) {
  order.resize(keys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  std::vector<Patch> patches;
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (patches.empty() || keys[order[i]] != patches.back().key) patches.push_back({keys[order[i]], i, 0});
    ++patches.back().count;
  }
  return patches;
}

// What one patch's simplification needs to know of the run.
struct PatchContext {
  const MultiLabelMesh& mesh;
  const std::vector<int>& plane;    // per vertex (planesOfVertices)
  const std::vector<char>& shared;  // per vertex (sharedVertices)
  double tolerance, edgeLength;     // input units
  double minAngle;                  // degrees
};

// The patch as a mesh of its own: its vertices (mesh ids, sorted), their positions and planes,
// and its triangles in local ids.
struct LocalPatch {
  std::vector<std::uint32_t> vertices, triangles;
  std::vector<float> positions;
  std::vector<int> plane;
};

// Mesh vertex ids to a patch's local ids: open addressing over twice the patch's corners, so
// that no patch sorts and searches every corner and a thread's scratch stays the size of a
// patch, not of the mesh. Reused by a thread's patches.
class LocalIds {
 public:
  void reset(std::size_t corners) {
    const std::size_t size = std::bit_ceil(std::max<std::size_t>(2 * corners, 16));
    ids_.assign(size, kEmpty), locals_.resize(size);
    shift_ = 32 - std::countr_zero(size);
  }
  // v's slot; `added` says whether v was new (its local id is then to be set).
  std::uint32_t& operator()(std::uint32_t v, bool& added) {
    std::size_t slot = (v * 2654435761u) >> shift_;  // Knuth's multiplicative hash, top bits
    for (; ids_[slot] != kEmpty; slot = (slot + 1) & (ids_.size() - 1))
      if (ids_[slot] == v) return added = false, locals_[slot];
    ids_[slot] = v, added = true;
    return locals_[slot];
  }

 private:
  static constexpr std::uint32_t kEmpty = ~0u;
  std::vector<std::uint32_t> ids_, locals_;
  int shift_ = 28;
};

LocalPatch localPatch(const PatchContext& ctx, std::span<const std::uint32_t> tris, LocalIds& local) {
  LocalPatch p;
  local.reset(3 * tris.size());
  bool added = false;
  for (std::uint32_t t : tris)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = ctx.mesh.triangles[3 * std::size_t{t} + c];
      local(v, added);
      if (added) p.vertices.push_back(v);
    }
  std::sort(p.vertices.begin(), p.vertices.end());
  for (std::uint32_t i = 0; i < p.vertices.size(); ++i) {
    const std::uint32_t v = p.vertices[i];
    local(v, added) = i;
    for (int c = 0; c < 3; ++c) p.positions.push_back(ctx.mesh.positions[3 * std::size_t{v} + c]);
    p.plane.push_back(ctx.plane[v]);
  }
  for (std::uint32_t t : tris)
    for (int c = 0; c < 3; ++c) p.triangles.push_back(local(ctx.mesh.triangles[3 * std::size_t{t} + c], added));
  return p;
}

// The sorted edges between two shared vertices (a << 32 | b, a < b) of triangles (mesh ids).
void appendSharedEdges(const PatchContext& ctx, std::span<const std::uint32_t> triangles, std::vector<std::uint64_t>& edges) {
  for (std::size_t t = 0; t < triangles.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      std::uint32_t a = triangles[t + e], b = triangles[t + (e + 1) % 3];
      if (!ctx.shared[a] || !ctx.shared[b]) continue;
      if (a > b) std::swap(a, b);
      edges.push_back(std::uint64_t{a} << 32 | b);
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
}

// The edges between two shared vertices that a patch's result has and its triangles had not:
// the only ones another patch can also use (every other one lies inside the patch or on its
// unchanged border).
std::vector<std::uint64_t> newSharedEdges(const PatchContext& ctx, std::span<const std::uint32_t> tris,
                                          const std::vector<std::uint32_t>& after) {
  std::vector<std::uint32_t> before;
  for (std::uint32_t t : tris)
    for (int c = 0; c < 3; ++c) before.push_back(ctx.mesh.triangles[3 * std::size_t{t} + c]);
  std::vector<std::uint64_t> had, has, joins;
  appendSharedEdges(ctx, before, had), appendSharedEdges(ctx, after, has);
  std::set_difference(has.begin(), has.end(), had.begin(), had.end(), std::back_inserter(joins));
  return joins;
}

// Simplifies one patch: vertices on contour planes or shared with another patch stay; empty
// triangles when nothing changed or a check refused the result.
PatchResult simplifyPatch(const PatchContext& ctx, std::span<const std::uint32_t> tris, LocalIds& local) {
  PatchResult result;
  const LocalPatch p = localPatch(ctx, tris, local);
  std::vector<char> locked(p.vertices.size());
  for (std::size_t v = 0; v < locked.size(); ++v) locked[v] = ctx.shared[p.vertices[v]] || p.plane[v] >= 0;
  // Where the patch meets a border vertex from two sides its triangles stay as they are: none
  // of its neighbours goes (nor anything onto it) and no flip touches it, so nothing re-pairs
  // its fans (checkPatch).
  const std::vector<char> pinched = pinchedVertices(p.triangles, p.vertices.size());
  for (std::size_t t = 0; t < p.triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c)
      if (pinched[p.triangles[t + c]])
        for (int k = 0; k < 3; ++k) {
          char& lock = locked[p.triangles[t + (c + k) % 3]];
          lock = k == 0 ? kFrozen : std::max(lock, char{1});
        }
  const CollapseLimits limits{ctx.tolerance, ctx.edgeLength, ctx.minAngle};
  std::vector<std::uint32_t> after = collapseEdges(p.positions, p.triangles, locked, p.plane, limits);
  if (after.size() == p.triangles.size()) return result;
  if (checkPatch(p.positions, p.plane, p.triangles, after, &result.changed) != PatchVerdict::Kept) {
    result.refused = true;
    return result;
  }
  for (std::uint32_t& v : after) v = p.vertices[v];
  result.triangles = std::move(after);
  result.joins = newSharedEdges(ctx, tris, result.triangles);
  return result;
}

// Per vertex, whether triangles of more than one patch use it.
std::vector<char> sharedVertices(const MultiLabelMesh& mesh, const std::vector<std::uint32_t>& order,
                                 const std::vector<Patch>& patches) {
  std::vector<std::uint32_t> owner(mesh.vertexCount(), ~0u);
  std::vector<char> shared(mesh.vertexCount(), 0);
  for (std::uint32_t i = 0; i < patches.size(); ++i)
    for (std::size_t k = patches[i].first; k < patches[i].first + patches[i].count; ++k)
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = mesh.triangles[3 * std::size_t{order[k]} + c];
        if (owner[v] == ~0u)
          owner[v] = i;
        else if (owner[v] != i)
          shared[v] = 1;
      }
  return shared;
}

// The mesh's triangles with the kept patches simplified: triangles, labels, and per triangle
// its patch and whether it is new (only new triangles can cross: the smoothed ones do not).
struct Candidate {
  std::vector<std::uint32_t> triangles, patchOf;
  std::vector<Label> labels;
  std::vector<char> changed;
};

Candidate candidateMesh(const MultiLabelMesh& mesh, const std::vector<std::uint32_t>& order, const std::vector<Patch>& patches,
                        const std::vector<PatchResult>& results, const std::vector<char>& kept) {
  Candidate c;
  for (std::uint32_t i = 0; i < patches.size(); ++i) {
    const Patch& p = patches[i];
    const std::size_t before = c.triangles.size();
    if (kept[i]) {
      c.triangles.insert(c.triangles.end(), results[i].triangles.begin(), results[i].triangles.end());
    } else {
      for (std::size_t k = p.first; k < p.first + p.count; ++k)
        for (int v = 0; v < 3; ++v) c.triangles.push_back(mesh.triangles[3 * std::size_t{order[k]} + v]);
    }
    const std::size_t added = (c.triangles.size() - before) / 3;
    c.patchOf.insert(c.patchOf.end(), added, i);
    if (kept[i])
      c.changed.insert(c.changed.end(), results[i].changed.begin(), results[i].changed.end());
    else
      c.changed.insert(c.changed.end(), added, 0);
    const std::array<Label, 2> labels = labelsOfKey(p.key);
    for (std::size_t t = 0; t < added; ++t) c.labels.insert(c.labels.end(), labels.begin(), labels.end());
  }
  return c;
}

// The kept patches that joined anew an edge (PatchResult::joins) that a triangle of another
// patch bounding one of the same labels also uses: that label's surface would have more than
// two triangles on the edge. Only such an edge can: every other one lies inside one patch or on
// its unchanged border.
std::vector<std::uint32_t> patchesOverusingJoins(const Candidate& c, const std::vector<Patch>& patches,
                                                 const std::vector<PatchResult>& results, const std::vector<char>& kept,
                                                 std::size_t vertexCount) {
  struct Join {
    std::uint32_t a, b, patch;
  };
  std::vector<Join> joins;
  for (std::uint32_t i = 0; i < results.size(); ++i)
    if (kept[i])
      for (std::uint64_t e : results[i].joins)
        joins.push_back({static_cast<std::uint32_t>(e >> 32), static_cast<std::uint32_t>(e), i});
  if (joins.empty()) return {};
  std::sort(joins.begin(), joins.end(), [](const Join& x, const Join& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  std::vector<std::uint32_t> first(vertexCount + 1, 0);  // joins[first[a], first[a + 1]) start at a
  for (const Join& j : joins) ++first[j.a + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<char> overusing(patches.size(), 0);
  for (std::uint32_t t = 0; t < c.patchOf.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      std::uint32_t a = c.triangles[3 * std::size_t{t} + e], b = c.triangles[3 * std::size_t{t} + (e + 1) % 3];
      if (a > b) std::swap(a, b);
      for (std::uint32_t k = first[a]; k < first[a + 1]; ++k) {
        const Join& j = joins[k];
        if (j.b != b || j.patch == c.patchOf[t]) continue;
        const std::array<Label, 2> l = labelsOfKey(patches[j.patch].key);
        const Label t0 = c.labels[2 * std::size_t{t}], t1 = c.labels[2 * std::size_t{t} + 1];
        if (t0 == l[0] || t0 == l[1] || t1 == l[0] || t1 == l[1]) overusing[j.patch] = 1;
      }
    }
  std::vector<std::uint32_t> list;
  for (std::uint32_t i = 0; i < overusing.size(); ++i)
    if (overusing[i]) list.push_back(i);
  return list;
}

// Drops the kept patches whose new triangles cross another triangle (both patches, when both
// are new) or that overuse an edge they joined (patchesOverusingJoins), until none does;
// returns how many were dropped. After the first round only the triangles put back need the
// crossing test, against the new ones: every other pair was tested as it is.
std::size_t dropCrossingPatches(const MultiLabelMesh& mesh, const std::vector<std::uint32_t>& order,
                                const std::vector<Patch>& patches, const std::vector<PatchResult>& results,
                                std::vector<char>& kept, Candidate& candidate, double cell, int threads) {
  std::size_t dropped = 0;
  std::vector<char> putBack;  // per patch: dropped in the last round
  for (bool first = true;; first = false) {
    candidate = candidateMesh(mesh, order, patches, results, kept);
    std::vector<char> query = candidate.changed;
    if (!first)
      for (std::size_t t = 0; t < query.size(); ++t) query[t] = putBack[candidate.patchOf[t]];
    std::vector<std::uint32_t> faulty = patchesOverusingJoins(candidate, patches, results, kept, mesh.vertexCount());
    for (const auto& [a, b] : crossingPairs(mesh.positions, candidate.triangles, query, candidate.changed, cell, threads))
      for (std::uint32_t t : {a, b})
        if (candidate.changed[t]) faulty.push_back(candidate.patchOf[t]);
    if (faulty.empty()) return dropped;
    putBack.assign(patches.size(), 0);
    for (std::uint32_t i : faulty)
      if (kept[i]) kept[i] = 0, putBack[i] = 1, ++dropped;
  }
}

// Replaces the mesh's triangles and labels, keeping only the vertices they use.
void replaceTriangles(MultiLabelMesh& mesh, Candidate&& candidate) {
  std::vector<std::uint32_t> index(mesh.vertexCount(), ~0u);
  for (std::uint32_t v : candidate.triangles) index[v] = 0;
  std::vector<float> positions;
  for (std::uint32_t v = 0, next = 0; v < index.size(); ++v)
    if (index[v] == 0) {
      index[v] = next++;
      positions.insert(positions.end(), mesh.positions.begin() + 3 * std::size_t{v},
                       mesh.positions.begin() + 3 * std::size_t{v} + 3);
    }
  for (std::uint32_t& v : candidate.triangles) v = index[v];
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(candidate.triangles);
  mesh.labels = std::move(candidate.labels);
  mesh.keys.clear();  // the lattice keys described the assembled triangles only
}

}  // namespace

SimplificationReport simplifyMesh(MultiLabelMesh& mesh, const Grid& grid, const std::vector<bool>& contourLayers,
                                  const SimplificationOptions& options, int threads) {
  SimplificationReport report;
  if (!options.enabled || mesh.triangleCount() == 0) return report;
  report.ran = true;
  report.trianglesBefore = mesh.triangleCount();
  report.anglesBefore = computeAngleFigures(mesh.positions, mesh.triangles, threads);
  const double voxel = std::min(grid.spacingX, grid.spacingY);
  const double planeTolerance = grid.planeTolerance > 0 ? grid.planeTolerance : 1e-6 * voxel;
  const std::vector<int> plane = planesOfVertices(mesh, grid, contourLayers, planeTolerance, threads);
  std::vector<std::uint32_t> order;
  const std::vector<Patch> patches = groupPatches(patchKeys(mesh, grid, contourLayers, 1e-6 * voxel, threads), order);
  const std::vector<char> shared = sharedVertices(mesh, order, patches);
  const PatchContext ctx{mesh, plane, shared, options.tolerance * voxel, options.edgeLength * voxel, options.minAngle};
  std::vector<PatchResult> results(patches.size());
  // Patches differ in size by orders of magnitude: workers take a few at a time.
  std::vector<LocalIds> local(static_cast<std::size_t>(chunkCount(patches.size(), threads)));
  parallelBlocks(patches.size(), threads, kPatchesATurn, [&](int worker, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      results[i] = simplifyPatch(ctx, std::span(order).subspan(patches[i].first, patches[i].count),
                                 local[static_cast<std::size_t>(worker)]);
  });
  std::vector<char> kept(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) kept[i] = !results[i].triangles.empty(), report.refused += results[i].refused;
  Candidate candidate;
  // Cells of 4 voxels: a triangle touches fewer of them than of 2, so the grid is built faster,
  // at no cost in candidates; any size gives the same pairs.
  report.crossing = dropCrossingPatches(mesh, order, patches, results, kept, candidate, 4 * voxel, threads);
  report.patches = patches.size();
  replaceTriangles(mesh, std::move(candidate));
  report.trianglesAfter = mesh.triangleCount();
  report.anglesAfter = computeAngleFigures(mesh.positions, mesh.triangles, threads);
  return report;
}

namespace {

void accumulateAngles(AngleFigures& into, std::size_t intoCount, const AngleFigures& layer, std::size_t layerCount) {
  if (layerCount == 0) return;
  if (intoCount == 0) {
    into = layer;
    return;
  }
  into.min = std::min(into.min, layer.min), into.p5 = std::min(into.p5, layer.p5);
  const auto a = static_cast<double>(intoCount), b = static_cast<double>(layerCount);
  into.mean = (into.mean * a + layer.mean * b) / (a + b);
}

}  // namespace

void accumulate(SimplificationReport& into, const SimplificationReport& layer) {
  accumulateAngles(into.anglesBefore, into.trianglesBefore, layer.anglesBefore, layer.trianglesBefore);
  accumulateAngles(into.anglesAfter, into.trianglesAfter, layer.anglesAfter, layer.trianglesAfter);
  into.ran = into.ran || layer.ran;
  into.trianglesBefore += layer.trianglesBefore, into.trianglesAfter += layer.trianglesAfter;
  into.patches += layer.patches, into.refused += layer.refused, into.crossing += layer.crossing;
}

}  // namespace scansurf
