// scansurf: the broad phase is a uniform grid hashed into buckets (a bucket shared by two cells
// only adds candidates, which the bounding-box test drops); the narrow phase is the exact test.
#include "geometry/mesh/crossing_search.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/parallel.h"
#include "geometry/mesh/triangle_intersection.h"

namespace scansurf {
namespace {

// Positions are floats, so their bounds are exactly floats too: half the memory of doubles.
struct Box {
  glm::vec3 lo, hi;
};

Point3 pointAt(std::span<const float> p, std::uint32_t v) {
  return {p[3 * std::size_t{v}], p[3 * std::size_t{v} + 1], p[3 * std::size_t{v} + 2]};
}

std::array<Point3, 3> cornersOf(std::span<const float> p, std::span<const std::uint32_t> tris, std::size_t t) {
  return {pointAt(p, tris[3 * t]), pointAt(p, tris[3 * t + 1]), pointAt(p, tris[3 * t + 2])};
}

Box boxOf(const std::array<Point3, 3>& c) {
  return {glm::vec3(glm::min(glm::min(c[0], c[1]), c[2])), glm::vec3(glm::max(glm::max(c[0], c[1]), c[2]))};
}

bool overlap(const Box& a, const Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// Triangles by the buckets of the cells their boxes touch (offsets into one list).
class BucketGrid {
 public:
  BucketGrid(const std::vector<Box>& boxes, double cell) : cell_(cell) {
    origin_ = boxes.empty() ? Vec3{0, 0, 0} : Vec3(boxes.front().lo);
    for (const Box& b : boxes) origin_ = glm::min(origin_, Vec3(b.lo));
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
  std::array<std::uint64_t, 3> cellOf(const glm::vec3& p) const {
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
  bool newQuery = false;
  for (std::size_t t = 0; t < count; ++t) newQuery = newQuery || (query[t] && isNew[t]);
  // A pair is tested only if one of the two is new: with old queries alone, only new triangles
  // can be their partners (simplification's later rounds, where a few patches were put back).
  // The triangles that can take part, in order: everything below is indexed by their rank.
  std::vector<std::uint32_t> members, queries;
  for (std::uint32_t t = 0; t < count; ++t)
    if (newQuery || isNew[t] || query[t]) {
      if (query[t]) queries.push_back(static_cast<std::uint32_t>(members.size()));
      members.push_back(t);
    }
  if (queries.empty()) return {};
  // Each member's corners side by side, since the narrow phase reads them for every candidate,
  // its box and its flags; old degenerate ones are skipped (no crossing to find).
  constexpr std::uint8_t kNew = 1, kQuery = 2, kSkipped = 4;
  std::vector<float> corners(9 * members.size());
  std::vector<Box> boxes(members.size());
  std::vector<std::uint8_t> flags(members.size());
  parallelChunks(members.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t m = begin; m < end; ++m) {
      const std::uint32_t t = members[m];
      const std::array<Point3, 3> p = cornersOf(positions, triangles, t);
      for (std::size_t c = 0; c < 3; ++c)
        std::copy_n(&positions[3 * std::size_t{triangles[3 * t + c]}], 3, &corners[9 * m + 3 * c]);
      boxes[m] = boxOf(p);
      flags[m] = static_cast<std::uint8_t>((isNew[t] ? kNew : 0) | (query[t] ? kQuery : 0) |
                                           (!isNew[t] && isDegenerate(p) ? kSkipped : 0));
    }
  });
  const auto cornersAt = [&](std::uint32_t m) -> std::array<Point3, 3> {
    const float* c = &corners[9 * std::size_t{m}];
    return {Point3{c[0], c[1], c[2]}, Point3{c[3], c[4], c[5]}, Point3{c[6], c[7], c[8]}};
  };
  const auto idsOf = [&](std::uint32_t m) -> std::array<std::uint32_t, 3> {
    const std::size_t t = members[m];
    return {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
  };
  const BucketGrid grid(boxes, cell);
  std::vector<std::vector<std::array<std::uint32_t, 2>>> found(static_cast<std::size_t>(chunkCount(queries.size(), threads)));
  parallelChunks(queries.size(), threads, [&](int chunk, std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> candidates;
    for (std::size_t q = begin; q < end; ++q) {
      const std::uint32_t a = queries[q];  // ranks order as the triangles do
      candidates.clear();
      grid.forCandidates(boxes[a], [&](std::uint32_t b) {
        if (b != a && !((flags[b] & kQuery) && b < a) && ((flags[a] | flags[b]) & kNew) && overlap(boxes[a], boxes[b]))
          candidates.push_back(b);
      });
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      const std::array<Point3, 3> pa = cornersAt(a);
      const std::array<std::uint32_t, 3> ia = idsOf(a);
      for (std::uint32_t b : candidates)
        if (!(flags[b] & kSkipped) && trianglesCross(ia, pa, idsOf(b), cornersAt(b)))
          found[static_cast<std::size_t>(chunk)].push_back({members[a], members[b]});
    }
  });
  std::vector<std::array<std::uint32_t, 2>> pairs;
  for (const auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  return pairs;
}

}  // namespace scansurf
