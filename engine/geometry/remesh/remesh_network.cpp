// The editable triangle network of remeshing (see remesh_network.h) and its topology check:
// an edit keeps every feature surface a closed oriented 2-manifold of the same genus when, at
// every vertex it touched, each surface's triangles still form one consistently oriented fan
// and no triangle is repeated (an edge collapse that breaks the link condition of Dey,
// Edelsbrunner et al., "Topology preserving edge contraction", 1999, always leaves an edge
// with four triangles or a repeated triangle at a touched vertex).
#include "geometry/remesh/remesh_network.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace scansurf::remesh {

// ---------------------------------------------------------------- feature surfaces

SurfaceTable::SurfaceTable(const MultiLabelMesh& mesh, const Nesting& nesting) {
  const int featureCount = static_cast<int>(nesting.parent.size());
  const auto featureOf = [&](Label l) {
    const int f = featureOfLabel(l);
    return f >= 0 && f < featureCount ? f : -1;
  };
  // Enclosing: the features whose set holds g (g and every feature g lies inside), ascending.
  const auto containers = [&](int g) {
    std::vector<int> out;
    if (g < 0) return out;
    for (int f = 0; f < featureCount; ++f)
      if (f == g || isInside(nesting, g, f)) out.push_back(f);
    return out;
  };
  for (std::size_t t = 0; t < mesh.labels.size() / 2; ++t) {
    const std::uint32_t key = labelPairKey(mesh.labels[2 * t], mesh.labels[2 * t + 1]);
    if (uses_.count(key)) continue;
    std::vector<SurfaceUse>& uses = uses_[key];
    const int fa = featureOf(mesh.labels[2 * t]), fb = featureOf(mesh.labels[2 * t + 1]);
    // Partition surfaces are numbered featureCount + f, enclosing ones f.
    if (fa >= 0) uses.push_back({featureCount + fa, false});
    if (fb >= 0) uses.push_back({featureCount + fb, true});
    const std::vector<int> inA = containers(fa), inB = containers(fb);
    for (int f : inA)
      if (!std::binary_search(inB.begin(), inB.end(), f)) uses.push_back({f, false});
    for (int f : inB)
      if (!std::binary_search(inA.begin(), inA.end(), f)) uses.push_back({f, true});
  }
}

const std::vector<SurfaceUse>& SurfaceTable::usesOf(std::uint32_t pair) const {
  static const std::vector<SurfaceUse> kNone;
  const auto it = uses_.find(pair);
  return it == uses_.end() ? kNone : it->second;
}

// ---------------------------------------------------------------- broad phase

template <typename F>
void TriangleGrid::forCells(const Vec3& lo, const Vec3& hi, F f) const {
  std::int64_t a[3], b[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = static_cast<std::int64_t>(std::floor(lo[k] / cell_));
    b[k] = static_cast<std::int64_t>(std::floor(hi[k] / cell_));
  }
  const auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    constexpr std::int64_t kBias = 1 << 20;
    return static_cast<std::uint64_t>(x + kBias) | (static_cast<std::uint64_t>(y + kBias) << 21) |
           (static_cast<std::uint64_t>(z + kBias) << 42);
  };
  for (std::int64_t z = a[2]; z <= b[2]; ++z)
    for (std::int64_t y = a[1]; y <= b[1]; ++y)
      for (std::int64_t x = a[0]; x <= b[0]; ++x) f(key(x, y, z));
}

void TriangleGrid::clear() {
  keys_.clear();
  lists_.clear();
  cells_.clear();
  shift_ = 64;
}

std::vector<std::uint32_t>* TriangleGrid::find(std::uint64_t key) {
  if (keys_.empty()) return nullptr;
  for (std::size_t s = slotOf(key);; s = (s + 1) & (keys_.size() - 1)) {
    if (keys_[s] == key) return &cells_[lists_[s]];
    if (keys_[s] == kEmpty) return nullptr;
  }
}

std::vector<std::uint32_t>& TriangleGrid::findOrAdd(std::uint64_t key) {
  if (2 * (cells_.size() + 1) > keys_.size()) {  // at most half full: short probes
    const std::vector<std::uint64_t> oldKeys = std::move(keys_);
    const std::vector<std::uint32_t> oldLists = std::move(lists_);
    const std::size_t size = std::max<std::size_t>(1024, 2 * oldKeys.size());
    keys_.assign(size, kEmpty);
    lists_.assign(size, 0);
    shift_ = 64 - std::countr_zero(size);
    for (std::size_t s = 0; s < oldKeys.size(); ++s) {
      if (oldKeys[s] == kEmpty) continue;
      std::size_t t = slotOf(oldKeys[s]);
      while (keys_[t] != kEmpty) t = (t + 1) & (size - 1);
      keys_[t] = oldKeys[s], lists_[t] = oldLists[s];
    }
  }
  std::size_t s = slotOf(key);
  for (; keys_[s] != kEmpty; s = (s + 1) & (keys_.size() - 1))
    if (keys_[s] == key) return cells_[lists_[s]];
  keys_[s] = key;
  lists_[s] = static_cast<std::uint32_t>(cells_.size());
  return cells_.emplace_back();
}

void TriangleGrid::insert(std::uint32_t t, const Vec3& lo, const Vec3& hi) {
  forCells(lo, hi, [&](std::uint64_t key) { findOrAdd(key).push_back(t); });
}

void TriangleGrid::query(const Vec3& lo, const Vec3& hi, const std::vector<char>& alive,
                         const std::vector<std::uint32_t>& pending, std::vector<std::uint32_t>& out) {
  out.clear();
  ++round_;
  forCells(lo, hi, [&](std::uint64_t key) {
    std::vector<std::uint32_t>* list = find(key);
    if (!list) return;
    std::size_t kept = 0;
    for (std::uint32_t t : *list) {
      if (!alive[t]) {
        if (std::find(pending.begin(), pending.end(), t) != pending.end()) (*list)[kept++] = t;
        continue;
      }
      (*list)[kept++] = t;
      if (t >= stamp_.size()) stamp_.resize(std::max<std::size_t>(t + 1, 2 * stamp_.size()), 0);  // amortized
      if (stamp_[t] == round_) continue;
      stamp_[t] = round_;
      out.push_back(t);
    }
    list->resize(kept);
  });
}

// ---------------------------------------------------------------- the network

Network::Network(const MultiLabelMesh& mesh, const std::vector<double>& planeZ, double sliceTolerance, double cell,
                 bool broadPhase)
    : grid(cell) {
  const std::size_t vertexCount = mesh.vertexCount(), triangleCount = mesh.triangleCount();
  pos.resize(vertexCount);
  plane.assign(vertexCount, -1);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    pos[v] = {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
    const auto it = std::lower_bound(planeZ.begin(), planeZ.end(), pos[v][2] - sliceTolerance);
    if (it != planeZ.end() && std::abs(*it - pos[v][2]) <= sliceTolerance) plane[v] = static_cast<int>(it - planeZ.begin());
  }
  tris.resize(triangleCount);
  pair.resize(triangleCount);
  alive.assign(triangleCount, 1);
  vtris.resize(vertexCount);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    for (int c = 0; c < 3; ++c) {
      tris[t][c] = mesh.triangles[3 * t + c];
      vtris[tris[t][c]].push_back(static_cast<std::uint32_t>(t));
    }
    pair[t] = labelPairKey(mesh.labels[2 * t], mesh.labels[2 * t + 1]);
  }
  assignRoles();
  if (!broadPhase) return;
  for (std::size_t t = 0; t < triangleCount; ++t) insertIntoGrid(static_cast<std::uint32_t>(t));
}

namespace {

// (neighbour, label pair) for each triangle around v and each of its other two vertices.
using Spokes = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Junction and in-plane edges around v, from one sorted pass over its fan: the edge to a
// neighbour w has the triangles listing w, and is a junction edge unless they are two of one
// label pair (Network::isJunctionEdge).
void countFeatureEdges(const Network& net, std::uint32_t v, int& junction, int& inPlane, Spokes& spokes) {
  junction = inPlane = 0;
  spokes.clear();
  for (std::uint32_t t : net.vtris[v])
    for (std::uint32_t w : net.tris[t])
      if (w != v) spokes.push_back({w, net.pair[t]});
  std::sort(spokes.begin(), spokes.end());
  for (std::size_t i = 0; i < spokes.size();) {
    std::size_t end = i + 1;
    while (end < spokes.size() && spokes[end].first == spokes[i].first) ++end;
    junction += end - i != 2 || spokes[i].second != spokes[i + 1].second;
    inPlane += net.isInPlaneEdge(v, spokes[i].first);
    i = end;
  }
}

}  // namespace

void Network::assignRoles() {
  const std::size_t n = pos.size();
  role.assign(n, VertexRole::Corner);
  junctions.assign(n, 0);
  inPlane.assign(n, 0);
  Spokes spokes;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (vtris[v].empty()) continue;
    int jc = 0, pc = 0;
    countFeatureEdges(*this, v, jc, pc, spokes);
    junctions[v] = static_cast<std::uint8_t>(std::min(jc, 255));
    inPlane[v] = static_cast<std::uint8_t>(std::min(pc, 255));
    if (plane[v] >= 0)
      role[v] = jc == 0 && pc == 2 ? VertexRole::Plane : VertexRole::Corner;
    else
      role[v] = jc == 0 ? VertexRole::Sheet : jc == 2 ? VertexRole::Curve : VertexRole::Corner;
  }
}

void Network::pin(std::uint32_t v) {
  Spokes spokes;
  int jc = 0, pc = 0;
  countFeatureEdges(*this, v, jc, pc, spokes);
  role[v] = VertexRole::Corner;
  junctions[v] = static_cast<std::uint8_t>(std::min(jc, 255));
  inPlane[v] = static_cast<std::uint8_t>(std::min(pc, 255));
}

void Network::edgeTriangles(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out) const {
  out.clear();
  for (std::uint32_t t : vtris[a]) {
    const auto& c = tris[t];
    if (c[0] == b || c[1] == b || c[2] == b) out.push_back(t);
  }
}

bool Network::isJunctionEdge(const std::vector<std::uint32_t>& edgeTris) const {
  return edgeTris.size() != 2 || pair[edgeTris[0]] != pair[edgeTris[1]];
}

void Network::neighbours(std::uint32_t v, std::vector<std::uint32_t>& out) const {
  out.clear();
  for (std::uint32_t t : vtris[v])
    for (std::uint32_t w : tris[t])
      if (w != v) out.push_back(w);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

Vec3 Network::normal(std::uint32_t t) const {
  const auto& c = tris[t];
  return cross(pos[c[1]] - pos[c[0]], pos[c[2]] - pos[c[0]]);
}

void Network::begin(Change& change) const {
  change.removed.clear();
  change.moved.clear();
  change.firstAdded = static_cast<std::uint32_t>(tris.size());
  change.addedVertex = false;
}

std::uint32_t Network::addVertex(const Vec3& p, VertexRole r, int planeIndex, Change& change) {
  pos.push_back(p);
  vtris.emplace_back();
  role.push_back(r);
  plane.push_back(planeIndex);
  junctions.push_back(r == VertexRole::Curve ? 2 : 0);
  inPlane.push_back(r == VertexRole::Plane ? 2 : 0);
  change.addedVertex = true;
  return static_cast<std::uint32_t>(pos.size() - 1);
}

namespace {
void eraseOne(std::vector<std::uint32_t>& v, std::uint32_t x) {
  const auto it = std::find(v.begin(), v.end(), x);
  if (it != v.end()) v.erase(it);  // keeps the order: the result must not depend on undo history
}
}  // namespace

void Network::removeTriangle(std::uint32_t t, Change& change) {
  alive[t] = 0;
  for (std::uint32_t v : tris[t]) eraseOne(vtris[v], t);
  change.removed.push_back(t);
}

std::uint32_t Network::addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t pairOf, Change&) {
  const auto t = static_cast<std::uint32_t>(tris.size());
  tris.push_back({a, b, c});
  pair.push_back(pairOf);
  alive.push_back(1);
  for (std::uint32_t v : tris[t]) vtris[v].push_back(t);
  return t;
}

void Network::move(std::uint32_t v, const Vec3& p, Change& change) {
  change.moved.push_back({v, pos[v]});
  pos[v] = p;
}

void Network::undo(Change& change) {
  while (tris.size() > change.firstAdded) {
    const auto t = static_cast<std::uint32_t>(tris.size() - 1);
    for (std::uint32_t v : tris[t]) eraseOne(vtris[v], t);
    tris.pop_back();
    pair.pop_back();
    alive.pop_back();
  }
  for (auto it = change.removed.rbegin(); it != change.removed.rend(); ++it) {
    alive[*it] = 1;
    for (std::uint32_t v : tris[*it]) {
      // Back where it was: triangle lists stay sorted by id, so neighbour order never
      // depends on which operations were tried.
      auto& list = vtris[v];
      list.insert(std::lower_bound(list.begin(), list.end(), *it), *it);
    }
  }
  for (auto it = change.moved.rbegin(); it != change.moved.rend(); ++it) pos[it->first] = it->second;
  if (change.addedVertex) {
    pos.pop_back();
    vtris.pop_back();
    role.pop_back();
    plane.pop_back();
    junctions.pop_back();
    inPlane.pop_back();
  }
  begin(change);
}

void Network::commit(const Change& change) {
  for (auto t = change.firstAdded; t < tris.size(); ++t)
    if (alive[t]) insertIntoGrid(t);
}

void Network::insertIntoGrid(std::uint32_t t) {
  Vec3 lo = pos[tris[t][0]], hi = lo;
  for (int c = 1; c < 3; ++c)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], pos[tris[t][c]][k]), hi[k] = std::max(hi[k], pos[tris[t][c]][k]);
  grid.insert(t, lo, hi);
}

void Network::compact() {
  std::size_t out = 0;
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (alive[t]) {
      tris[out] = tris[t];
      pair[out] = pair[t];
      ++out;
    }
  tris.resize(out);
  pair.resize(out);
  alive.assign(out, 1);
  for (auto& list : vtris) list.clear();
  for (std::uint32_t t = 0; t < out; ++t)
    for (std::uint32_t v : tris[t]) vtris[v].push_back(t);
  grid.clear();
  for (std::uint32_t t = 0; t < out; ++t) insertIntoGrid(t);
}

void Network::storeInto(MultiLabelMesh& mesh) const {
  std::vector<std::uint32_t> remap(pos.size(), UINT32_MAX);
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (alive[t])
      for (std::uint32_t v : tris[t]) remap[v] = 0;
  mesh.positions.clear();
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < pos.size(); ++v)
    if (remap[v] == 0) {
      remap[v] = next++;
      for (int k = 0; k < 3; ++k) mesh.positions.push_back(static_cast<float>(pos[v][k]));
    }
  mesh.triangles.clear();
  mesh.labels.clear();
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (!alive[t]) continue;
    for (std::uint32_t v : tris[t]) mesh.triangles.push_back(remap[v]);
    mesh.labels.push_back(static_cast<Label>(pair[t] & 0xffff));
    mesh.labels.push_back(static_cast<Label>(pair[t] >> 16));
  }
  mesh.keys.clear();  // the lattice keys described the assembled vertices only
}

// ---------------------------------------------------------------- topology check

namespace {

struct LinkEdge {
  int surface;
  std::uint32_t from, to;
  bool operator<(const LinkEdge& o) const { return surface != o.surface ? surface < o.surface : from < o.from; }
};

// One oriented cycle per surface: each link vertex starts exactly one edge and the walk from
// the first closes after visiting them all.
bool singleOrientedFans(std::vector<LinkEdge>& link) {
  std::sort(link.begin(), link.end());
  for (std::size_t i = 0; i < link.size();) {
    std::size_t e = i;
    while (e < link.size() && link[e].surface == link[i].surface) ++e;
    for (std::size_t k = i + 1; k < e; ++k)
      if (link[k].from == link[k - 1].from) return false;
    std::uint32_t at = link[i].to;
    std::size_t steps = 1;
    while (at != link[i].from) {
      const auto it = std::lower_bound(link.begin() + static_cast<std::ptrdiff_t>(i),
                                       link.begin() + static_cast<std::ptrdiff_t>(e), LinkEdge{link[i].surface, at, 0});
      if (it == link.begin() + static_cast<std::ptrdiff_t>(e) || it->from != at || ++steps > e - i) return false;
      at = it->to;
    }
    if (steps != e - i) return false;
    i = e;
  }
  return true;
}

bool roleHolds(const Network& net, std::uint32_t v, Spokes& spokes) {
  int jc = 0, pc = 0;
  countFeatureEdges(net, v, jc, pc, spokes);
  switch (net.role[v]) {
    case VertexRole::Sheet: return jc == 0 && pc == 0;
    case VertexRole::Curve: return jc == 2 && pc == 0;
    case VertexRole::Plane: return jc == 0 && pc == 2;
    case VertexRole::Corner: return jc == net.junctions[v] && pc == net.inPlane[v];
  }
  return false;
}

}  // namespace

bool topologyHolds(const Network& net, const SurfaceTable& surfaces, const std::vector<std::uint32_t>& vertices) {
  // Reused by every check on this thread (chunks run one remesher per thread): a check costs
  // a few microseconds, and its allocations were a good part of it.
  thread_local Spokes spokes;
  thread_local std::vector<std::array<std::uint32_t, 3>> sorted;
  thread_local std::vector<LinkEdge> link;
  for (std::uint32_t v : vertices) {
    if (net.vtris[v].empty()) continue;
    if (!roleHolds(net, v, spokes)) return false;
    sorted.clear();
    link.clear();
    for (std::uint32_t t : net.vtris[v]) {
      auto c = net.tris[t];
      const int at = c[0] == v ? 0 : c[1] == v ? 1 : 2;
      const std::uint32_t a = c[(at + 1) % 3], b = c[(at + 2) % 3];
      for (const SurfaceUse& u : surfaces.usesOf(net.pair[t])) link.push_back({u.surface, u.flip ? b : a, u.flip ? a : b});
      std::sort(c.begin(), c.end());
      sorted.push_back(c);
    }
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
    if (!singleOrientedFans(link)) return false;
  }
  return true;
}

}  // namespace scansurf::remesh
