// The smoothed surface as remeshing's projection target (Botsch & Kobbelt, "A remeshing
// approach to multiresolution modeling", 2004, project every relaxed vertex back onto the
// input). Nearest points by Ericson's closest-point-on-triangle ("Real-Time Collision
// Detection", 2005, 5.1.5).
#include "geometry/remesh_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scansurf::remesh {

FeatureKey sheetKey(std::uint32_t pair) { return {FeatureKey::Kind::Sheet, pair}; }

FeatureKey planeKey(int plane, std::uint32_t pair) {
  return {FeatureKey::Kind::Plane, (static_cast<std::uint64_t>(plane) << 32) | pair};
}

FeatureKey curveKey(const Network& net, const std::vector<std::uint32_t>& edgeTris) {
  std::vector<std::uint32_t> labels;
  for (std::uint32_t t : edgeTris) labels.push_back(net.pair[t] & 0xffff), labels.push_back(net.pair[t] >> 16);
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the label set
  for (std::uint32_t l : labels) h = (h ^ l) * 1099511628211ull;
  return {FeatureKey::Kind::Curve, h};
}

Vec3 nearestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len = dot(ab, ab);
  const double t = len > 0 ? std::clamp(dot(p - a, ab) / len, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

Vec3 nearestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1 / (va + vb + vc);
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

ReferenceSurface::ReferenceSurface(const Network& net, double cell) : cell_(cell) {
  std::vector<std::uint32_t> nb, et;
  for (std::uint32_t t = 0; t < net.tris.size(); ++t) {
    if (!net.alive[t]) continue;
    const Vec3 c[3] = {net.pos[net.tris[t][0]], net.pos[net.tris[t][1]], net.pos[net.tris[t][2]]};
    add(sheetKey(net.pair[t]), c, 3);
  }
  for (std::uint32_t v = 0; v < net.vertexCount(); ++v) {
    net.neighbours(v, nb);
    for (std::uint32_t w : nb) {
      if (w < v) continue;
      net.edgeTriangles(v, w, et);
      const Vec3 c[2] = {net.pos[v], net.pos[w]};
      if (net.isJunctionEdge(et))
        add(curveKey(net, et), c, 2);
      else if (net.isInPlaneEdge(v, w))
        add(planeKey(net.plane[v], net.pair[et[0]]), c, 2);
    }
  }
}

std::uint64_t ReferenceSurface::cellKey(std::int64_t x, std::int64_t y, std::int64_t z, const FeatureKey& key) const {
  constexpr std::int64_t kBias = 1 << 20;
  std::uint64_t h = static_cast<std::uint64_t>(x + kBias) | (static_cast<std::uint64_t>(y + kBias) << 21) |
                    (static_cast<std::uint64_t>(z + kBias) << 42);
  h ^= (key.value + static_cast<std::uint64_t>(key.kind) * 0x9e3779b97f4a7c15ull) * 0xff51afd7ed558ccdull;
  return h;
}

void ReferenceSurface::add(const FeatureKey& key, const Vec3* corners, int count) {
  const auto id = static_cast<std::uint32_t>(primitives_.size());
  Vec3 lo = corners[0], hi = corners[0];
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], corners[i][k]), hi[k] = std::max(hi[k], corners[i][k]);
  primitives_.push_back({static_cast<std::uint32_t>(points_.size()), static_cast<std::uint8_t>(count), key, lo, hi});
  points_.insert(points_.end(), corners, corners + count);
  std::int64_t a[3], b[3];
  for (int k = 0; k < 3; ++k) a[k] = std::llround(std::floor(lo[k] / cell_)), b[k] = std::llround(std::floor(hi[k] / cell_));
  for (std::int64_t z = a[2]; z <= b[2]; ++z)
    for (std::int64_t y = a[1]; y <= b[1]; ++y)
      for (std::int64_t x = a[0]; x <= b[0]; ++x) cells_[cellKey(x, y, z, key)].push_back(id);
}

namespace {

// Squared distance from p to the box [lo, hi].
double boxDistance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  double d = 0;
  for (int k = 0; k < 3; ++k) {
    const double e = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
    d += e * e;
  }
  return d;
}

}  // namespace

template <typename F>
void ReferenceSurface::visit(const Vec3& p, const FeatureKey& key, double radius, F f) const {
  std::int64_t a[3], b[3];
  for (int k = 0; k < 3; ++k)
    a[k] = std::llround(std::floor((p[k] - radius) / cell_)), b[k] = std::llround(std::floor((p[k] + radius) / cell_));
  for (std::int64_t z = a[2]; z <= b[2]; ++z)
    for (std::int64_t y = a[1]; y <= b[1]; ++y)
      for (std::int64_t x = a[0]; x <= b[0]; ++x) {
        const auto it = cells_.find(cellKey(x, y, z, key));
        if (it == cells_.end()) continue;
        for (std::uint32_t id : it->second) {
          const Primitive& q = primitives_[id];
          if (q.key.kind != key.kind || q.key.value != key.value) continue;  // a hash collision
          if (!f(q)) return;
        }
      }
}

Nearest ReferenceSurface::nearest(const Vec3& p, const FeatureKey& key, double radius) const {
  Nearest best;
  double best2 = radius * radius;
  visit(p, key, radius, [&](const Primitive& q) {
    if (boxDistance2(p, q.lo, q.hi) > best2) return true;
    const Vec3* c = &points_[q.first];
    const Vec3 n = q.count == 3 ? nearestOnTriangle(p, c[0], c[1], c[2]) : nearestOnSegment(p, c[0], c[1]);
    const double d2 = dot(n - p, n - p);
    // Ties go to the first primitive: deterministic, as the cell order is.
    if (d2 < best2 || (!best.found && d2 <= best2)) best = {true, n, 0}, best2 = d2;
    return true;
  });
  if (best.found) best.distance = std::sqrt(best2);
  return best;
}

Nearest ReferenceSurface::nearestNear(const Vec3& p, const FeatureKey& key, double radius) const {
  const Nearest close = nearest(p, key, 0.1 * radius);
  return close.found ? close : nearest(p, key, radius);
}

bool ReferenceSurface::within(const Vec3& p, const FeatureKey& key, double radius) const {
  bool found = false;
  const double r2 = radius * radius;
  visit(p, key, radius, [&](const Primitive& q) {
    if (boxDistance2(p, q.lo, q.hi) > r2) return true;
    const Vec3* c = &points_[q.first];
    const Vec3 n = q.count == 3 ? nearestOnTriangle(p, c[0], c[1], c[2]) : nearestOnSegment(p, c[0], c[1]);
    found = dot(n - p, n - p) <= r2;
    return !found;
  });
  return found;
}

}  // namespace scansurf::remesh
