// scansurf: quadric-error half-edge collapses (see edge_collapse.h). Garland & Heckbert's
// quadrics, unweighted: a vertex's quadric sums the squared distances to the planes of every
// triangle merged into it, so a cost of at most d^2 keeps it within d of each of those planes.
// Half-edge collapses (onto an existing vertex, as meshoptimizer's) keep every vertex where
// smoothing put it: a triangle never leaves the tier its vertices span. Candidates sit in one
// heap with version stamps; a stale entry is skipped when it comes up. An edge no longer than
// the bound collapses at no cost (its ends may have merged many planes, whose summed squared
// distances would refuse it): that is what removes most needle slivers. After the collapses,
// edge flips (Lawson's, restricted): a flip that blunts the pair's sharpest corner, keeps the
// surface within the bound and turns nothing; then collapses again, which the flips open up.
#include "geometry/simplification/edge_collapse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>

#include "geometry/mesh/vec3.h"

namespace scansurf {
namespace {

constexpr double kLeastTurnCosine = 0.5;  // a collapse or flip may turn a triangle by at most 60 degrees
constexpr int kFlipPasses = 4;            // passes of edge flips after the collapses (later ones flip few)
constexpr int kRounds = 2;                // collapses then flips, twice: flips open collapses refused before

// A symmetric 4x4 quadric, upper triangle: xx xy xz xw yy yz yw zz zw ww.
struct Quadric {
  std::array<double, 10> q{};
  void addPlane(const Vec3& n, double d) {
    const double p[4] = {n.x, n.y, n.z, d};
    int k = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) q[k++] += p[i] * p[j];
  }
  Quadric& operator+=(const Quadric& o) {
    for (int k = 0; k < 10; ++k) q[k] += o.q[k];
    return *this;
  }
  double at(const Vec3& v) const {
    const double x = v.x, y = v.y, z = v.z;
    return q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + 2 * q[3] * x + q[4] * y * y + 2 * q[5] * y * z + 2 * q[6] * y +
           q[7] * z * z + 2 * q[8] * z + q[9];
  }
};

struct Candidate {
  double cost;
  std::uint32_t from, to, fromVersion, toVersion;
  bool operator>(const Candidate& o) const {
    return cost != o.cost ? cost > o.cost : (from != o.from ? from > o.from : to > o.to);
  }
};

Vec3 normalOf(const Vec3& a, const Vec3& b, const Vec3& c) { return glm::cross(b - a, c - a); }

// The largest cosine of a triangle's corners (its smallest angle's); 1 when degenerate.
double sharpestCosine(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e[3] = {b - a, c - b, a - c};
  const double length[3] = {glm::length(e[0]), glm::length(e[1]), glm::length(e[2])};
  double worst = -1;
  for (int k = 0; k < 3; ++k) {
    const double l = length[k] * length[(k + 2) % 3];  // the two edges leaving corner k
    if (l == 0) return 1;
    worst = std::max(worst, glm::dot(e[k], -e[(k + 2) % 3]) / l);
  }
  return worst;
}

class Collapser {
 public:
  Collapser(std::span<const float> positions, std::span<const std::uint32_t> triangles, std::span<const char> locked,
            std::span<const int> plane, const CollapseLimits& limits)
      : locked_(locked), plane_(plane), limits_(limits) {
    for (std::size_t v = 0; v < positions.size() / 3; ++v)
      pos_.push_back({positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]});
    vtris_.resize(pos_.size()), quadric_.resize(pos_.size()), version_.assign(pos_.size(), 0);
    normal_.assign(pos_.size(), Vec3{0, 0, 0});
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
      const std::array<std::uint32_t, 3> tri{triangles[t], triangles[t + 1], triangles[t + 2]};
      tris_.push_back(tri), alive_.push_back(1);
      cosine_.push_back(sharpestCosine(pos_[tri[0]], pos_[tri[1]], pos_[tri[2]]));
      const Vec3 n = normalOf(pos_[tri[0]], pos_[tri[1]], pos_[tri[2]]);
      const double length = glm::length(n);
      for (std::uint32_t v : tri) {
        vtris_[v].push_back(static_cast<std::uint32_t>(tris_.size() - 1));
        normal_[v] += n;
        if (length > 0) quadric_[v].addPlane(n / length, -glm::dot(n / length, pos_[tri[0]]));
      }
    }
    starChangedAt_.assign(pos_.size(), 0), refusedAt_.assign(tris_.size(), 0), mark_.assign(pos_.size(), 0);
    leastCosine_ = std::cos(limits.minAngle * std::numbers::pi / 180);
    maxCost_ = limits.maxDistance * limits.maxDistance;
  }

  std::vector<std::uint32_t> run() {
    // Every edge both ways, once each: v -> w here, w -> v in w's turn.
    for (std::uint32_t v = 0; v < pos_.size(); ++v) {
      neighbours(v, around_);
      for (std::uint32_t w : around_) push(v, w);
    }
    for (int round = 0; round < kRounds; ++round) {
      collapseQueued();
      for (int pass = 0; pass < kFlipPasses && flipPass() > 0; ++pass) {
      }
      for (std::uint32_t v : flipped_)  // the second round: around the flips only
        if (!vtris_[v].empty()) pushAround(v);
      flipped_.clear();
    }
    std::vector<std::uint32_t> out;
    for (std::size_t t = 0; t < tris_.size(); ++t)
      if (alive_[t]) out.insert(out.end(), tris_[t].begin(), tris_[t].end());
    return out;
  }

 private:
  // The queued candidates, cheapest first, until none is left within the bound.
  void collapseQueued() {
    while (!heap_.empty()) {
      const Candidate c = heap_.top();
      heap_.pop();
      if (version_[c.from] != c.fromVersion || version_[c.to] != c.toVersion || !canCollapse(c.from, c.to)) continue;
      collapse(c.from, c.to);
      pushAround(c.to);
    }
  }

  // One pass of edge flips over every triangle's edges, in order; returns how many were made.
  // A triangle whose edges were all refused before, and whose corners' stars have not changed
  // since, is refused again (tryFlip reads nothing else that changes): it is skipped.
  std::size_t flipPass() {
    std::size_t flips = 0;
    for (std::uint32_t t = 0; t < tris_.size(); ++t) {
      if (!alive_[t] || refusedSinceChange(t)) continue;
      bool flipped = false;
      for (int c = 0; c < 3 && !flipped; ++c) flipped = tryFlip(t, tris_[t][c], tris_[t][(c + 1) % 3]);
      if (flipped)
        ++flips;
      else
        refusedAt_[t] = ++clock_;
    }
    return flips;
  }

  bool refusedSinceChange(std::uint32_t t) const {
    const std::uint32_t refused = refusedAt_[t];
    return refused > 0 &&
           std::all_of(tris_[t].begin(), tris_[t].end(), [&](std::uint32_t v) { return starChangedAt_[v] < refused; });
  }
  void starChanged(std::uint32_t v) { starChangedAt_[v] = ++clock_; }

  // The other live triangle on edge a-b (a -> b in t), or ~0u when there is none or several.
  std::uint32_t across(std::uint32_t t, std::uint32_t a, std::uint32_t b) const {
    std::uint32_t found = ~0u;
    for (std::uint32_t u : vtris_[a])
      if (u != t && contains(u, b)) {
        if (found != ~0u) return ~0u;
        found = u;
      }
    return found;
  }

  std::uint32_t opposite(std::uint32_t t, std::uint32_t a, std::uint32_t b) const {
    for (std::uint32_t w : tris_[t])
      if (w != a && w != b) return w;
    return a;
  }

  // Flips edge a-b of t (t = a, b, c; its neighbour b, a, d) to c-d when that sharpens no
  // corner: the pair's sharpest corner gets blunter, the surface moves within the distance
  // bound, no triangle turns, and no edge is added along a contour plane or twice.
  bool tryFlip(std::uint32_t t, std::uint32_t a, std::uint32_t b) {
    if (plane_[a] >= 0 && plane_[a] == plane_[b]) return false;  // a piece of a cross-section
    const std::uint32_t u = across(t, a, b);
    if (u == ~0u) return false;
    const std::uint32_t c = opposite(t, a, b), d = opposite(u, a, b);
    if (c == d || (plane_[c] >= 0 && plane_[c] == plane_[d])) return false;
    for (std::uint32_t w : {a, b, c, d})
      if (locked_[w] == kFrozen) return false;
    for (std::uint32_t w : vtris_[c])
      if (contains(w, d)) return false;  // c and d are joined already
    const Vec3 &pa = pos_[a], &pb = pos_[b], &pc = pos_[c], &pd = pos_[d];
    const double before = std::max(cosine_[t], cosine_[u]);
    const double after = std::max(sharpestCosine(pa, pd, pc), sharpestCosine(pd, pb, pc));
    if (after >= before - 1e-9) return false;
    const Vec3 n1 = normalOf(pa, pd, pc), n2 = normalOf(pd, pb, pc), m1 = normalOf(pa, pb, pc), m2 = normalOf(pb, pa, pd);
    const double l1 = glm::length(n1), l2 = glm::length(n2), k1 = glm::length(m1), k2 = glm::length(m2);
    if (l1 == 0 || l2 == 0 || k1 == 0 || k2 == 0) return false;
    for (const Vec3& n : {n1 / l1, n2 / l2})
      for (const Vec3& m : {m1 / k1, m2 / k2})
        if (glm::dot(n, m) < kLeastTurnCosine) return false;
    if (std::abs(glm::dot(pd - pa, m1 / k1)) > limits_.maxDistance) return false;  // the tetrahedron a b c d is flat
    for (std::uint32_t w : {a, d, c})
      if (glm::dot(n1, normal_[w]) <= 0) return false;
    for (std::uint32_t w : {d, b, c})
      if (glm::dot(n2, normal_[w]) <= 0) return false;
    flip(t, u, a, b, c, d);
    return true;
  }

  // t = a, b, c and u = b, a, d become a, d, c and d, b, c.
  void flip(std::uint32_t t, std::uint32_t u, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    for (std::uint32_t w : {a, b, c, d}) starChanged(w);
    tris_[t] = {a, d, c}, tris_[u] = {d, b, c};
    std::erase(vtris_[a], u), std::erase(vtris_[b], t);
    vtris_[d].push_back(t), vtris_[c].push_back(u);
    flipped_.insert(flipped_.end(), {a, b, c, d});
    cosine_[t] = sharpestCosine(pos_[a], pos_[d], pos_[c]), cosine_[u] = sharpestCosine(pos_[d], pos_[b], pos_[c]);
  }

  // v's neighbours, each once, into `out`; until the next call, isMarked(w) says whether w is one.
  void neighbours(std::uint32_t v, std::vector<std::uint32_t>& out) {
    out.clear();
    if (++stamp_ == 0) std::fill(mark_.begin(), mark_.end(), 0), stamp_ = 1;
    for (std::uint32_t t : vtris_[v])
      for (std::uint32_t w : tris_[t])
        if (w != v && mark_[w] != stamp_) mark_[w] = stamp_, out.push_back(w);
  }
  bool isMarked(std::uint32_t w) const { return mark_[w] == stamp_; }

  void push(std::uint32_t from, std::uint32_t to) {
    if (locked_[from]) return;
    Quadric q = quadric_[from];
    q += quadric_[to];
    // An edge no longer than the bound moves the surface by less than that however many planes
    // its ends have merged: it goes first, at no cost.
    const double cost = glm::length(pos_[to] - pos_[from]) <= limits_.maxDistance ? 0.0 : std::max(0.0, q.at(pos_[to]));
    if (cost <= maxCost_) heap_.push({cost, from, to, version_[from], version_[to]});
  }

  // Candidates on every edge at v, both ways.
  void pushAround(std::uint32_t v) {
    neighbours(v, around_);
    for (std::uint32_t w : around_) push(v, w), push(w, v);
  }

  bool contains(std::uint32_t t, std::uint32_t v) const { return tris_[t][0] == v || tris_[t][1] == v || tris_[t][2] == v; }

  // The link condition: u and v share exactly the two vertices opposite their edge. u's
  // neighbours are the ones marked (neighbours(u, ...) was the last call).
  bool keepsManifold(std::uint32_t v, std::uint32_t u, const std::vector<std::uint32_t>& nv) const {
    int shared = 0;
    for (std::uint32_t t : vtris_[v]) shared += contains(t, u);
    if (shared != 2) return false;
    std::size_t common = 0;
    for (std::uint32_t w : nv) common += isMarked(w);
    return common == 2;
  }

  // Whether triangle t (of v, not holding u) keeps its shape with v replaced by u: it turns by
  // at most 60 degrees, faces the side the smoothed surface faced at each corner and gets no
  // sharper than the lesser of the angle limit and v's sharpest corner before.
  bool keepsShape(std::uint32_t t, std::uint32_t v, std::uint32_t u, double worstBefore) const {
    std::array<Vec3, 3> before, after;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t w = tris_[t][c];
      before[c] = pos_[w], after[c] = pos_[w == v ? u : w];
    }
    const Vec3 n0 = normalOf(before[0], before[1], before[2]), n1 = normalOf(after[0], after[1], after[2]);
    const double l0 = glm::length(n0), l1 = glm::length(n1);
    if (l1 <= 1e-12 * (l0 + 1e-300) || glm::dot(n0, n1) < kLeastTurnCosine * l0 * l1) return false;
    for (int c = 0; c < 3; ++c)
      if (glm::dot(n1, normal_[tris_[t][c] == v ? u : tris_[t][c]]) <= 0) return false;
    return sharpestCosine(after[0], after[1], after[2]) <= std::max(leastCosine_, worstBefore);
  }

  // Whether triangle t's new edges (from u to its other corners) are allowed: none longer than
  // the edge bound and none along a contour plane, unless u has that edge already (its
  // neighbours marked).
  bool keepsEdges(std::uint32_t t, std::uint32_t v, std::uint32_t u) const {
    int onPlane = 0;
    for (const std::uint32_t w : tris_[t]) {
      if (w == v) continue;
      if (glm::length(pos_[w] - pos_[u]) > limits_.maxEdge && !isMarked(w)) return false;
      if (plane_[u] >= 0 && plane_[w] == plane_[u] && (++onPlane == 2 || !isMarked(w))) return false;
    }
    return true;
  }

  // The shapes first: most candidates fail there, before their neighbour lists are sorted.
  bool canCollapse(std::uint32_t v, std::uint32_t u) {
    if (vtris_[v].empty() || vtris_[u].empty()) return false;
    double worstBefore = -1;  // the sharpest corner among v's triangles
    for (std::uint32_t t : vtris_[v]) worstBefore = std::max(worstBefore, cosine_[t]);
    for (std::uint32_t t : vtris_[v])
      if (!contains(t, u) && !keepsShape(t, v, u, worstBefore)) return false;
    neighbours(v, nv_), neighbours(u, nu_);  // marks u's neighbours for the two checks below
    if (!keepsManifold(v, u, nv_)) return false;
    for (std::uint32_t t : vtris_[v])
      if (!contains(t, u) && !keepsEdges(t, v, u)) return false;
    return true;
  }

  void collapse(std::uint32_t v, std::uint32_t u) {
    for (std::uint32_t t : vtris_[v])
      for (std::uint32_t w : tris_[t]) starChanged(w);
    for (std::uint32_t t : vtris_[v]) {
      if (contains(t, u)) {
        alive_[t] = 0;
        for (std::uint32_t w : tris_[t])
          if (w != v) std::erase(vtris_[w], t);
      } else {
        for (std::uint32_t& w : tris_[t])
          if (w == v) w = u;
        cosine_[t] = sharpestCosine(pos_[tris_[t][0]], pos_[tris_[t][1]], pos_[tris_[t][2]]);
        vtris_[u].push_back(t);
      }
    }
    vtris_[v].clear();
    quadric_[u] += quadric_[v];
    ++version_[u], ++version_[v];
  }

  std::span<const char> locked_;
  std::span<const int> plane_;
  CollapseLimits limits_;
  double leastCosine_ = 1, maxCost_ = 0;
  std::vector<Vec3> pos_;
  std::vector<Vec3> normal_;  // area-weighted normals of the triangles as given
  std::vector<std::array<std::uint32_t, 3>> tris_;
  std::vector<char> alive_;
  std::vector<double> cosine_;                   // per triangle, its sharpest corner's cosine
  std::vector<std::uint32_t> nv_, nu_, around_;  // scratch neighbour lists
  std::vector<std::uint32_t> mark_;              // per vertex, the stamp of the last list it was in
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> flipped_;  // corners of this round's flips
  std::vector<std::vector<std::uint32_t>> vtris_;
  std::vector<Quadric> quadric_;
  std::vector<std::uint32_t> version_;
  // Event times (clock_ ticks at each): when a vertex's star last changed (a flip or collapse
  // there), when each triangle's edges were last all refused a flip (0: never tried).
  std::uint32_t clock_ = 0;
  std::vector<std::uint32_t> starChangedAt_, refusedAt_;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> heap_;
};

}  // namespace

std::vector<std::uint32_t> collapseEdges(std::span<const float> positions, std::span<const std::uint32_t> triangles,
                                         std::span<const char> locked, std::span<const int> plane, const CollapseLimits& limits) {
  return Collapser(positions, triangles, locked, plane, limits).run();
}

}  // namespace scansurf
