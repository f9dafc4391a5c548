// scansurf: which changed triangles of a mesh cross another (simplification's last check).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace scansurf {

// Pairs {a, b} of triangles (3 indices each into xyz positions) that cross (exact test,
// trianglesCross: shared vertices and edges are allowed to meet where they must), for every
// triangle a with query[a] and every b near it, each pair once; a pair is tested only if one
// of the two is new (isNew: pairs of old triangles are known not to cross), degenerate old
// ones are skipped. Candidates come from a uniform grid of `cell` (input units). The same
// pairs, in the same order, for any thread count (0: all).
std::vector<std::array<std::uint32_t, 2>> crossingPairs(std::span<const float> positions,
                                                        std::span<const std::uint32_t> triangles, const std::vector<char>& query,
                                                        const std::vector<char>& isNew, double cell, int threads = 0);

}  // namespace scansurf
