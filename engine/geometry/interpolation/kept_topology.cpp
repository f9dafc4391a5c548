// scansurf: the homotopic deformation from the slab rule to the interpolated labels (see
// kept_topology.h). The simple-point test reads the voxel's 14 neighbours once, as a bit mask,
// and floods the mask along their precomputed links.
#include "geometry/interpolation/kept_topology.h"

#include <array>
#include <bit>
#include <cstdlib>
#include <deque>
#include <vector>

namespace scansurf {
namespace {

// The 14 neighbours a voxel shares a tetrahedron edge with in the Freudenthal split of the
// cells (classification.h: every cube cut along its main diagonal into six): offsets in
// {0,1}^3 or {0,-1}^3. Two of them are linked when they share an edge too, i.e. when they form
// a triangle with the voxel; the links make the voxel's link, a triangulated sphere.
struct Neighbourhood {
  static constexpr int kCount = 14;
  std::array<std::array<int, 3>, kCount> offset{};
  std::array<std::uint32_t, kCount> linked{};

  static bool freudenthal(int dx, int dy, int dz) {
    const bool up = dx >= 0 && dy >= 0 && dz >= 0, down = dx <= 0 && dy <= 0 && dz <= 0;
    return (dx || dy || dz) && std::abs(dx) <= 1 && std::abs(dy) <= 1 && std::abs(dz) <= 1 && (up || down);
  }

  Neighbourhood() {
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (freudenthal(dx, dy, dz)) offset[static_cast<std::size_t>(n++)] = {dx, dy, dz};
    for (std::size_t a = 0; a < kCount; ++a)
      for (std::size_t b = 0; b < kCount; ++b)
        if (a != b && freudenthal(offset[b][0] - offset[a][0], offset[b][1] - offset[a][1], offset[b][2] - offset[a][2]))
          linked[a] |= 1u << b;
  }
};

const Neighbourhood kHood;
constexpr std::uint32_t kAll = (1u << Neighbourhood::kCount) - 1;

// The part of `mask` connected to its lowest bit along the link.
std::uint32_t flood(std::uint32_t mask) {
  std::uint32_t part = mask & (~mask + 1), frontier = part;
  while (frontier) {
    std::uint32_t next = 0;
    for (std::uint32_t f = frontier; f; f &= f - 1) next |= kHood.linked[static_cast<std::size_t>(std::countr_zero(f))];
    frontier = next & mask & ~part;
    part |= frontier;
  }
  return part;
}

// Whether the voxel whose neighbours with the label are `members` is simple for the label:
// on its link (a sphere) the neighbours with the label and those without are each one
// connected, non-empty patch, so the voxel's star meets the label's region in a disk and
// flipping it changes neither the region's topology nor the rest's.
bool simple(std::uint32_t members) {
  const std::uint32_t rest = ~members & kAll;
  return members && rest && flood(members) == members && flood(rest) == rest;
}

struct Gap {
  int nx = 0, ny = 0, layers = 0;  // layers m = 0 .. factor
  std::vector<Label> labels;       // the slab rule's, flipped toward the interpolation

  std::size_t index(int x, int y, int m) const {
    return (static_cast<std::size_t>(m) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(y)) *
               static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(x);
  }
  // The neighbours of (x, y, m) with `label`, as a mask (outside the grid: background).
  std::uint32_t members(int x, int y, int m, Label label) const {
    std::uint32_t mask = 0;
    for (std::size_t k = 0; k < Neighbourhood::kCount; ++k) {
      const int u = x + kHood.offset[k][0], v = y + kHood.offset[k][1], w = m + kHood.offset[k][2];
      const bool in = u >= 0 && v >= 0 && u < nx && v < ny && w >= 0 && w < layers;
      if ((in ? labels[index(u, v, w)] : kBackground) == label) mask |= 1u << k;
    }
    return mask;
  }
};

Label interpolatedLabel(const std::uint32_t* words, std::size_t i) { return static_cast<Label>(words[i] & 0xFFFFu); }

// Labels on both planes whose regions share no pixel: the interpolation moves them along their
// centroid shift as one tube (interpolation_plan.h), which the slab rule would cut in two; they
// start from the interpolation's labels.
std::vector<char> shiftingLabels(const Label* planeA, const Label* planeB, std::size_t plane) {
  constexpr std::size_t kLabels = std::size_t{1} << 16;
  std::vector<char> onA(kLabels, 0), onB(kLabels, 0), shared(kLabels, 0);
  for (std::size_t i = 0; i < plane; ++i) {
    const Label a = planeA[i], b = planeB[i];
    onA[a] = 1, onB[b] = 1;
    if (a == b) shared[a] = 1;
  }
  std::vector<char> shifting(kLabels, 0);
  for (std::size_t l = 1; l < kLabels; ++l) shifting[l] = onA[l] && onB[l] && !shared[l];
  return shifting;
}

}  // namespace

std::size_t keepSlabTopology(std::uint32_t* words, const Label* planeA, const Label* planeB, int nx, int ny, int factor,
                             std::uint16_t clearance) {
  if (factor < 2 || nx < 1 || ny < 1) return 0;
  Gap gap{nx, ny, factor + 1, {}};
  const std::size_t plane = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  gap.labels.resize(plane * static_cast<std::size_t>(factor + 1));
  const std::vector<char> shifting = shiftingLabels(planeA, planeB, plane);
  for (int m = 0; m <= factor; ++m)
    for (std::size_t i = 0; i < plane; ++i) {  // ties at the middle go to the lower plane
      const std::size_t at = static_cast<std::size_t>(m) * plane + i;
      const Label slabRule = 2 * m <= factor ? planeA[i] : planeB[i];
      const Label interpolated = m == 0 || m == factor ? slabRule : interpolatedLabel(words, at);
      gap.labels[at] = shifting[slabRule] || shifting[interpolated] ? interpolated : slabRule;
    }
  std::deque<std::size_t> queue;
  for (std::size_t i = plane; i < plane * static_cast<std::size_t>(factor); ++i)
    if (gap.labels[i] != interpolatedLabel(words, i)) queue.push_back(i);
  while (!queue.empty()) {
    const std::size_t i = queue.front();
    queue.pop_front();
    const Label from = gap.labels[i], to = interpolatedLabel(words, i);
    if (from == to) continue;
    const int x = static_cast<int>(i % static_cast<std::size_t>(nx));
    const int y = static_cast<int>((i / static_cast<std::size_t>(nx)) % static_cast<std::size_t>(ny));
    const int m = static_cast<int>(i / plane);
    if (!simple(gap.members(x, y, m, from)) || !simple(gap.members(x, y, m, to))) continue;
    gap.labels[i] = to;
    for (std::size_t k = 0; k < Neighbourhood::kCount; ++k) {
      const int u = x + kHood.offset[k][0], v = y + kHood.offset[k][1], w = m + kHood.offset[k][2];
      if (u < 0 || v < 0 || u >= nx || v >= ny || w < 1 || w >= factor) continue;
      const std::size_t j = gap.index(u, v, w);
      if (gap.labels[j] != interpolatedLabel(words, j)) queue.push_back(j);
    }
  }
  std::size_t kept = 0;
  for (std::size_t i = plane; i < plane * static_cast<std::size_t>(factor); ++i)
    if (gap.labels[i] != interpolatedLabel(words, i)) {
      words[i] = gap.labels[i] | (static_cast<std::uint32_t>(clearance) << 16);
      ++kept;
    }
  return kept;
}

}  // namespace scansurf
