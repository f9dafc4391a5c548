// scansurf: quadric-error half-edge collapses (see edge_collapse.h). Garland & Heckbert's
// quadrics, unweighted: a vertex's quadric sums the squared distances to the planes of every
// triangle merged into it, so a cost of at most d^2 keeps it within d of each of those planes.
// Half-edge collapses (onto an existing vertex, as meshoptimizer's) keep every vertex where
// smoothing put it: a triangle never leaves the slab its vertices span. Candidates sit in one
// heap with version stamps; a stale entry is skipped when it comes up.
#include "geometry/edge_collapse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>

#include "geometry/vec3.h"

namespace scansurf {
namespace {

constexpr double kLeastTurnCosine = 0.5;  // a collapse may turn a triangle by at most 60 degrees

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
  double worst = -1;
  for (int k = 0; k < 3; ++k) {
    const Vec3 u = e[k], w = -e[(k + 2) % 3];  // the two edges leaving corner k
    const double l = glm::length(u) * glm::length(w);
    if (l == 0) return 1;
    worst = std::max(worst, glm::dot(u, w) / l);
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
    leastCosine_ = std::cos(limits.minAngle * std::numbers::pi / 180);
    maxCost_ = limits.maxDistance * limits.maxDistance;
  }

  std::vector<std::uint32_t> run() {
    for (std::uint32_t v = 0; v < pos_.size(); ++v) pushAround(v);
    while (!heap_.empty()) {
      const Candidate c = heap_.top();
      heap_.pop();
      if (version_[c.from] != c.fromVersion || version_[c.to] != c.toVersion || !canCollapse(c.from, c.to)) continue;
      collapse(c.from, c.to);
      pushAround(c.to);
    }
    std::vector<std::uint32_t> out;
    for (std::size_t t = 0; t < tris_.size(); ++t)
      if (alive_[t]) out.insert(out.end(), tris_[t].begin(), tris_[t].end());
    return out;
  }

 private:
  // v's neighbours, sorted, into `out`.
  void neighbours(std::uint32_t v, std::vector<std::uint32_t>& out) const {
    out.clear();
    for (std::uint32_t t : vtris_[v])
      for (std::uint32_t w : tris_[t])
        if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  void push(std::uint32_t from, std::uint32_t to) {
    if (locked_[from]) return;
    Quadric q = quadric_[from];
    q += quadric_[to];
    const double cost = std::max(0.0, q.at(pos_[to]));
    if (cost <= maxCost_) heap_.push({cost, from, to, version_[from], version_[to]});
  }

  // Candidates on every edge at v, both ways.
  void pushAround(std::uint32_t v) {
    neighbours(v, around_);
    for (std::uint32_t w : around_) push(v, w), push(w, v);
  }

  bool contains(std::uint32_t t, std::uint32_t v) const { return tris_[t][0] == v || tris_[t][1] == v || tris_[t][2] == v; }

  // The link condition: u and v share exactly the two vertices opposite their edge.
  bool keepsManifold(std::uint32_t v, std::uint32_t u, const std::vector<std::uint32_t>& nv,
                     const std::vector<std::uint32_t>& nu) const {
    int shared = 0;
    for (std::uint32_t t : vtris_[v]) shared += contains(t, u);
    if (shared != 2) return false;
    std::size_t common = 0;
    for (std::uint32_t w : nv) common += std::binary_search(nu.begin(), nu.end(), w);
    return common == 2;
  }

  // Whether triangle t (of v, not holding u) may have v replaced by u.
  bool keepsTriangle(std::uint32_t t, std::uint32_t v, std::uint32_t u, const std::vector<std::uint32_t>& nu,
                     double worstBefore) const {
    std::array<Vec3, 3> before, after;
    int onPlane = 0;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t w = tris_[t][c];
      before[c] = pos_[w], after[c] = pos_[w == v ? u : w];
      if (w == v) continue;
      if (glm::length(pos_[w] - pos_[u]) > limits_.maxEdge && !std::binary_search(nu.begin(), nu.end(), w)) return false;
      if (plane_[u] >= 0 && plane_[w] == plane_[u] && (++onPlane == 2 || !std::binary_search(nu.begin(), nu.end(), w)))
        return false;
    }
    const Vec3 n0 = normalOf(before[0], before[1], before[2]), n1 = normalOf(after[0], after[1], after[2]);
    const double l0 = glm::length(n0), l1 = glm::length(n1);
    if (l1 <= 1e-12 * (l0 + 1e-300) || glm::dot(n0, n1) < kLeastTurnCosine * l0 * l1) return false;
    for (int c = 0; c < 3; ++c)  // and faces the side the smoothed surface faced at each corner
      if (glm::dot(n1, normal_[tris_[t][c] == v ? u : tris_[t][c]]) <= 0) return false;
    return sharpestCosine(after[0], after[1], after[2]) <= std::max(leastCosine_, worstBefore);
  }

  bool canCollapse(std::uint32_t v, std::uint32_t u) {
    if (vtris_[v].empty() || vtris_[u].empty()) return false;
    neighbours(v, nv_), neighbours(u, nu_);
    if (!keepsManifold(v, u, nv_, nu_)) return false;
    double worstBefore = -1;  // the sharpest corner among v's triangles
    for (std::uint32_t t : vtris_[v]) worstBefore = std::max(worstBefore, cosine_[t]);
    for (std::uint32_t t : vtris_[v])
      if (!contains(t, u) && !keepsTriangle(t, v, u, nu_, worstBefore)) return false;
    return true;
  }

  void collapse(std::uint32_t v, std::uint32_t u) {
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
  std::vector<std::vector<std::uint32_t>> vtris_;
  std::vector<Quadric> quadric_;
  std::vector<std::uint32_t> version_;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> heap_;
};

}  // namespace

std::vector<std::uint32_t> collapseEdges(std::span<const float> positions, std::span<const std::uint32_t> triangles,
                                         std::span<const char> locked, std::span<const int> plane, const CollapseLimits& limits) {
  return Collapser(positions, triangles, locked, plane, limits).run();
}

}  // namespace scansurf
