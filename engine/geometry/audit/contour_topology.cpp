// scansurf: the slab volume's components, cavities and Euler characteristic from pixel runs
// (see contour_topology.h), without a voxel array: union-find over the runs for connectivity,
// and for the Euler characteristic the runs' cell counts.
//
// For the 6-adjacent set S, χ(S) is that of its dual cubical complex (voxels as vertices, face
// neighbours as edges, 2×2 squares as faces, 2×2×2 blocks as cubes). Within one layer the runs
// make χ = runs − (pairs of runs in adjacent rows sharing a column), and stacking layers glues
// each pair of consecutive layers along their common pixels (Mayer–Vietoris):
//   χ(S) = Σ χ(layer) − Σ χ(layer ∩ next layer).
// The boundary of a solid with c surfaces has Euler characteristic 2χ, so its surfaces' total
// genus is c − χ. For the 26-adjacent pair the surfaces are those of the 6-adjacent complement
// inside a padded box, less the box's own outer sphere: genus c − (χ(complement) − 1).
#include "geometry/audit/contour_topology.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "geometry/mesh/mesh_topology.h"
#include "geometry/overlaps/pixel_runs.h"

namespace scansurf {
namespace {

// Runs of a padded box of layers × rows: runs[start[layer * rows + row] ..] in column order.
struct RunBox {
  int layers = 0, rows = 0;
  int firstColumn = 0, endColumn = 0;  // the box's columns [first, end)
  std::vector<PixelRun> runs;
  std::vector<std::uint32_t> start;  // layers * rows + 1 offsets

  std::size_t first(int layer, int row) const { return start[static_cast<std::size_t>(layer * rows + row)]; }
  std::size_t last(int layer, int row) const { return start[static_cast<std::size_t>(layer * rows + row) + 1]; }
};

// The region with an empty layer, row and column on every side; rows renumbered from 0.
RunBox foreground(const FeatureRegion& region) {
  // Each region layer's place in the box: after the empty bottom layer, with an empty layer
  // wherever the region skips grid layers (a long gap, capped on each side).
  std::vector<std::size_t> place(region.layers.size());
  for (std::size_t l = 0, at = 1; l < region.layers.size(); ++l, ++at) {
    if (l > 0 && region.layers[l] > region.layers[l - 1] + 1) ++at;
    place[l] = at;
  }
  RunBox box;
  box.layers = static_cast<int>(place.empty() ? 2 : place.back() + 2);
  box.rows = region.maxRow - region.minRow + 3;
  box.firstColumn = region.minColumn - 1;
  box.endColumn = region.maxColumn + 2;
  box.start.assign(static_cast<std::size_t>(box.layers * box.rows) + 1, 0);
  std::vector<std::uint32_t> count(box.start.size(), 0);
  for (std::size_t l = 0; l < region.runs.size(); ++l)
    for (const PixelRun& r : region.runs[l]) {
      PixelRun local = r;
      local.row = r.row - region.minRow + 1;
      box.runs.push_back(local);
      ++count[place[l] * static_cast<std::size_t>(box.rows) + static_cast<std::size_t>(local.row)];
    }
  std::partial_sum(count.begin(), count.end() - 1, box.start.begin() + 1);
  return box;
}

// The box's pixels that the set leaves out, as runs.
RunBox complement(const RunBox& set) {
  RunBox box = set;
  box.runs.clear();
  for (int l = 0; l < set.layers; ++l)
    for (int row = 0; row < set.rows; ++row) {
      box.start[static_cast<std::size_t>(l * set.rows + row)] = static_cast<std::uint32_t>(box.runs.size());
      int column = set.firstColumn;
      for (std::size_t i = set.first(l, row); i < set.last(l, row); ++i) {
        if (set.runs[i].begin > column) box.runs.push_back({row, column, set.runs[i].begin});
        column = set.runs[i].end;
      }
      if (column < set.endColumn) box.runs.push_back({row, column, set.endColumn});
    }
  box.start.back() = static_cast<std::uint32_t>(box.runs.size());
  return box;
}

// Whether two runs share a column (slack 0) or touch at a corner at least (slack 1).
bool meet(const PixelRun& a, const PixelRun& b, int slack) { return a.begin < b.end + slack && b.begin < a.end + slack; }

// Calls pair(i, j) for each run i of row A and run j of row B that meet.
template <typename Pair>
void forMeetingRuns(const RunBox& box, std::size_t a0, std::size_t a1, std::size_t b0, std::size_t b1, int slack, Pair&& pair) {
  for (std::size_t i = a0, j = b0; i < a1 && j < b1;) {
    if (meet(box.runs[i], box.runs[j], slack)) pair(i, j);
    (box.runs[i].end < box.runs[j].end ? i : j)++;
  }
}

// Connected parts of the box's runs: 6-adjacency (wide = false) or 26 (true). With `inner`,
// only the parts that do not reach the box's outer shell (cavities of the complement).
int connectedParts(const RunBox& box, bool wide, bool inner) {
  UnionFind sets(box.runs.size());
  const int slack = wide ? 1 : 0;
  const auto unite = [&](std::size_t i, std::size_t j) {
    sets.unite(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
  };
  for (int l = 0; l < box.layers; ++l)
    for (int row = 0; row < box.rows; ++row) {
      const std::size_t a0 = box.first(l, row), a1 = box.last(l, row);
      if (row + 1 < box.rows) forMeetingRuns(box, a0, a1, box.first(l, row + 1), box.last(l, row + 1), slack, unite);
      if (l + 1 == box.layers) continue;
      forMeetingRuns(box, a0, a1, box.first(l + 1, row), box.last(l + 1, row), slack, unite);
      if (!wide) continue;
      if (row > 0) forMeetingRuns(box, a0, a1, box.first(l + 1, row - 1), box.last(l + 1, row - 1), 1, unite);
      if (row + 1 < box.rows) forMeetingRuns(box, a0, a1, box.first(l + 1, row + 1), box.last(l + 1, row + 1), 1, unite);
    }
  std::vector<bool> outer(box.runs.size(), false);
  for (std::size_t i = 0; i < box.runs.size(); ++i) {
    const PixelRun& r = box.runs[i];
    const bool shell = i < box.first(1, 0) || i >= box.first(box.layers - 1, 0) || r.row == 0 || r.row + 1 == box.rows ||
                       r.begin == box.firstColumn || r.end == box.endColumn;
    if (shell) outer[sets.find(static_cast<std::uint32_t>(i))] = true;
  }
  int parts = 0;
  for (std::size_t i = 0; i < box.runs.size(); ++i)
    if (sets.find(static_cast<std::uint32_t>(i)) == i && !(inner && outer[i])) ++parts;
  return parts;
}

// χ of one layer's 4-adjacent pixels (rows of sorted runs, each row's runs apart).
long layerEuler(const std::vector<PixelRun>& runs) {
  long chi = static_cast<long>(runs.size());
  std::size_t i = 0;
  while (i < runs.size()) {
    std::size_t rowEnd = i;
    while (rowEnd < runs.size() && runs[rowEnd].row == runs[i].row) ++rowEnd;
    std::size_t next = rowEnd;
    while (next < runs.size() && runs[next].row == runs[rowEnd].row) ++next;
    if (rowEnd < runs.size() && runs[rowEnd].row == runs[i].row + 1)
      for (std::size_t a = i, b = rowEnd; a < rowEnd && b < next;) {
        if (meet(runs[a], runs[b], 0)) --chi;
        (runs[a].end < runs[b].end ? a : b)++;
      }
    i = rowEnd;
  }
  return chi;
}

std::vector<PixelRun> layerRuns(const RunBox& box, int layer) {
  return {box.runs.begin() + static_cast<std::ptrdiff_t>(box.first(layer, 0)),
          box.runs.begin() + static_cast<std::ptrdiff_t>(box.first(layer + 1, 0))};
}

// χ of the box's runs as a 6-adjacent set (Mayer–Vietoris over the layers).
long euler6(const RunBox& box) {
  long chi = 0;
  std::vector<PixelRun> below = layerRuns(box, 0);
  chi += layerEuler(below);
  for (int l = 1; l < box.layers; ++l) {
    std::vector<PixelRun> here = layerRuns(box, l);
    chi += layerEuler(here) - layerEuler(intersectPixelRuns(below, here));
    below = std::move(here);
  }
  return chi;
}

// Pixel-weighted centroid of a layer's runs, in pixels.
std::pair<double, double> centroid(const std::vector<PixelRun>& runs) {
  double area = 0, x = 0, y = 0;
  for (const PixelRun& r : runs) {
    const double n = r.end - r.begin;
    area += n, x += n * 0.5 * (r.begin + r.end - 1), y += n * r.row;
  }
  return {x / area, y / area};
}

// Where a layer shares no pixel with the one below, interpolation moves the structure along
// its centroid shift (one tube, interpolation_plan.h): the layers from there up are moved back
// by that shift, so that stacking them joins what the interpolation joins.
FeatureRegion aligned(const FeatureRegion& region) {
  FeatureRegion out = region;
  int dx = 0, dy = 0;
  for (std::size_t l = 1; l < out.runs.size(); ++l) {
    const std::vector<PixelRun>& below = region.runs[l - 1];
    const std::vector<PixelRun>& here = region.runs[l];
    const bool adjacent = region.layers[l] == region.layers[l - 1] + 1;  // not across a long gap
    if (adjacent && !below.empty() && !here.empty() && sharedPixels(below, here) == 0) {
      const auto [ax, ay] = centroid(below);
      const auto [bx, by] = centroid(here);
      dx += static_cast<int>(std::lround(bx - ax)), dy += static_cast<int>(std::lround(by - ay));
    }
    for (PixelRun& r : out.runs[l]) r.row -= dy, r.begin -= dx, r.end -= dx;
  }
  out.minRow = out.minColumn = std::numeric_limits<int>::max();
  out.maxRow = out.maxColumn = std::numeric_limits<int>::min();
  for (const std::vector<PixelRun>& layer : out.runs)
    for (const PixelRun& r : layer) {
      out.minRow = std::min(out.minRow, r.row), out.maxRow = std::max(out.maxRow, r.row);
      out.minColumn = std::min(out.minColumn, r.begin), out.maxColumn = std::max(out.maxColumn, r.end - 1);
    }
  return out;
}

}  // namespace

TopologyRange contourTopology(const FeatureRegion& given) {
  TopologyRange range;
  if (given.maxRow < given.minRow || given.layers.empty()) return range;
  const FeatureRegion region = aligned(given);
  if (region.maxRow < region.minRow) return range;
  const RunBox set = foreground(region);
  const RunBox rest = complement(set);
  // 6-adjacent set, 26-adjacent complement.
  const int surfaces6 = connectedParts(set, false, false) + connectedParts(rest, true, true);
  const long genus6 = surfaces6 - euler6(set);
  // 26-adjacent set, 6-adjacent complement.
  const int surfaces26 = connectedParts(set, true, false) + connectedParts(rest, false, true);
  const long genus26 = surfaces26 - (euler6(rest) - 1);
  range.minComponents = std::min(surfaces6, surfaces26);
  range.maxComponents = std::max(surfaces6, surfaces26);
  range.minGenus = static_cast<int>(std::min(genus6, genus26));
  range.maxGenus = static_cast<int>(std::max(genus6, genus26));
  return range;
}

}  // namespace scansurf
