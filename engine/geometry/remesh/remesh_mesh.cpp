// Isotropic remeshing of the separating-surface network (Botsch & Kobbelt, "A remeshing
// approach to multiresolution modeling", SGP 2004): split edges longer than 4/3 L, collapse
// those shorter than 4/5 L, flip toward Delaunay, relax tangentially and project back onto
// the smoothed surface; four rounds, the last three with a target length graded down around
// the feature-line edges that stayed short (gradeSizes). Then a few passes move each sheet
// vertex along its normal so that the remeshed surface is centred on the smoothed one rather
// than inscribed in it.
//
// The network is not a manifold: junction curves (edges of three or more triangles, or of two
// triangles of different label pairs) and the cross-sections at the contour planes are
// feature lines. Their vertices move, split and collapse only along them (curve and plane
// vertices project onto the smoothed curve or cross-section, the original contour's fit);
// their meeting points (corners) never move. Flips never touch a feature edge.
//
// Smoothing could prove its surfaces never cross from where its vertices may go; remeshing
// cannot, so every operation is tried, checked and undone if it fails (remesh_network.h): each
// feature surface of both conventions stays one oriented fan around every touched vertex with
// its feature edges unchanged (closed, manifold, oriented, same genus), every new triangle is
// tested exactly against every triangle near it (geometry/mesh/triangle_intersection.h), none
// turns over, and new triangles stay within a tenth of a voxel of the smoothed sheet of their
// label pair (in-plane edges: a twentieth of the cross-section). Large networks are remeshed
// chunk by chunk, the chunks of a phase in parallel (remesh_chunks.h); each chunk serially, so
// the result is the same for any thread count.
#include "geometry/remesh/remesh_mesh.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>
#include <vector>

#include "core/parallel.h"
#include "geometry/mesh/triangle_intersection.h"
#include "geometry/remesh/remesh_chunks.h"
#include "geometry/remesh/remesh_network.h"
#include "geometry/remesh/remesh_reference.h"

namespace scansurf {
namespace {

using namespace remesh;

constexpr double kSurfaceBound = 0.1;  // voxels: new triangles off the smoothed sheet
constexpr double kPlaneBound = 0.05;   // voxels: new in-plane edges off the cross-section
constexpr double kTurnCos = 0.5;       // least cosine between a triangle's normal before and after
// Centring passes (fit): moving one vertex by d moves its triangles' samples by d / 3 on
// average, all of them together by d; 2 settles the test shapes in 4 passes as 1.5 did in 8.
constexpr double kFitRelaxation = 2.0;
constexpr int kFitPasses = 4;
// The default edge length, in in-plane voxels: about as many triangles as flying edges +
// windowed sinc while the analytic shapes keep smoothing's volume error; beyond it, with
// contour planes two pixels apart, one row of free vertices no longer fits between them and the
// chords from plane to plane lose volume that centring cannot restore.
constexpr double kDefaultLength = 1.15;
// ... and at least this fraction of the contour planes' median gap. Between the planes the
// surface is an interpolation with no detail at the pixel scale, and flying edges on the slice
// lattice makes triangles as tall as the gap: with pixels far finer than the gap, a length in
// pixels alone would give far more triangles than it. Three rows of free vertices still fit
// between two planes, so centring keeps the volume.
constexpr double kPlaneGapFraction = 0.33;
// Graded sizes around short feature edges (gradeSizes): the target drops to kFeatureGrade
// times such an edge and grows back by kGradeSlope per unit of distance.
constexpr double kFeatureGrade = 1.5, kGradeSlope = 0.6;
// Curvature sizing: chords may stand kCurvatureSagitta voxels inside the surface at their
// middle, twice the distance bound, since centring (fit) splits that gap between inside and
// outside; the target shrinks to no less than kLeastCurvatureSize L (a thin bar's sharp ends).
// Edges under kShortestCurvatureEdge L do not measure curvature (curvatureSize).
constexpr double kCurvatureSagitta = 2 * kSurfaceBound, kLeastCurvatureSize = 0.3, kShortestCurvatureEdge = 0.3;
constexpr double kHigh = 4.0 / 3.0, kLow = 4.0 / 5.0;  // Botsch & Kobbelt's split and collapse bounds

using Edge = std::pair<std::uint32_t, std::uint32_t>;

// The target edge length: the option's if usable, else kDefaultLength pixels or
// kPlaneGapFraction of the median gap between contour planes, whichever is longer.
double targetLength(const RemeshOptions& options, const Grid& grid, const std::vector<double>& planes) {
  if (std::isfinite(options.edgeLength) && options.edgeLength > 0) return options.edgeLength;
  const double pixels = kDefaultLength * std::min(grid.spacingX, grid.spacingY);
  if (planes.size() < 2) return pixels;
  std::vector<double> gaps;
  for (std::size_t i = 1; i < planes.size(); ++i) gaps.push_back(planes[i] - planes[i - 1]);
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  return std::max(pixels, kPlaneGapFraction * gaps[gaps.size() / 2]);
}

Point3 point(const Vec3& v) { return {v[0], v[1], v[2]}; }

double angleAt(const Vec3& o, const Vec3& p, const Vec3& q) {
  const Vec3 u = p - o, v = q - o;
  const double nu = std::sqrt(dot(u, u)), nv = std::sqrt(dot(v, v));
  if (nu == 0 || nv == 0) return 0;
  return std::acos(std::clamp(dot(u, v) / (nu * nv), -1.0, 1.0));
}

// What every remesher of one run shares: read-only, so chunks may use it at once.
struct Context {
  std::vector<double> planes;  // the contour planes' z, ascending
  double sliceTolerance, length, voxel;
  double sagitta;  // curvature sizing's chord tolerance, input units (0: off)
  int iterations;
  const SurfaceTable& surfaces;
  const ReferenceSurface& reference;
};

class Remesher {
 public:
  // The whole network (sub = null), or a work unit's part of it with its pins.
  Remesher(Network net, const Context& context, const WorkUnit& unit, const SubMesh* sub)
      : length_(context.length),
        voxel_(context.voxel),
        sagitta_(context.sagitta),
        lo_(unit.lo),
        hi_(unit.hi),
        net_(std::move(net)),
        surfaces_(context.surfaces),
        reference_(context.reference) {
    if (!sub) return;
    pinned_ = sub->pinned;
    rim_ = sub->rim;
    settled_ = sub->settled;
    for (std::uint32_t v = 0; v < pinned_.size(); ++v)
      if (pinned_[v]) net_.pin(v);
  }

  // `iterations` rounds, graded from the second on (from the first on an already remeshed
  // band: an ungraded round would coarsen what grading refined), then the centring passes.
  void run(int iterations, bool remeshedBefore = false);
  void storeInto(MultiLabelMesh& mesh) { net_.storeInto(mesh); }
  // The unit's result: every vertex's position and the live triangles but sub's fixed ones.
  UnitResult result(const SubMesh& sub) const;
  // The operations applied and refused, in a report's fields.
  RemeshReport counts() const {
    RemeshReport r;
    r.splits = splits, r.collapses = collapses, r.flips = flips, r.moves = moves, r.rejected = rejected;
    return r;
  }

 private:
  std::size_t splits = 0, collapses = 0, flips = 0, moves = 0, rejected = 0;
  // settledOnly: graded around the feature edges of settled vertices only.
  void round(bool graded, bool settledOnly = false);
  void relaxAll();
  void fitAll();
  // Per-vertex flags of a work unit's submesh; false for new vertices and whole meshes.
  static bool flagged(const std::vector<char>& flags, std::uint32_t v) { return v < flags.size() && flags[v]; }
  bool pinned(std::uint32_t v) const { return flagged(pinned_, v); }
  bool settled(std::uint32_t v) const { return flagged(settled_, v); }
  void liveEdges(std::vector<Edge>& out) const;
  // The area-weighted normal of v's fan (a sheet vertex's: one label pair), not normalised.
  Vec3 fanNormal(std::uint32_t v) const {
    Vec3 n{0, 0, 0};
    for (std::uint32_t t : net_.vtris[v]) n = n + net_.normal(t);
    return n;
  }
  double length(std::uint32_t a, std::uint32_t b) const {
    const Vec3 d = net_.pos[a] - net_.pos[b];
    return std::sqrt(dot(d, d));
  }
  bool split(std::uint32_t a, std::uint32_t b);
  void gradeSizes();
  double curvatureSize(std::uint32_t v);
  // The target edge length at v, and of the edge ab.
  double sizeAt(std::uint32_t v) const { return v < size_.size() ? size_[v] : length_; }
  double target(std::uint32_t a, std::uint32_t b) const {
    if (settledOnly_ && !(settled(a) && settled(b))) return length_;  // a cut's smoothed triangles: ungraded
    return std::min(sizeAt(a), sizeAt(b));
  }
  bool collapse(std::uint32_t u, std::uint32_t v);
  bool flip(std::uint32_t a, std::uint32_t b);
  bool relax(std::uint32_t v);
  bool relaxTo(std::uint32_t v, const Vec3& target);
  bool fit(std::uint32_t v);
  // Checks the open change (added triangles from change_.firstAdded, their normals before in
  // before_) around `touched` (none: the connectivity did not change); commits it or undoes it.
  bool settle(const std::vector<std::uint32_t>& touched);
  bool shapeHolds() const;
  bool nearSmoothed();
  bool crossesNothing();

  double length_, voxel_;
  double sagitta_;  // Context::sagitta
  double lo_, hi_;  // new triangles strictly between, in z (WorkUnit)
  Network net_;
  const SurfaceTable& surfaces_;
  const ReferenceSurface& reference_;
  std::vector<char> pinned_, rim_, settled_;  // per vertex of a work unit's submesh (SubMesh)
  bool settledOnly_ = false;                  // this round grades settled vertices only
  Change change_;
  std::vector<Vec3> before_;  // per added triangle, the normal it must not turn away from
  std::vector<double> size_;  // per vertex, the target edge length (empty: length_ everywhere)
  std::vector<std::uint32_t> scratch_, candidates_;
  // Per-operation lists, kept to reuse their memory: an operation costs some 40 us, and a
  // handful of allocations each was a few per cent of it.
  std::vector<std::uint32_t> edgeTris_, touched_, around_, along_;
  std::vector<std::array<std::uint32_t, 3>> done_;  // nearSmoothed's edges looked up
  std::vector<std::pair<Edge, Nearest>> fitted_;    // fit's edge midpoints looked up
  struct Box {
    Vec3 lo, hi;
    bool touches(const Box& o) const {
      for (int k = 0; k < 3; ++k)
        if (hi[k] < o.lo[k] || lo[k] > o.hi[k]) return false;
      return true;
    }
  };
  std::vector<std::pair<std::uint32_t, Box>> near_;  // crossesNothing's candidates near the change
};

void Remesher::liveEdges(std::vector<Edge>& out) const {
  out.clear();
  for (std::uint32_t t = 0; t < net_.tris.size(); ++t) {
    if (!net_.alive[t]) continue;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = net_.tris[t][c], b = net_.tris[t][(c + 1) % 3];
      out.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

// ---------------------------------------------------------------- checks

bool Remesher::shapeHolds() const {
  for (std::uint32_t t = change_.firstAdded; t < net_.tris.size(); ++t) {
    for (std::uint32_t v : net_.tris[t])
      if (!(net_.pos[v][2] > lo_ && net_.pos[v][2] < hi_)) return false;  // out of the unit's region
    const Vec3 n = net_.normal(t), m = before_[t - change_.firstAdded];
    const double nn = std::sqrt(dot(n, n)), mm = std::sqrt(dot(m, m));
    if (nn <= 1e-9 * length_ * length_ || dot(n, m) < kTurnCos * nn * mm) return false;
    const auto& c = net_.tris[t];
    if (isDegenerate({point(net_.pos[c[0]]), point(net_.pos[c[1]]), point(net_.pos[c[2]])})) return false;
  }
  return true;
}

// Edge midpoints whose geometry the change did not touch (an edge of a removed triangle of the
// same pair, between unmoved vertices) passed when they were made, and so did unmoved
// vertices: each was checked against every sheet it lies on when it was placed, and no edit
// puts a vertex on a new sheet (a collapse moves u's triangles to v only along an edge that
// already joins v to u's sheets). Every centroid, the new and moved vertices and the other
// edges' midpoints are looked up.
bool Remesher::nearSmoothed() {
  const double bound = kSurfaceBound * voxel_, planeBound = kPlaneBound * voxel_;
  const auto changed = [&](std::uint32_t v) {
    if (change_.addedVertex && v + 1 == net_.vertexCount()) return true;
    for (const auto& m : change_.moved)
      if (m.first == v) return true;
    return false;
  };
  const auto oldEdge = [&](std::uint32_t a, std::uint32_t b, std::uint32_t pairOf) {
    for (std::uint32_t t : change_.removed) {
      const auto& c = net_.tris[t];
      if (net_.pair[t] == pairOf && (c[0] == a || c[1] == a || c[2] == a) && (c[0] == b || c[1] == b || c[2] == b)) return true;
    }
    return false;
  };
  std::vector<std::array<std::uint32_t, 3>>& done = done_;  // (a, b, pair) of the edges looked up, a == b for vertices
  done.clear();
  const auto once = [&](std::uint32_t a, std::uint32_t b, std::uint32_t pairOf) {
    const std::array<std::uint32_t, 3> key = {std::min(a, b), std::max(a, b), pairOf};
    if (std::find(done.begin(), done.end(), key) != done.end()) return false;
    done.push_back(key);
    return true;
  };
  for (std::uint32_t t = change_.firstAdded; t < net_.tris.size(); ++t) {
    const auto& c = net_.tris[t];
    const FeatureKey sheet = sheetKey(net_.pair[t]);
    if (!reference_.within((1.0 / 3) * (net_.pos[c[0]] + net_.pos[c[1]] + net_.pos[c[2]]), sheet, bound)) return false;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = c[e], b = c[(e + 1) % 3];
      const bool moved = changed(a) || changed(b);
      if (changed(a) && once(a, a, net_.pair[t]) && !reference_.within(net_.pos[a], sheet, bound)) return false;
      if ((!moved && oldEdge(a, b, net_.pair[t])) || !once(a, b, net_.pair[t])) continue;
      if (!reference_.within(0.5 * (net_.pos[a] + net_.pos[b]), sheet, bound)) return false;
      if (!net_.isInPlaneEdge(a, b)) continue;
      const FeatureKey key = planeKey(net_.plane[a], net_.pair[t]);
      for (double f : {0.25, 0.5, 0.75})
        if (!reference_.within(net_.pos[a] + f * (net_.pos[b] - net_.pos[a]), key, planeBound)) return false;
    }
  }
  return true;
}

// One broad-phase query for the whole change (its new triangles lie side by side); the
// candidates whose boxes touch the change's box are kept with their boxes, then each new
// triangle is tested against those whose boxes touch its own, and against the other new ones.
bool Remesher::crossesNothing() {
  const auto end = static_cast<std::uint32_t>(net_.tris.size());
  if (change_.firstAdded == end) return true;
  const auto corners = [&](std::uint32_t t) {
    const auto& c = net_.tris[t];
    return std::array<Point3, 3>{point(net_.pos[c[0]]), point(net_.pos[c[1]]), point(net_.pos[c[2]])};
  };
  const auto boxOf = [&](std::uint32_t t) {
    const auto& c = net_.tris[t];
    Box b{net_.pos[c[0]], net_.pos[c[0]]};
    for (int i = 1; i < 3; ++i)
      for (int k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], net_.pos[c[i]][k]), b.hi[k] = std::max(b.hi[k], net_.pos[c[i]][k]);
    return b;
  };
  Box all = boxOf(change_.firstAdded);
  for (std::uint32_t t = change_.firstAdded + 1; t < end; ++t) {
    const Box b = boxOf(t);
    for (int k = 0; k < 3; ++k) all.lo[k] = std::min(all.lo[k], b.lo[k]), all.hi[k] = std::max(all.hi[k], b.hi[k]);
  }
  net_.grid.query(all.lo, all.hi, net_.alive, change_.removed, candidates_);
  near_.clear();
  for (std::uint32_t u : candidates_) {
    if (u >= change_.firstAdded) continue;
    const Box b = boxOf(u);
    if (b.touches(all)) near_.push_back({u, b});
  }
  for (std::uint32_t t = change_.firstAdded; t < end; ++t) {
    if (!net_.alive[t]) continue;
    const auto a = corners(t);
    const Box box = boxOf(t);
    for (const auto& [u, b] : near_)
      if (b.touches(box) && trianglesCross(net_.tris[t], a, net_.tris[u], corners(u))) return false;
    for (std::uint32_t u = t + 1; u < end; ++u)
      if (net_.alive[u] && boxOf(u).touches(box) && trianglesCross(net_.tris[t], a, net_.tris[u], corners(u))) return false;
  }
  return true;
}

bool Remesher::settle(const std::vector<std::uint32_t>& touched) {
  if (shapeHolds() && topologyHolds(net_, surfaces_, touched) && nearSmoothed() && crossesNothing()) {
    net_.commit(change_);
    return true;
  }
  net_.undo(change_);
  ++rejected;
  return false;
}

// ---------------------------------------------------------------- operations

bool Remesher::split(std::uint32_t a, std::uint32_t b) {
  if (pinned(a) && pinned(b)) return false;  // its triangles may be another unit's
  std::vector<std::uint32_t>& edgeTris = edgeTris_;
  net_.edgeTriangles(a, b, edgeTris);
  if (edgeTris.empty()) return false;
  const bool junction = net_.isJunctionEdge(edgeTris);
  const bool inPlane = !junction && net_.isInPlaneEdge(a, b);
  const FeatureKey key = junction  ? curveKey(net_, edgeTris)
                         : inPlane ? planeKey(net_.plane[a], net_.pair[edgeTris[0]])
                                   : sheetKey(net_.pair[edgeTris[0]]);
  const Nearest m = reference_.nearestNear(0.5 * (net_.pos[a] + net_.pos[b]), key, length(a, b));
  if (!m.found) return false;
  net_.begin(change_);
  before_.clear();
  const VertexRole role = junction ? VertexRole::Curve : inPlane ? VertexRole::Plane : VertexRole::Sheet;
  const std::uint32_t mid = net_.addVertex(storable(m.point), role, inPlane ? net_.plane[a] : -1, change_);
  std::vector<std::uint32_t>& touched = touched_;
  touched.assign({a, b, mid});
  for (std::uint32_t t : edgeTris) {
    const auto c = net_.tris[t];
    const Vec3 n = net_.normal(t);
    net_.removeTriangle(t, change_);
    // (x, y, z) with edge x -> y becomes (x, mid, z) and (mid, y, z), same winding.
    const int e = (c[0] != a && c[0] != b) ? 1 : (c[1] != a && c[1] != b) ? 2 : 0;
    const std::uint32_t x = c[e], y = c[(e + 1) % 3], z = c[(e + 2) % 3];
    net_.addTriangle(x, mid, z, net_.pair[t], change_);
    net_.addTriangle(mid, y, z, net_.pair[t], change_);
    before_.push_back(n);
    before_.push_back(n);
    touched.push_back(z);
  }
  const double inherited = target(a, b);
  if (!settle(touched)) return false;
  if (!size_.empty()) size_.resize(net_.vertexCount(), length_), size_[mid] = inherited;
  return true;
}

int rank(VertexRole r) { return r == VertexRole::Sheet ? 0 : r == VertexRole::Corner ? 2 : 1; }

// u goes into v (v stays where it is).
bool Remesher::collapse(std::uint32_t u, std::uint32_t v) {
  const VertexRole ru = net_.role[u], rv = net_.role[v];
  if (ru == VertexRole::Corner || rank(ru) > rank(rv)) return false;
  std::vector<std::uint32_t>& edgeTris = edgeTris_;
  net_.edgeTriangles(u, v, edgeTris);
  const bool junction = net_.isJunctionEdge(edgeTris);
  if (ru == VertexRole::Curve && !junction) return false;                  // only along its curve
  if (ru == VertexRole::Plane && !net_.isInPlaneEdge(u, v)) return false;  // only along its cross-section
  net_.neighbours(u, scratch_);
  for (std::uint32_t w : scratch_)
    if (w != v && length(v, w) > kHigh * target(v, w)) return false;
  net_.begin(change_);
  before_.clear();
  touched_ = scratch_;
  around_ = net_.vtris[u];
  const std::vector<std::uint32_t>& around = around_;
  for (std::uint32_t t : around) {
    auto c = net_.tris[t];
    const Vec3 n = net_.normal(t);
    net_.removeTriangle(t, change_);
    if (c[0] == v || c[1] == v || c[2] == v) continue;
    for (auto& x : c)
      if (x == u) x = v;
    net_.addTriangle(c[0], c[1], c[2], net_.pair[t], change_);
    before_.push_back(n);
  }
  return settle(touched_);
}

bool Remesher::flip(std::uint32_t a, std::uint32_t b) {
  if (net_.isInPlaneEdge(a, b) || (pinned(a) && pinned(b))) return false;
  std::vector<std::uint32_t>& edgeTris = edgeTris_;
  net_.edgeTriangles(a, b, edgeTris);
  if (net_.isJunctionEdge(edgeTris)) return false;
  // t1 = (a, b, c) and t2 = (b, a, d) in winding order, relabelling a and b if need be.
  auto t1 = net_.tris[edgeTris[0]];
  while (t1[2] == a || t1[2] == b) std::rotate(t1.begin(), t1.begin() + 1, t1.end());
  a = t1[0], b = t1[1];
  const std::uint32_t c = t1[2];
  const auto& t2 = net_.tris[edgeTris[1]];
  const std::uint32_t d = t2[0] != a && t2[0] != b ? t2[0] : t2[1] != a && t2[1] != b ? t2[1] : t2[2];
  if (c == d) return false;
  const Vec3 &pa = net_.pos[a], &pb = net_.pos[b], &pc = net_.pos[c], &pd = net_.pos[d];
  if (angleAt(pc, pa, pb) + angleAt(pd, pa, pb) <= std::numbers::pi + 1e-6) return false;  // Delaunay already
  net_.edgeTriangles(c, d, scratch_);
  if (!scratch_.empty()) return false;
  const Vec3 n1 = net_.normal(edgeTris[0]), n2 = net_.normal(edgeTris[1]);
  const Vec3 n = (1 / std::sqrt(dot(n1, n1))) * n1 + (1 / std::sqrt(dot(n2, n2))) * n2;
  const std::uint32_t pairOf = net_.pair[edgeTris[0]];
  net_.begin(change_);
  net_.removeTriangle(edgeTris[0], change_);
  net_.removeTriangle(edgeTris[1], change_);
  net_.addTriangle(a, d, c, pairOf, change_);
  net_.addTriangle(d, b, c, pairOf, change_);
  before_.assign(2, n);
  touched_.assign({a, b, c, d});
  return settle(touched_);
}

bool Remesher::relaxTo(std::uint32_t v, const Vec3& target) {
  around_ = net_.vtris[v];
  const std::vector<std::uint32_t>& around = around_;
  net_.begin(change_);
  before_.clear();
  for (std::uint32_t t : around) before_.push_back(net_.normal(t));
  net_.move(v, storable(target), change_);
  for (std::uint32_t t : around) {
    const auto c = net_.tris[t];
    net_.removeTriangle(t, change_);
    net_.addTriangle(c[0], c[1], c[2], net_.pair[t], change_);
  }
  return settle({});  // the same triangles: only the geometry can fail
}

// Tangential relaxation: toward the centroid of the neighbours along the sheet (curve and plane
// vertices: of their two neighbours along the line), then onto the smoothed surface.
bool Remesher::relax(std::uint32_t v) {
  const VertexRole r = net_.role[v];
  if (r == VertexRole::Corner || net_.vtris[v].empty()) return false;
  net_.neighbours(v, scratch_);
  std::vector<std::uint32_t>& along = along_;
  std::vector<std::uint32_t>& edgeTris = edgeTris_;
  along.clear();
  FeatureKey key = sheetKey(net_.pair[net_.vtris[v][0]]);
  for (std::uint32_t w : scratch_) {
    if (r == VertexRole::Sheet) {
      along.push_back(w);
      continue;
    }
    net_.edgeTriangles(v, w, edgeTris);
    if (r == VertexRole::Curve && net_.isJunctionEdge(edgeTris)) along.push_back(w), key = curveKey(net_, edgeTris);
    if (r == VertexRole::Plane && net_.isInPlaneEdge(v, w))
      along.push_back(w), key = planeKey(net_.plane[v], net_.pair[edgeTris[0]]);
  }
  if (along.empty()) return false;
  Vec3 centroid{0, 0, 0};
  for (std::uint32_t w : along) centroid = centroid + net_.pos[w];
  const Vec3 p = net_.pos[v];
  Vec3 step = (1.0 / static_cast<double>(along.size())) * centroid - p;
  if (r == VertexRole::Sheet) {
    const Vec3 n = fanNormal(v);
    const double nn = dot(n, n);
    if (nn > 0) step = step - (dot(step, n) / nn) * n;
  }
  if (dot(step, step) < 1e-4 * length_ * length_) return false;  // settled: a hundredth of L
  for (double s : {1.0, 0.5}) {
    const Nearest q = reference_.nearestNear(p + s * step, key, length_);
    if (q.found && relaxTo(v, q.point)) return true;
  }
  return false;
}

// Chords cut inside convex parts and outside concave ones, so a mesh with its vertices on the
// smoothed surface encloses less volume than it (0.7 % against 0.37 % on a 10 mm sphere of
// 1 mm triangles). A sheet vertex moves along its normal by the mean gap between its triangles
// (centroid and edge midpoints) and the smoothed surface, which leaves the remeshed surface
// centred on the smoothed one instead of inscribed.
bool Remesher::fit(std::uint32_t v) {
  if (net_.role[v] != VertexRole::Sheet || net_.vtris[v].empty()) return false;
  Vec3 n = fanNormal(v);
  const double nn = std::sqrt(dot(n, n));
  if (nn == 0) return false;
  n = (1 / nn) * n;
  const FeatureKey key = sheetKey(net_.pair[net_.vtris[v][0]]);
  double gap = 0;
  int samples = 0;
  const auto sample = [&](const Vec3& q, const Nearest& r) {
    if (!r.found) return false;
    gap += dot(r.point - q, n);
    ++samples;
    return true;
  };
  // Each edge from v is a side of two triangles of the fan: its midpoint is looked up once.
  fitted_.clear();
  const auto nearestAt = [&](std::uint32_t a, std::uint32_t b, const Vec3& q) {
    const Edge e{std::min(a, b), std::max(a, b)};
    for (const auto& [edge, r] : fitted_)
      if (edge == e) return r;
    const Nearest r = reference_.nearestNear(q, key, length_);
    fitted_.push_back({e, r});
    return r;
  };
  for (std::uint32_t t : net_.vtris[v]) {
    const auto& c = net_.tris[t];
    const Vec3 centroid = (1.0 / 3) * (net_.pos[c[0]] + net_.pos[c[1]] + net_.pos[c[2]]);
    if (!sample(centroid, reference_.nearestNear(centroid, key, length_))) return false;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = c[e], b = c[(e + 1) % 3];
      const Vec3 mid = 0.5 * (net_.pos[a] + net_.pos[b]);
      if (!sample(mid, nearestAt(a, b, mid))) return false;
    }
  }
  // Over-relaxed: the corners on contour planes and junction curves stay on the smoothed
  // surface, so the vertices between them must make up for them.
  gap *= kFitRelaxation / samples;
  if (std::abs(gap) < 1e-3 * voxel_) return false;
  return relaxTo(v, net_.pos[v] + gap * n);
}

void Remesher::fitAll() {
  for (std::uint32_t v = 0; v < net_.vertexCount(); ++v) fit(v);
}

// ---------------------------------------------------------------- rounds

void Remesher::round(bool graded, bool settledOnly) {
  settledOnly_ = settledOnly;
  if (graded) gradeSizes();
  std::vector<Edge> edges;
  liveEdges(edges);
  for (const auto& [a, b] : edges)
    if (length(a, b) > kHigh * target(a, b) && split(a, b)) ++splits;
  liveEdges(edges);
  for (const auto& [a, b] : edges) {
    if (net_.vtris[a].empty() || net_.vtris[b].empty() || length(a, b) >= kLow * target(a, b)) continue;
    net_.edgeTriangles(a, b, scratch_);
    if (scratch_.empty()) continue;
    if (collapse(a, b) || collapse(b, a)) ++collapses;
  }
  net_.compact();
  liveEdges(edges);
  for (const auto& [a, b] : edges) {
    net_.edgeTriangles(a, b, scratch_);
    if (scratch_.size() == 2 && flip(a, b)) ++flips;
  }
  relaxAll();
  net_.compact();
}

// Feature edges that the first round could not shorten away (a contour's own points a fraction
// of a pixel apart, kept by the cross-section bound) leave thin triangles between them and the
// next row. Around each, the target length drops to kFeatureGrade times the edge and grows
// back to L by kGradeSlope per unit of distance along the mesh (a graded sizing field, as in
// Botsch & Kobbelt's adaptive variant), so the triangles there get small rather than thin.
// Where the surface curves too tightly for L (curvatureSize), the target drops the same way:
// otherwise the distance bound refuses the operations that would even the triangles out there.
void Remesher::gradeSizes() {
  const std::uint32_t n = net_.vertexCount();
  size_.assign(n, length_);
  const auto graded = [&](std::uint32_t v) { return !settledOnly_ || settled(v); };
  std::vector<std::uint32_t> edgeTris;
  for (std::uint32_t v = 0; v < n; ++v) {
    // A rim vertex's edges to outside the submesh are missing: it would look like a junction.
    if (net_.role[v] == VertexRole::Sheet || net_.vtris[v].empty() || flagged(rim_, v) || !graded(v)) continue;
    net_.neighbours(v, scratch_);
    for (std::uint32_t w : scratch_) {
      net_.edgeTriangles(v, w, edgeTris);
      if (net_.isFeatureEdge(v, w, edgeTris))
        size_[v] = std::min(size_[v], std::max(kFeatureGrade * length(v, w), 0.05 * length_));
    }
  }
  if (sagitta_ > 0)
    for (std::uint32_t v = 0; v < n; ++v)
      if (net_.role[v] == VertexRole::Sheet && !net_.vtris[v].empty() && graded(v))
        size_[v] = std::min(size_[v], curvatureSize(v));
  // Dijkstra from every shortened vertex: size(w) <= size(v) + slope |vw|.
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (std::uint32_t v = 0; v < n; ++v)
    if (size_[v] < length_) queue.push({size_[v], v});
  std::vector<std::uint32_t> nb;
  while (!queue.empty()) {
    const auto [h, v] = queue.top();
    queue.pop();
    if (h > size_[v]) continue;
    net_.neighbours(v, nb);
    for (std::uint32_t w : nb) {
      const double g = h + kGradeSlope * length(v, w);
      if (g < size_[w] && graded(w)) size_[w] = g, queue.push({g, w});
    }
  }
}

// The longest chord that stays within the sagitta tolerance where the surface curves most at v:
// a chord h of a circle of radius r lies h^2 / 8r inside it at its middle. The normal
// curvature toward a neighbour w is that of the circle tangent at v through w,
// 2 |n.(w - v)| / |w - v|^2; short edges are skipped, their few hundredths of a millimetre of
// height being mostly the smoothed surface's noise.
double Remesher::curvatureSize(std::uint32_t v) {
  Vec3 n = fanNormal(v);
  const double nn = std::sqrt(dot(n, n));
  if (nn == 0) return length_;
  n = (1 / nn) * n;
  net_.neighbours(v, scratch_);
  const double shortest = kShortestCurvatureEdge * length_;
  double kappa = 0;
  for (std::uint32_t w : scratch_) {
    const Vec3 d = net_.pos[w] - net_.pos[v];
    const double dd = dot(d, d);
    if (dd > shortest * shortest) kappa = std::max(kappa, 2 * std::abs(dot(n, d)) / dd);
  }
  return kappa > 0 ? std::max(std::sqrt(8 * sagitta_ / kappa), kLeastCurvatureSize * length_) : length_;
}

void Remesher::run(int iterations, bool remeshedBefore) {
  // A band's first round grades what the chunks remeshed only: the cut's own triangles, pinned
  // until now, are the smoothed mesh's and get one ungraded round, as everything did in the
  // chunks (their short edges would otherwise keep them dense).
  for (int i = 0; i < iterations; ++i) round(/*graded=*/i > 0 || remeshedBefore, /*settledOnly=*/remeshedBefore && i == 0);
  for (int i = 0; i < kFitPasses; ++i) fitAll();
}

UnitResult Remesher::result(const SubMesh& sub) const {
  UnitResult r;
  r.positions = net_.pos;
  const auto original = static_cast<std::uint32_t>(sub.globalVertex.size());
  for (std::uint32_t t = 0; t < net_.tris.size(); ++t) {
    if (!net_.alive[t]) continue;
    const auto& c = net_.tris[t];
    if (c[0] < original && c[1] < original && c[2] < original && pinned(c[0]) && pinned(c[1]) && pinned(c[2])) {
      std::array<std::uint32_t, 4> key = {c[0], c[1], c[2], net_.pair[t]};
      std::sort(key.begin(), key.begin() + 3);
      if (std::binary_search(sub.fixed.begin(), sub.fixed.end(), key)) continue;  // the whole mesh keeps it
    }
    r.triangles.push_back(c);
    r.pairs.push_back(net_.pair[t]);
  }
  return r;
}

void Remesher::relaxAll() {
  for (std::uint32_t v = 0; v < net_.vertexCount(); ++v)
    if (relax(v)) ++moves;
}

// Largest distance of any vertex, edge midpoint or centroid from the smoothed sheet of its
// triangle's label pair.
double largestDistance(const MultiLabelMesh& mesh, const ReferenceSurface& reference, double length, int threads) {
  const std::size_t n = mesh.triangleCount();
  std::vector<double> worst(static_cast<std::size_t>(chunkCount(n, threads)), 0);
  parallelChunks(n, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    const auto at = [&](std::size_t t, int c) {
      const std::uint32_t v = mesh.triangles[3 * t + static_cast<std::size_t>(c)];
      return Vec3{mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
    };
    for (std::size_t t = begin; t < end; ++t) {
      const Vec3 p0 = at(t, 0), p1 = at(t, 1), p2 = at(t, 2);
      const Vec3 samples[7] = {p0, p1, p2, 0.5 * (p0 + p1), 0.5 * (p1 + p2), 0.5 * (p2 + p0), (1.0 / 3) * (p0 + p1 + p2)};
      const FeatureKey key = sheetKey(labelPairKey(mesh.labels[2 * t], mesh.labels[2 * t + 1]));
      for (const Vec3& q : samples) {
        const Nearest r = reference.nearestNear(q, key, length);
        worst[static_cast<std::size_t>(chunk)] = std::max(worst[static_cast<std::size_t>(chunk)], r.found ? r.distance : length);
      }
    }
  });
  return *std::max_element(worst.begin(), worst.end());
}

void addCounts(RemeshReport& into, const RemeshReport& from) {
  into.splits += from.splits, into.collapses += from.collapses, into.flips += from.flips;
  into.moves += from.moves, into.rejected += from.rejected;
}

// One phase of chunk units, at most `threads` at once; merged in unit order.
void runPhase(MultiLabelMesh& mesh, const std::vector<WorkUnit>& units, bool remeshedBefore, std::vector<char>& settled,
              const Context& context, int threads, RemeshReport& report) {
  const std::vector<std::uint32_t> valence = vertexValence(mesh);
  std::vector<SubMesh> subs(units.size());
  std::vector<UnitResult> results(units.size());
  std::vector<RemeshReport> counts(units.size());  // summed in unit order below
  // The largest first (longest processing time first), so no thread is left with a big one at
  // the end; the order of work never changes the result.
  std::vector<std::size_t> order(units.size());
  for (std::size_t u = 0; u < order.size(); ++u) order[u] = u;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return units[a].triangles > units[b].triangles; });
  std::atomic<std::size_t> next{0};
  parallelChunks(units.size(), threads, [&](int, std::size_t, std::size_t) {
    for (std::size_t i = next++; i < order.size(); i = next++) {
      const std::size_t u = order[i];
      subs[u] = extractUnit(mesh, valence, settled, units[u]);
      Remesher remesher(Network(subs[u].mesh, context.planes, context.sliceTolerance, context.length), context, units[u],
                        &subs[u]);
      subs[u].mesh = {};
      remesher.run(context.iterations, remeshedBefore);
      results[u] = remesher.result(subs[u]);
      counts[u] = remesher.counts();
    }
  });
  mergeUnits(mesh, subs, results, settled);
  for (const RemeshReport& c : counts) addCounts(report, c);
}

}  // namespace

AngleFigures computeAngleFigures(std::span<const float> positions, std::span<const std::uint32_t> triangles, int threads) {
  std::vector<double> smallest(triangles.size() / 3);
  const auto at = [&](std::uint32_t v) { return Vec3{positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]}; };
  parallelChunks(smallest.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      const Vec3 p[3] = {at(triangles[3 * t]), at(triangles[3 * t + 1]), at(triangles[3 * t + 2])};
      // The smallest angle lies opposite the shortest edge (law of sines): one arc cosine.
      int c = 0;
      double shortest = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        const Vec3 e = p[(k + 2) % 3] - p[(k + 1) % 3];
        if (dot(e, e) < shortest) shortest = dot(e, e), c = k;
      }
      smallest[t] = angleAt(p[c], p[(c + 1) % 3], p[(c + 2) % 3]) * 180 / std::numbers::pi;
    }
  });
  AngleFigures f;
  if (smallest.empty()) return f;
  double sum = 0;
  for (double a : smallest) sum += a;
  f.mean = sum / static_cast<double>(smallest.size());
  f.min = *std::min_element(smallest.begin(), smallest.end());
  // The 5th percentile: a selection, not a sort (a clinical set's millions of triangles).
  std::nth_element(smallest.begin(), smallest.begin() + static_cast<std::ptrdiff_t>(smallest.size() / 20), smallest.end());
  f.p5 = smallest[smallest.size() / 20];
  return f;
}

void accumulate(RemeshReport& into, const RemeshReport& layer) {
  if (!layer.ran) return;
  if (!into.ran) {
    into = layer;
    return;
  }
  const auto merge = [](AngleFigures& a, std::size_t na, const AngleFigures& b, std::size_t nb) {
    a.min = std::min(a.min, b.min);
    a.p5 = std::min(a.p5, b.p5);
    a.mean = na + nb ? (a.mean * static_cast<double>(na) + b.mean * static_cast<double>(nb)) / static_cast<double>(na + nb) : 0;
  };
  merge(into.anglesBefore, into.trianglesBefore, layer.anglesBefore, layer.trianglesBefore);
  merge(into.anglesAfter, into.trianglesAfter, layer.anglesAfter, layer.trianglesAfter);
  into.trianglesBefore += layer.trianglesBefore;
  into.trianglesAfter += layer.trianglesAfter;
  into.maxDistance = std::max(into.maxDistance, layer.maxDistance);
  into.chunks += layer.chunks, into.bands += layer.bands;
  addCounts(into, layer);
}

RemeshReport remeshMesh(MultiLabelMesh& mesh, const Grid& grid, const ContourSet* contours, const Nesting& nesting,
                        const RemeshOptions& options, int threads, std::size_t trianglesPerChunk) {
  const double sliceTolerance = grid.planeTolerance;
  RemeshReport report;
  if (!options.enabled || mesh.triangleCount() == 0) return report;
  report.ran = true;
  report.trianglesBefore = mesh.triangleCount();
  report.anglesBefore = computeAngleFigures(mesh.positions, mesh.triangles, threads);
  std::vector<double> planes = contours ? contourPlanes(*contours, sliceTolerance) : std::vector<double>{};
  report.edgeLength = targetLength(options, grid, planes);
  const SurfaceTable surfaces(mesh, nesting);
  const ChunkPlan plan = planChunks(mesh, report.edgeLength, trianglesPerChunk);
  const bool whole = plan.phases[0].size() == 1 && plan.phases[0][0].whole();
  report.chunks = plan.phases[0].size(), report.bands = plan.phases[1].size();
  Network network(mesh, planes, sliceTolerance, report.edgeLength, /*broadPhase=*/whole);
  const ReferenceSurface reference(network, report.edgeLength, threads);
  const double voxel = std::min(grid.spacingX, grid.spacingY);
  const double sagitta = options.curvatureSizing ? kCurvatureSagitta * voxel : 0;
  const Context context{std::move(planes), sliceTolerance,     report.edgeLength, voxel,
                        sagitta,           options.iterations, surfaces,          reference};
  if (whole) {
    Remesher remesher(std::move(network), context, WorkUnit{}, nullptr);
    remesher.run(options.iterations);
    remesher.storeInto(mesh);
    addCounts(report, remesher.counts());
  } else {
    { const Network freed = std::move(network); }
    std::vector<char> settled;  // per vertex: remeshed by a chunk
    runPhase(mesh, plan.phases[0], /*remeshedBefore=*/false, settled, context, threads, report);
    runPhase(mesh, plan.phases[1], /*remeshedBefore=*/true, settled, context, threads, report);
    compactVertices(mesh);
    mesh.keys.clear();
  }
  report.maxDistance = largestDistance(mesh, reference, report.edgeLength, threads);
  report.trianglesAfter = mesh.triangleCount();
  report.anglesAfter = computeAngleFigures(mesh.positions, mesh.triangles, threads);
  return report;
}

}  // namespace scansurf
