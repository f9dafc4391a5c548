// scansurf: the broad phase is a uniform grid hashed into buckets (a bucket shared by two cells
// only adds candidates, which the bounding-box test drops); the narrow phase is the exact test.
#include "geometry/crossing_search.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/parallel.h"
#include "geometry/triangle_intersection.h"

namespace scansurf {
namespace {

struct Box {
  Vec3 lo, hi;
};

Point3 pointAt(std::span<const float> p, std::uint32_t v) {
  return {p[3 * std::size_t{v}], p[3 * std::size_t{v} + 1], p[3 * std::size_t{v} + 2]};
}

std::array<Point3, 3> cornersOf(std::span<const float> p, std::span<const std::uint32_t> tris, std::size_t t) {
  return {pointAt(p, tris[3 * t]), pointAt(p, tris[3 * t + 1]), pointAt(p, tris[3 * t + 2])};
}

Box boxOf(const std::array<Point3, 3>& c) { return {glm::min(glm::min(c[0], c[1]), c[2]), glm::max(glm::max(c[0], c[1]), c[2])}; }

bool overlap(const Box& a, const Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// Triangles by the buckets of the cells their boxes touch (offsets into one list).
class BucketGrid {
 public:
  BucketGrid(const std::vector<Box>& boxes, double cell) : cell_(cell) {
    origin_ = boxes.empty() ? Vec3{0, 0, 0} : boxes.front().lo;
    for (const Box& b : boxes) origin_ = glm::min(origin_, b.lo);
    const std::size_t buckets = std::bit_ceil(std::max<std::size_t>(2 * boxes.size(), 64));
    shift_ = 64 - std::countr_zero(buckets);
    start_.assign(buckets + 1, 0);
    for (const Box& b : boxes) forBuckets(b, [&](std::size_t s) { ++start_[s + 1]; });
    for (std::size_t s = 0; s < buckets; ++s) start_[s + 1] += start_[s];
    list_.resize(start_.back());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t t = 0; t < boxes.size(); ++t) forBuckets(boxes[t], [&](std::size_t s) { list_[fill[s]++] = t; });
  }

  // Calls f(triangle) for every triangle in a bucket of a cell the box touches (with repeats).
  template <typename F>
  void forCandidates(const Box& b, F f) const {
    forBuckets(b, [&](std::size_t s) {
      for (std::uint32_t i = start_[s]; i < start_[s + 1]; ++i) f(list_[i]);
    });
  }

 private:
  template <typename F>
  void forBuckets(const Box& b, F f) const {
    const auto lo = cellOf(b.lo), hi = cellOf(b.hi);
    for (std::uint64_t z = lo[2]; z <= hi[2]; ++z)
      for (std::uint64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::uint64_t x = lo[0]; x <= hi[0]; ++x) {
          const std::uint64_t key = x | y << 21 | z << 42;
          f(static_cast<std::size_t>((key * 0x9e3779b97f4a7c15ull) >> shift_));
        }
  }
  std::array<std::uint64_t, 3> cellOf(const Vec3& p) const {
    std::array<std::uint64_t, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = static_cast<std::uint64_t>(std::floor((p[k] - origin_[k]) / cell_)) & 0x1fffff;
    return c;
  }

  double cell_;
  Vec3 origin_{0, 0, 0};
  int shift_ = 58;
  std::vector<std::uint32_t> start_, list_;
};

}  // namespace

std::vector<std::array<std::uint32_t, 2>> crossingPairs(std::span<const float> positions,
                                                        std::span<const std::uint32_t> triangles, const std::vector<char>& query,
                                                        const std::vector<char>& isNew, double cell, int threads) {
  const std::size_t count = triangles.size() / 3;
  std::vector<Box> boxes(count);
  std::vector<char> skipped(count, 0);  // old and degenerate: no crossing to find (once each, not per query)
  parallelChunks(count, threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      const std::array<Point3, 3> p = cornersOf(positions, triangles, t);
      boxes[t] = boxOf(p);
      skipped[t] = !isNew[t] && isDegenerate(p);
    }
  });
  const BucketGrid grid(boxes, cell);
  std::vector<std::uint32_t> queries;
  for (std::uint32_t t = 0; t < count; ++t)
    if (query[t]) queries.push_back(t);
  if (queries.empty()) return {};
  std::vector<std::vector<std::array<std::uint32_t, 2>>> found(static_cast<std::size_t>(chunkCount(queries.size(), threads)));
  parallelChunks(queries.size(), threads, [&](int chunk, std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> candidates;
    for (std::size_t q = begin; q < end; ++q) {
      const std::uint32_t a = queries[q];
      candidates.clear();
      grid.forCandidates(boxes[a], [&](std::uint32_t b) {
        if (b != a && !(query[b] && b < a) && (isNew[a] || isNew[b]) && overlap(boxes[a], boxes[b])) candidates.push_back(b);
      });
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      const std::array<Point3, 3> pa = cornersOf(positions, triangles, a);
      const std::array<std::uint32_t, 3> ia{triangles[3 * a], triangles[3 * a + 1], triangles[3 * a + 2]};
      for (std::uint32_t b : candidates) {
        if (skipped[b]) continue;
        const std::array<Point3, 3> pb = cornersOf(positions, triangles, b);
        if (trianglesCross(ia, pa, {triangles[3 * b], triangles[3 * b + 1], triangles[3 * b + 2]}, pb))
          found[static_cast<std::size_t>(chunk)].push_back({a, b});
      }
    }
  });
  std::vector<std::array<std::uint32_t, 2>> pairs;
  for (const auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  return pairs;
}

}  // namespace scansurf
