// scansurf: small topology tools shared by the mesh statistics and simplification's patch checks.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

namespace scansurf {

// Disjoint sets over 0 .. n-1 (path halving; the smaller index is each set's root).
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::uint32_t{0}); }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

// True when the triangles around v (given as the opposite edges of v's link) form one fan: the
// link is connected (a cycle inside the surface, a path on its border).
bool singleFan(std::span<const std::array<std::uint32_t, 2>> link, std::vector<std::uint32_t>& scratch);

}  // namespace scansurf
