// The smoothed surface as remeshing's projection target (Botsch & Kobbelt, "A remeshing
// approach to multiresolution modeling", 2004, project every relaxed vertex back onto the
// input). Nearest points by Ericson's closest-point-on-triangle ("Real-Time Collision
// Detection", 2005, 5.1.5).
#include "geometry/remesh/remesh_reference.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/parallel.h"

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

namespace {

// Squared distance from p to the box [lo, hi]. The box is the primitive's widened to floats,
// so the distance is no larger than to its exact box (rounding included: every step is
// monotonic): a primitive it rejects lies farther than the limit.
double boxDistance2(const Vec3& p, const std::array<float, 3>& lo, const std::array<float, 3>& hi) {
  double d = 0;
  for (int k = 0; k < 3; ++k) {
    const double e = std::max({static_cast<double>(lo[k]) - p[k], 0.0, p[k] - static_cast<double>(hi[k])});
    d += e * e;
  }
  return d;
}

float floatBelow(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

float floatAbove(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

}  // namespace

ReferenceSurface::ReferenceSurface(const Network& net, double cell, int threads) : cell_(cell), points_(net.pos) {
  addPrimitives(net, threads);
  bucket(threads);
}

// The sheets' live triangles in order, then the junction and in-plane edges by their lower
// vertex (each chunk of vertices makes its part, joined in order: the same ids for any
// thread count).
void ReferenceSurface::addPrimitives(const Network& net, int threads) {
  const auto make = [](const FeatureKey& key, std::array<std::uint32_t, 3> corners, int count) {
    return Primitive{key.value, corners, static_cast<std::uint8_t>(count), key.kind};
  };
  primitives_.reserve(net.tris.size());
  for (std::uint32_t t = 0; t < net.tris.size(); ++t)
    if (net.alive[t]) primitives_.push_back(make(sheetKey(net.pair[t]), net.tris[t], 3));
  std::vector<std::vector<Primitive>> edges(static_cast<std::size_t>(chunkCount(net.vertexCount(), threads)));
  parallelChunks(net.vertexCount(), threads, [&](int chunk, std::size_t begin, std::size_t end) {
    std::vector<Primitive>& part = edges[static_cast<std::size_t>(chunk)];
    std::vector<std::uint32_t> nb, et;
    for (auto v = static_cast<std::uint32_t>(begin); v < end; ++v) {
      net.neighbours(v, nb);
      for (std::uint32_t w : nb) {
        if (w < v) continue;
        net.edgeTriangles(v, w, et);
        if (net.isJunctionEdge(et))
          part.push_back(make(curveKey(net, et), {v, w, 0}, 2));
        else if (net.isInPlaneEdge(v, w))
          part.push_back(make(planeKey(net.plane[v], net.pair[et[0]]), {v, w, 0}, 2));
      }
    }
  });
  for (const std::vector<Primitive>& part : edges) primitives_.insert(primitives_.end(), part.begin(), part.end());
}

void ReferenceSurface::boxOf(const Primitive& q, Vec3& lo, Vec3& hi) const {
  lo = hi = points_[q.corners[0]];
  for (int i = 1; i < q.count; ++i)
    for (int k = 0; k < 3; ++k) {
      const double c = points_[q.corners[static_cast<std::size_t>(i)]][k];
      lo[k] = std::min(lo[k], c), hi[k] = std::max(hi[k], c);
    }
}

std::uint64_t ReferenceSurface::cellKey(std::int64_t x, std::int64_t y, std::int64_t z, const FeatureKey& key) const {
  constexpr std::int64_t kBias = 1 << 20;
  std::uint64_t h = static_cast<std::uint64_t>(x + kBias) | (static_cast<std::uint64_t>(y + kBias) << 21) |
                    (static_cast<std::uint64_t>(z + kBias) << 42);
  h ^= (key.value + static_cast<std::uint64_t>(key.kind) * 0x9e3779b97f4a7c15ull) * 0xff51afd7ed558ccdull;
  return h;
}

template <typename F>
void ReferenceSurface::forCells(const Vec3& lo, const Vec3& hi, const FeatureKey& key, F f) const {
  std::int64_t a[3], b[3];
  for (int k = 0; k < 3; ++k) a[k] = std::llround(std::floor(lo[k] / cell_)), b[k] = std::llround(std::floor(hi[k] / cell_));
  for (std::int64_t z = a[2]; z <= b[2]; ++z)
    for (std::int64_t y = a[1]; y <= b[1]; ++y)
      for (std::int64_t x = a[0]; x <= b[0]; ++x) f(cellKey(x, y, z, key));
}

// Every (cell, primitive) pair, sorted by cell then primitive (chunks sorted at once, then
// merged), becomes the runs; then each run's key goes into the table.
void ReferenceSurface::bucket(int threads) {
  using Entry = std::pair<std::uint64_t, std::uint32_t>;
  const int chunks = chunkCount(primitives_.size(), threads);
  std::vector<std::vector<Entry>> parts(static_cast<std::size_t>(chunks));
  parallelChunks(primitives_.size(), threads, [&](int chunk, std::size_t begin, std::size_t end) {
    std::vector<Entry>& part = parts[static_cast<std::size_t>(chunk)];
    Vec3 lo, hi;
    for (std::size_t id = begin; id < end; ++id) {
      const Primitive& q = primitives_[id];
      boxOf(q, lo, hi);
      forCells(lo, hi, {q.keyKind, q.keyValue}, [&](std::uint64_t key) {
        part.push_back({key, static_cast<std::uint32_t>(id)});
      });
    }
    std::sort(part.begin(), part.end());
  });
  std::vector<Entry> entries;
  for (const std::vector<Entry>& part : parts) {
    const auto middle = static_cast<std::ptrdiff_t>(entries.size());
    entries.insert(entries.end(), part.begin(), part.end());
    std::inplace_merge(entries.begin(), entries.begin() + middle, entries.end());
  }
  parts.clear();
  CellTable& table = cells_;
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (i == 0 || entries[i].first != entries[i - 1].first) table.starts.push_back(static_cast<std::uint32_t>(i));
  table.entries.resize(entries.size());
  parallelChunks(entries.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    Vec3 lo, hi;
    for (std::size_t i = begin; i < end; ++i) {
      boxOf(primitives_[entries[i].second], lo, hi);
      CellEntry& e = table.entries[i];
      for (int k = 0; k < 3; ++k) e.lo[k] = floatBelow(lo[k]), e.hi[k] = floatAbove(hi[k]);
      e.primitive = entries[i].second;
    }
  });
  const std::size_t runs = table.starts.size();
  table.starts.push_back(static_cast<std::uint32_t>(entries.size()));
  const std::size_t size = std::bit_ceil(std::max<std::size_t>(1024, 2 * runs));  // at most half full
  table.keys.assign(size, CellTable::kEmpty);
  table.runs.assign(size, 0);
  table.shift = 64 - std::countr_zero(size);
  for (std::size_t r = 0; r < runs; ++r) {
    const std::uint64_t key = entries[table.starts[r]].first;
    std::size_t s = table.slotOf(key);
    while (table.keys[s] != CellTable::kEmpty) s = (s + 1) & (size - 1);
    table.keys[s] = key, table.runs[s] = static_cast<std::uint32_t>(r);
  }
}

std::span<const ReferenceSurface::CellEntry> ReferenceSurface::CellTable::find(std::uint64_t key) const {
  for (std::size_t s = slotOf(key);; s = (s + 1) & (keys.size() - 1)) {
    if (keys[s] == key) return {entries.data() + starts[runs[s]], entries.data() + starts[runs[s] + 1]};
    if (keys[s] == kEmpty) return {};
  }
}

template <typename F>
void ReferenceSurface::visit(const Vec3& p, const FeatureKey& key, double radius, const double& limit2, F f) const {
  const Vec3 r{radius, radius, radius};
  bool going = true;
  forCells(p - r, p + r, key, [&](std::uint64_t cell) {
    if (!going) return;
    for (const CellEntry& e : cells_.find(cell)) {
      if (boxDistance2(p, e.lo, e.hi) > limit2) continue;
      const Primitive& q = primitives_[e.primitive];
      if (!q.is(key)) continue;  // a hash collision
      if (!f(q)) {
        going = false;
        return;
      }
    }
  });
}

Vec3 ReferenceSurface::nearestOn(const Primitive& q, const Vec3& p) const {
  const Vec3 &a = points_[q.corners[0]], &b = points_[q.corners[1]];
  return q.count == 3 ? nearestOnTriangle(p, a, b, points_[q.corners[2]]) : nearestOnSegment(p, a, b);
}

Nearest ReferenceSurface::nearest(const Vec3& p, const FeatureKey& key, double radius) const {
  Nearest best;
  double best2 = radius * radius;
  visit(p, key, radius, best2, [&](const Primitive& q) {
    const Vec3 n = nearestOn(q, p);
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
  visit(p, key, radius, r2, [&](const Primitive& q) {
    const Vec3 n = nearestOn(q, p);
    found = dot(n - p, n - p) <= r2;
    return !found;
  });
  return found;
}

}  // namespace scansurf::remesh
