// Constrained smoothing of separating surfaces (Lee, Fletcher, Whitaker et al., "Scanline
// Surfacing", §3.5; after Whitaker, "Reducing aliasing artifacts in iso-surfaces of binary
// volumes", 2000, and Gibson's constrained elastic surface nets, 1998).
//
// The paper confines each vertex to an ellipsoid around its original position, the
// ellipsoids packed without overlap. We take the tightest region that provably keeps the
// surfaces apart: every vertex of the separating surface is the barycentre of a simplex of
// the grid's Freudenthal tetrahedra (an edge, a face or a tetrahedron whose corners are voxel
// centres; its "carrier", recovered exactly from the vertex's integer key), and it may move
// anywhere strictly inside that simplex (barycentric weights >= kMargin). These regions never
// overlap (the open simplices of a triangulation are disjoint) and are anisotropic exactly as
// the voxels are. Why no two triangles can then cross: every triangle of a tetrahedron T has
// its vertices in simplices of T, so it stays inside T, and two triangles of different
// tetrahedra can meet only on their common face, where both sides use the same face curve.
// Inside T, with two labels the triangle (3+1) or the quad split along a diagonal (2+2)
// joins points interior to distinct edges, a convex section or two triangles either side of
// an interior diagonal; with three or more labels the face curves are segments from edge
// points to one interior face point, which cannot cross, and the triangles are their cone
// from a point interior to T, each ray of which leaves T once, so cones meet only along
// common rays. Hence any positions inside the carriers give an embedded mesh with the same
// combinatorics: closed, oriented, same genus, abutting surfaces sharing every vertex.
//
// Relaxation: a vertex's neighbours are its edge neighbours on its sheet; a vertex on a
// junction curve (an edge there has triangles of more than one label pair) uses its two curve
// neighbours, and where curves meet the vertex stays. Each sweep is bi-Laplacian fairing
// (umbrella of umbrellas, Kobbelt et al. 1998) plus a little Laplacian tension, with Jacobi
// updates: unlike Laplacian or Taubin smoothing between pinned rings, fairing carries the
// curvature across the contour rings, so it neither shrinks the shape toward the chords nor
// flattens the caps beyond the last contours. A sheet vertex then slides along its carrier
// edge to where the target's tangent plane cuts it (tangential drift would otherwise turn into
// normal error on slanted edges); junction vertices take the nearest point of their carrier.
// Vertices fitted to the contours (geometry/smoothing/contour_fit.h) stay. With SmoothingOptions::minAngle,
// the placement and every stage shorten moves that would leave a sliver (geometry/smoothing/angle_guard.h);
// a shortened move stays on a segment inside the carrier, so the argument above still holds.
//
// Schedule: the relaxation is a low-pass filter, not a solver run to convergence. Its fixed
// point is worse than its 150th sweep (the tension shrinks and the fairing extrapolates caps:
// after 1200 sweeps the torus of smoothing_test.cpp loses 4 % of its volume and lies up to
// 0.96 mm off, against 0.77 % and 0.25 mm after 150), and about a third of the vertices never
// settle (they keep moving by a tenth of a voxel a sweep and more on the sweeps that refresh
// the slide slopes), so no residual can say when to stop. The amount of smoothing is
// the option's sweep count, read as a diffusion time: we integrate that time with
// Runge-Kutta-Legendre super-steps
// (RKL1 of Meyer, Balsara and Aslam, "A stabilized Runge-Kutta-Legendre method for explicit
// super-time-stepping of parabolic and mixed equations", J. Comput. Phys. 257, 2014; after
// Alexiades, Amiez and Gremaud's super-time-stepping, 1996). Stage j of an s-stage super-step
// of length tau (in plain sweeps) is Y_j = mu_j Y_{j-1} + nu_j Y_{j-2} + mu_j w1 tau S(Y_{j-1}),
// mu_j = (2j - 1) / j, nu_j = (1 - j) / j, w1 = 2 / (s^2 + s), S one plain sweep's step: a
// shifted Legendre polynomial in the sweep operator, stable while tau |lambda| <= s^2 + s, so
// s stages cover about s^2 / 2 sweeps of smoothing. Every stage ends in the carrier projection
// as a plain sweep does, so positions stay inside their carriers and the argument above holds
// unchanged; mu_j + nu_j = 1, so an edge vertex's stage stays on its edge's line. The 150
// sweeps of the default run as 5 super-steps of 7 stages (35 sweeps), with the accuracy of
// plain sweeps (smoothing_test.cpp holds it).
#include "geometry/smoothing/smooth_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/huge_pages.h"
#include "core/parallel.h"
#include "geometry/extraction/assembly.h"
#include "geometry/mesh/incident_triangles.h"
#include "geometry/mesh/vec3.h"
#include "geometry/mesh/vertex_roles.h"
#include "geometry/overlaps/overlap_split.h"
#include "geometry/smoothing/angle_guard.h"
#include "geometry/smoothing/carrier_projection.h"
#include "geometry/smoothing/contour_fit.h"
#include "geometry/smoothing/plane_blend.h"

namespace scansurf {
namespace {

constexpr double kMargin = kCarrierMargin;
constexpr double kBending = 0.45;    // bi-Laplacian step at strength 1
constexpr double kTension = 0.0875;  // Laplacian step at strength 1
constexpr int kNormalPeriod = 4;     // sweeps between vertex normal updates
constexpr int kSuperStep = 30;       // most plain sweeps' worth of smoothing in one super-step
constexpr double kStability = 1.15;  // least ratio of a super-step's stability bound to its need

// x, y, z and an unused lane: one SIMD register (GCC and Clang vector extension).
using Float4 = float __attribute__((vector_size(16)));

// Per vertex, one byte: its VertexRole in the low bits, and for a sheet vertex whether it slides
// along its carrier edge (kOnEdge) and whether its link is not one cycle (kPinched).
constexpr std::uint8_t kRoleMask = 3, kOnEdge = 4, kPinched = 8;
constexpr std::uint8_t kSlides = 16;              // slides along its normal until the next refresh
constexpr std::uint8_t kStepX = 32, kStepY = 64;  // its carrier edge runs along x, along y
VertexRole roleOf(std::uint8_t kind) { return static_cast<VertexRole>(kind & kRoleMask); }

struct Adjacency {
  std::vector<std::uint8_t> kind;   // VertexRole | kOnEdge | kPinched
  HugeVector<std::uint32_t> start;  // size V + 1, into neighbours
  // A sheet vertex's neighbours in the order of its link cycle (each triangle (v, a, b) of v,
  // counter-clockwise, is a consecutive a, b, the last neighbour followed by the first), so
  // its area-weighted normal is the sum of cross(a - v, b - v) over consecutive pairs; a curve
  // vertex's two curve neighbours.
  HugeVector<std::uint32_t> neighbours;
  std::vector<Label> labels;  // 2 per vertex: the pair of its first triangle
  // Sheet vertices whose link is not one cycle (kPinched; rare): {v, a, b} per triangle
  // (v, a, b), sorted by v, for their normals.
  std::vector<std::array<std::uint32_t, 3>> pinchedLinks;
};

// One thread's working lists while classifying vertices.
struct ClassifyScratch {
  std::vector<std::uint32_t> tris;                             // v's triangles
  std::vector<std::uint32_t> sorted;                           // v's neighbours, ascending
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // (neighbour, label pair)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> link;   // (a, b) of each triangle (v, a, b)
  std::vector<std::array<std::uint32_t, 3>> pinched;
};

// v's edges with their triangles' label pairs, sorted, in scratch.edges; whether all its
// triangles are of one pair.
bool collectEdges(const MultiLabelMesh& mesh, std::size_t v, ClassifyScratch& scratch) {
  scratch.edges.clear();
  bool onePair = true;
  std::uint32_t firstPair = 0;
  for (std::size_t i = 0; i < scratch.tris.size(); ++i) {
    const std::uint32_t t = scratch.tris[i];
    const std::uint32_t pair = labelPairKey(mesh.labels[2 * t], mesh.labels[2 * t + 1]);
    if (i == 0) firstPair = pair;
    onePair &= pair == firstPair;
    for (int c = 0; c < 3; ++c)
      if (mesh.triangles[3 * t + c] != v) scratch.edges.push_back({mesh.triangles[3 * t + c], pair});
  }
  std::sort(scratch.edges.begin(), scratch.edges.end());
  return onePair;
}

// v's distinct neighbours (ascending, in scratch.sorted) and its junction edges: an edge not
// shared by exactly two triangles of one pair. Returns how many, the first two kept.
std::uint32_t junctionNeighbours(ClassifyScratch& scratch, std::uint32_t first[2]) {
  const auto& edges = scratch.edges;
  scratch.sorted.clear();
  std::uint32_t curve = 0;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t e = i;
    while (e < edges.size() && edges[e].first == edges[i].first) ++e;
    scratch.sorted.push_back(edges[i].first);
    if (e - i != 2 || edges[i].second != edges[e - 1].second) {
      if (curve < 2) first[curve] = edges[i].first;
      ++curve;
    }
    i = e;
  }
  return curve;
}

// A sheet vertex's neighbours in the order of its link cycle from the least, into out; false
// when its link is not one cycle (pinched).
bool orderLinkCycle(const MultiLabelMesh& mesh, std::size_t v, ClassifyScratch& scratch, std::uint32_t* out) {
  auto& link = scratch.link;
  link.clear();
  for (std::uint32_t t : scratch.tris) {
    const std::uint32_t* c3 = &mesh.triangles[3 * t];
    const int c = c3[0] == v ? 0 : c3[1] == v ? 1 : 2;
    link.push_back({c3[(c + 1) % 3], c3[(c + 2) % 3]});
  }
  std::sort(link.begin(), link.end());
  const std::uint32_t* first = scratch.sorted.data();
  const auto all = static_cast<std::uint32_t>(scratch.sorted.size());
  bool cycle = link.size() == all;
  for (std::size_t i = 0; cycle && i < all; ++i) cycle = link[i].first == first[i];  // each neighbour once a start
  if (!cycle) return false;
  std::uint32_t steps = 0, a = first[0];
  do {
    scratch.edges[steps].first = a;  // reuse as the ordered list
    const std::size_t i = static_cast<std::size_t>(std::lower_bound(first, first + all, a) - first);
    a = link[i].second;
    ++steps;
  } while (a != first[0] && steps < all && std::binary_search(first, first + all, a));
  if (a != first[0] || steps != all) return false;
  for (std::uint32_t i = 0; i < all; ++i) out[i] = scratch.edges[i].first;
  return true;
}

// Classifies v (its kind byte) and writes its neighbours to out, which may be v's own range of
// the incident triangle list: a sheet vertex has one neighbour per triangle (each of its edges
// has two), a curve vertex two and at least three triangles. Returns their count.
std::uint32_t classifyVertex(const MultiLabelMesh& mesh, std::size_t v, bool junctions, ClassifyScratch& scratch,
                             std::uint32_t* out, std::uint8_t& kind) {
  const bool onePair = collectEdges(mesh, v, scratch);
  std::uint32_t curveNeighbours[2] = {0, 0};
  const std::uint32_t curve = junctionNeighbours(scratch, curveNeighbours);
  const auto all = static_cast<std::uint32_t>(scratch.sorted.size());
  if (onePair && curve == 0 && all <= scratch.tris.size()) {
    kind = static_cast<std::uint8_t>(VertexRole::Sheet);
    if (!orderLinkCycle(mesh, v, scratch, out)) {
      kind |= kPinched;
      std::copy(scratch.sorted.begin(), scratch.sorted.end(), out);
      for (const auto& [a, b] : scratch.link) scratch.pinched.push_back({static_cast<std::uint32_t>(v), a, b});
    }
    return all;
  }
  if (junctions && curve == 2 && scratch.tris.size() >= 2) {
    kind = static_cast<std::uint8_t>(VertexRole::Curve);
    out[0] = curveNeighbours[0], out[1] = curveNeighbours[1];
    return 2;
  }
  kind = static_cast<std::uint8_t>(VertexRole::Corner);
  return 0;
}

Adjacency buildAdjacency(const MultiLabelMesh& mesh, bool junctions, int threads) {
  const std::size_t vertexCount = mesh.vertexCount();
  Adjacency adj;
  IncidentTriangles in = incidentTriangles(mesh);
  adj.kind.assign(vertexCount, static_cast<std::uint8_t>(VertexRole::Corner));
  adj.labels.assign(2 * vertexCount, 0);
  adj.start.assign(vertexCount + 1, 0);  // counts first (at v + 1), then offsets
  // One pass writes each vertex's neighbours over its own triangles in the list; they then
  // close up from the front, and the list becomes the neighbour list.
  std::vector<std::vector<std::array<std::uint32_t, 3>>> pinched(static_cast<std::size_t>(chunkCount(vertexCount, threads)));
  parallelChunks(vertexCount, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    ClassifyScratch scratch;
    for (std::size_t v = begin; v < end; ++v) {
      if (in.start[v] == in.start[v + 1]) continue;
      const std::uint32_t t = in.list[in.start[v]];
      adj.labels[2 * v] = mesh.labels[2 * t];
      adj.labels[2 * v + 1] = mesh.labels[2 * t + 1];
      scratch.tris.assign(in.list.begin() + in.start[v], in.list.begin() + in.start[v + 1]);
      adj.start[v + 1] = classifyVertex(mesh, v, junctions, scratch, in.list.data() + in.start[v], adj.kind[v]);
    }
    pinched[static_cast<std::size_t>(chunk)] = std::move(scratch.pinched);
  });
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const std::uint32_t count = adj.start[v + 1];
    adj.start[v + 1] += adj.start[v];
    if (count && adj.start[v] != in.start[v])  // start[v] <= in.start[v]: ranges may overlap
      std::memmove(in.list.data() + adj.start[v], in.list.data() + in.start[v], count * sizeof(std::uint32_t));
  }
  in.list.resize(adj.start.back());
  adj.neighbours = std::move(in.list);
  for (const auto& p : pinched) adj.pinchedLinks.insert(adj.pinchedLinks.end(), p.begin(), p.end());
  return adj;
}

// The ends of the grid edge whose midpoint is the vertex with this key (as carrierOfKey's
// corners, for a key with residues 0 and 6 only).
void edgeOfKey(const Grid& grid, std::uint64_t key, Vec3& a, Vec3& b) {
  const std::uint64_t c[3] = {key & kKeyMask, (key >> kKeyBits) & kKeyMask, (key >> (2 * kKeyBits)) & kKeyMask};
  int lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = static_cast<int>(c[k] / 12);
    hi[k] = lo[k] + (c[k] % 12 != 0 ? 1 : 0);
  }
  a = cornerPosition(grid, lo);
  b = cornerPosition(grid, hi);
}

// Where the interpolated labels change along the vertex's carrier edge: its corners'
// clearances weighted as marching cubes weights its corner values; -1 when not on an edge.
double clearanceCrossing(const Grid& grid, std::span<const std::uint16_t> clearance, std::uint64_t key) {
  const Carrier c = carrierOfKey(key);
  if (c.count != 2) return -1;
  const double a = clearance[grid.index(c.corners[0][0], c.corners[0][1], c.corners[0][2])];
  const double b = clearance[grid.index(c.corners[1][0], c.corners[1][1], c.corners[1][2])];
  return a + b > 0 ? a / (a + b) : 0.5;
}

// Plane vertices (contour-fitted) go to their contour crossing, or on interpolated volumes to where the
// interpolated labels change along their edge, and stay: the surface between the contour
// planes is then the interpolated shape itself, which relaxation inside each vertex's simplex
// could only roughen on the finer grid (an orange-peel texture in the previews).
// An incidental pair's interface vertex on a contour plane goes to the pair's medial line
// instead of onto either drawn outline (geometry/overlaps/overlap_split.h).
void placeOnMedialLines(const MultiLabelMesh& mesh, const Grid& grid, const Adjacency& adj, const MedialCrossings& medial,
                        std::vector<double>& t) {
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    if (!medial.separates(adj.labels[2 * v], adj.labels[2 * v + 1])) continue;  // most vertices: no key decoding
    const Carrier c = carrierOfKey(mesh.keys[v]);
    if (c.count != 2 || c.corners[0][2] != c.corners[1][2]) continue;
    const auto point = [&](const int* corner) {
      return Point2{grid.originX + corner[0] * grid.spacingX, grid.originY + corner[1] * grid.spacingY};
    };
    const double m =
        medial.crossing(adj.labels[2 * v], adj.labels[2 * v + 1], grid.layerZ[static_cast<std::size_t>(c.corners[0][2])],
                        point(c.corners[0]), point(c.corners[1]));
    if (m >= 0) t[v] = m;
  }
}

// Returns the keys of the vertices the blend placed between two planes of their structure (sorted).
std::vector<std::uint64_t> placeFittedVertices(MultiLabelMesh& mesh, const Grid& grid, const ContourSet* contours,
                                               std::span<const std::uint16_t> clearance, Adjacency& adj, int threads,
                                               const MedialCrossings* medial) {
  std::vector<std::uint64_t> heldKeys;
  std::vector<double> t = contours ? fitContourCrossings(grid, *contours, mesh.keys, adj.labels, threads)
                                   : std::vector<double>(mesh.vertexCount(), -1.0);
  if (medial && !medial->empty()) placeOnMedialLines(mesh, grid, adj, *medial, t);
  if (contours) {  // where no layer separates two planes: the blend across them, at the vertices
    const BlendedCrossings blended = blendedCrossings(grid, *contours, mesh.keys, adj.labels, threads);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
      if (t[v] < 0 && blended.t[v] >= 0) {
        t[v] = blended.t[v];
        if (blended.interior[v]) heldKeys.push_back(mesh.keys[v]);
      }
  }
  if (clearance.size() == grid.voxelCount())
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
      if (t[v] < 0) t[v] = clearanceCrossing(grid, clearance, mesh.keys[v]);
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    if (t[v] < 0) continue;
    const Carrier c = carrierOfKey(mesh.keys[v]);
    const double tc = std::clamp(t[v], kMargin, 1 - kMargin);
    const Vec3 a = cornerPosition(grid, c.corners[0]), b = cornerPosition(grid, c.corners[1]);
    for (int k = 0; k < 3; ++k) mesh.positions[3 * v + k] = static_cast<float>(a[k] + tc * (b[k] - a[k]));
    adj.kind[v] = static_cast<std::uint8_t>(VertexRole::Plane);
  }
  return heldKeys;  // keys are sorted, and so are their vertices
}

// Fixes the vertices whose carrier is a single grid point (nowhere to move), marks the sheet
// vertices whose carrier is an edge (kOnEdge), and counts the roles.
SmoothingReport settleRoles(const std::vector<std::uint64_t>& keys, std::vector<std::uint8_t>& kind) {
  SmoothingReport report;
  for (std::size_t v = 0; v < kind.size(); ++v) {
    const VertexRole role = roleOf(kind[v]);
    if (role == VertexRole::Sheet || role == VertexRole::Curve) {
      const int count = carrierOfKey(keys[v]).count;
      if (count < 2)
        kind[v] = static_cast<std::uint8_t>(VertexRole::Corner);
      else if (role == VertexRole::Sheet && count == 2)
        kind[v] |= kOnEdge;
    }
    switch (roleOf(kind[v])) {
      case VertexRole::Sheet: ++report.sheet; break;
      case VertexRole::Curve: ++report.curve; break;
      case VertexRole::Corner: ++report.fixed; break;
      case VertexRole::Plane: ++report.fitted; break;
    }
  }
  return report;
}

// The relaxation's working set: vertex positions in float, one 16-byte lane group per vertex
// (x, y, z, t) so that a gather and a sum are one vector operation each. Every update is
// computed from small differences (neighbour - vertex, position along the carrier edge), so
// float loses nothing beyond the final rounding to float that the mesh stores anyway.
//
// Each plain sweep moves a vertex by strength * (kTension * U - kBending * U^2), then into its
// carrier (a stage of a super-step combines that step with the last two positions, Stage). Bending alone is stable below 0.5 for
// uniform weights (eigenvalues of U^2 <= 4) and would extrapolate a cap past the last contour by the chord slope of the rings
// below; a little tension balances that (measured on spheres and tori, see smoothing_test.cpp).
//
// A sheet vertex on a carrier edge e = b - a then goes where the plane through its target
// with normal n cuts the edge (t clamped to [kMargin, 1 - kMargin]): it follows the
// surface's normal motion and ignores tangential drift, which a nearest-point projection
// onto a slanted edge would turn into normal error. With the target p + d and p = a + t e,
// that cut is t + d . n / (e . n), so the slope n / (e . n) is all a sweep needs. Where the
// edge runs nearly inside the tangent plane (e.n^2 < 0.01 |e|^2 |n|^2), and for every other
// vertex, the target's nearest point of the carrier.
// One stage of a super-step: the vertex goes to mu * (its position) + nu * (its position one
// sweep earlier) + w * (its step), then into its carrier. A plain sweep is {1, 0, 1}.
struct Stage {
  float mu = 1, nu = 0, w = 1;
};

class Relaxation {
 public:
  // Takes over mesh.positions (released until storeInto, its memory serves the sweeps) and
  // the roles in adj.kind, which must outlive this object.
  // With a guard, every sweep's moves keep the triangles as it allows.
  Relaxation(MultiLabelMesh& mesh, const Grid& grid, Adjacency& adj, double strength, AngleGuard& guard, int threads);

  // One Jacobi sweep over the vertices that relax, a stage of a super-step (see Stage); refreshNormals
  // recomputes the slide slopes.
  void sweep(const Stage& stage, bool refreshNormals);
  // Frees the working set and writes the positions back into mesh.positions.
  void storeInto(MultiLabelMesh& mesh);

 private:
  void startOnCarrierEdges();
  void findRelaxing();
  Float4 edgeVectorOf(std::uint8_t kind, const Float4& a) const;
  Float4 edgeStartOf(std::size_t v) const;
  Vec3 normalOf(std::size_t v) const;
  void computeUmbrella(std::size_t v, bool refreshNormals);
  void refreshSlide(std::size_t v);
  Float4 stepOf(std::size_t v) const;
  void moveVertex(std::size_t v, const Stage& stage);
  Float4 alongCarrierEdge(std::size_t v, std::uint8_t kind, float along, const Float4& d) const;
  Float4 intoCarrier(std::size_t v, const Float4& p, const Float4& d) const;

  const Grid& grid_;
  AngleGuard& guard_;
  const int threads_;
  const std::size_t vertexCount_;
  // The adjacency and keys as plain arrays, for the per-vertex loops.
  std::uint8_t* const kinds_;
  const std::uint32_t* const start_;
  const std::uint32_t* const neighbours_;
  const std::vector<std::array<std::uint32_t, 3>>& pinchedLinks_;
  const std::uint64_t* const keys_;
  const float stepX_, stepY_;      // grid spacing, the x and y extent of a carrier edge
  const float bending_, tension_;  // kBending and kTension at the options' strength
  HugeVector<Float4> cur_;         // positions before the sweep
  // After it; before it, the positions of the sweep before cur_ (a stage's second term).
  // Corner and plane vertices hold the same value in both.
  HugeVector<Float4> next_;
  // Umbrella operator U(v) = mean of neighbours - v (last lane unused); zero where a vertex has
  // none.
  HugeVector<Float4> umbrella_;
  // A sheet vertex on its carrier edge a -> b is a + t (b - a), t in its position's last lane:
  // edgeStartOf gives a and (b - a).z from its key, kStepX and kStepY say whether b - a has
  // x, y components (one grid spacing), and slope, while the vertex slides along the normal n,
  // holds n / ((b - a) . n). Zero for other vertices.
  HugeVector<Float4> slope_;
  std::vector<std::uint32_t> relaxing_, umbrellaSet_;  // see findRelaxing
  std::vector<std::uint32_t> watched_;                 // the triangles of the vertices that relax, for the guard
};

Relaxation::Relaxation(MultiLabelMesh& mesh, const Grid& grid, Adjacency& adj, double strength, AngleGuard& guard, int threads)
    : grid_(grid),
      guard_(guard),
      threads_(threads),
      vertexCount_(mesh.vertexCount()),
      kinds_(adj.kind.data()),
      start_(adj.start.data()),
      neighbours_(adj.neighbours.data()),
      pinchedLinks_(adj.pinchedLinks),
      keys_(mesh.keys.data()),
      stepX_(static_cast<float>(grid.spacingX)),
      stepY_(static_cast<float>(grid.spacingY)),
      bending_(static_cast<float>(kBending * std::clamp(strength, 0.0, 1.0))),
      tension_(static_cast<float>(kTension * std::clamp(strength, 0.0, 1.0))),
      cur_(vertexCount_) {
  for (std::size_t v = 0; v < vertexCount_; ++v)
    cur_[v] = Float4{mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2], 0.0f};
  std::vector<float>().swap(mesh.positions);
  slope_.assign(vertexCount_, Float4{0, 0, 0, 0});
  startOnCarrierEdges();
  next_ = cur_;
  umbrella_.assign(vertexCount_, Float4{0, 0, 0, 0});
  findRelaxing();
  if (guard.enabled()) watched_ = guard.trianglesAround(relaxing_);
}

// The vertices that relax (sheet and curve) and those whose umbrellas their steps read (they
// and their neighbours): on interpolated volumes almost every vertex is placed and stays, and
// a sweep over these lists alone costs a small fraction of one over every vertex.
void Relaxation::findRelaxing() {
  std::vector<std::uint8_t> needed(vertexCount_, 0);
  for (std::size_t v = 0; v < vertexCount_; ++v)
    if (roleOf(kinds_[v]) == VertexRole::Sheet || roleOf(kinds_[v]) == VertexRole::Curve) {
      relaxing_.push_back(static_cast<std::uint32_t>(v));
      needed[v] = 1;
      for (std::uint32_t i = start_[v]; i < start_[v + 1]; ++i) needed[neighbours_[i]] = 1;
    }
  for (std::size_t v = 0; v < vertexCount_; ++v)
    if (needed[v]) umbrellaSet_.push_back(static_cast<std::uint32_t>(v));
}

// Puts each vertex that slides along its carrier edge into the edge form a + t (b - a).
void Relaxation::startOnCarrierEdges() {
  parallelChunks(vertexCount_, threads_, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
      if (kinds_[v] & kOnEdge) {
        Vec3 a, b;
        edgeOfKey(grid_, keys_[v], a, b);
        double de = 0, ee = 0;
        for (int k = 0; k < 3; ++k) de += (cur_[v][k] - a[k]) * (b[k] - a[k]), ee += (b[k] - a[k]) * (b[k] - a[k]);
        cur_[v][3] = static_cast<float>(de / ee);
        if (b[0] != a[0]) kinds_[v] |= kStepX;
        if (b[1] != a[1]) kinds_[v] |= kStepY;
      }
  });
}

// a of edge vertex v's carrier edge a -> b, and (b - a).z in the last lane: from its key
// each time (52 MiB less than an array of them on a clinical set, the same floats), as
// edgeOfKey reads it but without b's x and y, since every sweep asks at every edge vertex.
Float4 Relaxation::edgeStartOf(std::size_t v) const {
  const std::uint64_t key = keys_[v], z = (key >> (2 * kKeyBits)) & kKeyMask;
  const int low[3] = {static_cast<int>((key & kKeyMask) / 12), static_cast<int>(((key >> kKeyBits) & kKeyMask) / 12),
                      static_cast<int>(z / 12)};
  const Vec3 a = cornerPosition(grid_, low);
  const double bz = grid_.layerZ[static_cast<std::size_t>(low[2]) + (z % 12 != 0 ? 1 : 0)];
  return Float4{static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2]), static_cast<float>(bz - a[2])};
}

// b - a of the carrier edge that starts at a (edgeStartOf).
Float4 Relaxation::edgeVectorOf(std::uint8_t kind, const Float4& a) const {
  return Float4{(kind & kStepX) ? stepX_ : 0.0f, (kind & kStepY) ? stepY_ : 0.0f, a[3], 0.0f};
}

// The area-weighted normal of sheet vertex v: the sum of cross(a - v, b - v) over its
// triangles (v, a, b), from its link cycle or, for a pinched vertex, its triangles.
Vec3 Relaxation::normalOf(std::size_t v) const {
  const Float4* p = cur_.data();
  Vec3 n{0, 0, 0};
  const auto add = [&](std::uint32_t a, std::uint32_t b) {
    const Float4 da = p[a] - p[v], db = p[b] - p[v];
    const double u[3] = {da[0], da[1], da[2]}, w[3] = {db[0], db[1], db[2]};
    n[0] += u[1] * w[2] - u[2] * w[1];
    n[1] += u[2] * w[0] - u[0] * w[2];
    n[2] += u[0] * w[1] - u[1] * w[0];
  };
  if (kinds_[v] & kPinched) {
    auto l = std::lower_bound(pinchedLinks_.begin(), pinchedLinks_.end(), static_cast<std::uint32_t>(v),
                              [](const std::array<std::uint32_t, 3>& x, std::uint32_t y) { return x[0] < y; });
    for (; l != pinchedLinks_.end() && (*l)[0] == v; ++l) add((*l)[1], (*l)[2]);
  } else {
    const std::uint32_t s = start_[v], e = start_[v + 1];
    for (std::uint32_t i = s; i < e; ++i) add(neighbours_[i], neighbours_[i + 1 == e ? s : i + 1]);
  }
  return n;
}

void Relaxation::sweep(const Stage& stage, bool refreshNormals) {
  parallelChunks(umbrellaSet_.size(), threads_, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) computeUmbrella(umbrellaSet_[i], refreshNormals);
  });
  parallelChunks(relaxing_.size(), threads_, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) moveVertex(relaxing_[i], stage);
  });
  guard_.apply(reinterpret_cast<const float*>(cur_.data()), reinterpret_cast<float*>(next_.data()), 4, &watched_);
  cur_.swap(next_);
}

void Relaxation::computeUmbrella(std::size_t v, bool refreshNormals) {
  const std::uint32_t s = start_[v], e = start_[v + 1];
  if (s == e) return;  // its umbrella stays 0
  const Float4* p = cur_.data();
  const Float4 pv = p[v];
  Float4 sum{0, 0, 0, 0};
  for (std::uint32_t i = s; i < e; ++i) sum += p[neighbours_[i]] - pv;
  umbrella_[v] = sum / static_cast<float>(e - s);
  if (refreshNormals && (kinds_[v] & kOnEdge)) refreshSlide(v);
}

// Whether edge vertex v slides along its normal until the next refresh (kSlides), and its
// slope n / (e . n) if so.
void Relaxation::refreshSlide(std::size_t v) {
  const Vec3 n = normalOf(v);
  const Float4 ev = edgeVectorOf(kinds_[v], edgeStartOf(v));
  const double ed[3] = {ev[0], ev[1], ev[2]};
  const double en = ed[0] * n[0] + ed[1] * n[1] + ed[2] * n[2];
  const double ee = ed[0] * ed[0] + ed[1] * ed[1] + ed[2] * ed[2], nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  if (en * en < 0.01 * ee * nn) {
    kinds_[v] &= static_cast<std::uint8_t>(~kSlides);
  } else {
    kinds_[v] |= kSlides;
    slope_[v] = Float4{static_cast<float>(n[0] / en), static_cast<float>(n[1] / en), static_cast<float>(n[2] / en), 0.0f};
  }
}

// v's target - p: tension * U - bending * U^2.
Float4 Relaxation::stepOf(std::size_t v) const {
  const Float4* u = umbrella_.data();
  const std::uint32_t s = start_[v], e = start_[v + 1];
  Float4 sum{0, 0, 0, 0};
  for (std::uint32_t i = s; i < e; ++i) sum += u[neighbours_[i]];
  const Float4 uv = u[v];
  return tension_ * uv - bending_ * (sum / static_cast<float>(e - s) - uv);
}

void Relaxation::moveVertex(std::size_t v, const Stage& stage) {
  const std::uint8_t kind = kinds_[v];
  const VertexRole role = roleOf(kind);
  if (role == VertexRole::Corner || role == VertexRole::Plane) return;
  // With mu = 1, nu = 0 and w = 1 (a plain sweep) this is exactly p + d.
  const Float4 d = stage.w * stepOf(v);
  const Float4 p = stage.mu * cur_[v] + stage.nu * next_[v];
  next_[v] = (kind & kOnEdge) ? alongCarrierEdge(v, kind, p[3], d) : intoCarrier(v, p, d);
}

// Edge vertex v at t = along on its edge, moved by d: where the tangent plane cuts its edge,
// or the nearest point of the edge; t in the last lane.
Float4 Relaxation::alongCarrierEdge(std::size_t v, std::uint8_t kind, float along, const Float4& d) const {
  const Float4 a = edgeStartOf(v), ev = edgeVectorOf(kind, a);
  float t;
  if (kind & kSlides) {
    const Float4 m = d * slope_[v];
    t = std::clamp(along + (m[0] + m[1] + m[2]), static_cast<float>(kMargin), static_cast<float>(1 - kMargin));
  } else {
    // The nearest point of the edge, weights clamped to kMargin (projectIntoCarrier).
    const Float4 de = d * ev, ee = ev * ev;
    const double w1 = along + (de[0] + de[1] + de[2]) / static_cast<double>(ee[0] + ee[1] + ee[2]);
    const double w0 = std::max(1 - w1, kMargin), w1c = std::max(w1, kMargin);
    t = static_cast<float>(w1c / (w0 + w1c));
  }
  Float4 out = a + t * ev;
  out[3] = t;
  return out;
}

// The nearest point of v's carrier to p + d.
Float4 Relaxation::intoCarrier(std::size_t v, const Float4& p, const Float4& d) const {
  const Vec3 out =
      projectIntoCarrier(grid_, carrierOfKey(keys_[v]),
                         {p[0] + static_cast<double>(d[0]), p[1] + static_cast<double>(d[1]), p[2] + static_cast<double>(d[2])});
  return Float4{static_cast<float>(out[0]), static_cast<float>(out[1]), static_cast<float>(out[2]), 0.0f};
}

void Relaxation::storeInto(MultiLabelMesh& mesh) {
  HugeVector<Float4>().swap(next_);
  HugeVector<Float4>().swap(umbrella_);
  HugeVector<Float4>().swap(slope_);
  mesh.positions.resize(3 * vertexCount_);
  for (std::size_t v = 0; v < vertexCount_; ++v)
    for (int k = 0; k < 3; ++k) mesh.positions[3 * v + k] = cur_[v][k];
}

// The stages that smooth as much as `iterations` plain sweeps at this strength: super-steps of
// RKL1 (see the top of this file) of at most kSuperStep sweeps each, each with the fewest
// stages that keep it stable.
std::vector<Stage> scheduleOf(int iterations, double strength) {
  std::vector<Stage> stages;
  if (iterations <= 0) return stages;
  const int supers = (iterations + kSuperStep - 1) / kSuperStep;
  const double tau = static_cast<double>(iterations) / supers;  // plain sweeps per super-step
  // A plain sweep's largest step factor: strength (kTension |u| + kBending u^2) at u = -2, the
  // least eigenvalue an umbrella operator can have.
  const double lambda = std::clamp(strength, 0.0, 1.0) * (2 * kTension + 4 * kBending);
  int s = 1;
  while (s * (s + 1) < kStability * tau * lambda) ++s;
  const double w1 = 2.0 / (s * (s + 1));
  for (int k = 0; k < supers; ++k)
    for (int j = 1; j <= s; ++j) {
      const double mu = (2.0 * j - 1) / j, nu = (1.0 - j) / j;
      stages.push_back({static_cast<float>(mu), static_cast<float>(nu), static_cast<float>(mu * w1 * tau)});
    }
  return stages;
}

}  // namespace

SmoothingReport smoothMesh(MultiLabelMesh& mesh, const Grid& grid, const ContourSet* contours, const SmoothingOptions& options,
                           int threads, std::span<const std::uint16_t> clearance, const MedialCrossings* medial) {
  const std::size_t vertexCount = mesh.vertexCount();
  if (!options.enabled || vertexCount == 0 || mesh.keys.size() != vertexCount) return {};
  Adjacency adj = buildAdjacency(mesh, options.junctions, threads);
  AngleGuard guard(mesh, options.minAngle, threads);
  std::vector<std::uint64_t> heldKeys;
  if (options.contourFit && (contours || !clearance.empty())) {
    const std::vector<float> assembled = guard.enabled() ? mesh.positions : std::vector<float>();
    heldKeys = placeFittedVertices(mesh, grid, contours, clearance, adj, threads, medial);
    guard.apply(assembled.data(), mesh.positions.data(), 3);
  }
  std::vector<Label>().swap(adj.labels);  // only the contour fit needs them
  SmoothingReport report = settleRoles(mesh.keys, adj.kind);
  Relaxation relaxation(mesh, grid, adj, options.strength, guard, threads);
  const std::vector<Stage> schedule = scheduleOf(options.iterations, options.strength);
  for (std::size_t it = 0; it < schedule.size(); ++it) {
    // Normals turn slowly; refreshing them every few sweeps saves most of a sweep's time.
    relaxation.sweep(schedule[it], it % kNormalPeriod == 0);
  }
  report.sweeps = static_cast<int>(schedule.size());
  report.betweenPlanes = std::move(heldKeys);
  report.onSheet.resize(vertexCount);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const VertexRole role = roleOf(adj.kind[v]);
    report.onSheet[v] = role == VertexRole::Sheet || role == VertexRole::Plane;
  }
  relaxation.storeInto(mesh);
  return report;
}

}  // namespace scansurf
