// scansurf: parts of labels between two planes that reach neither (invented_islands.h), found
// by union-find over runs of one label along rows rather than over voxels: uniform stretches
// are one element, so the cost follows the boundaries.
#include "geometry/interpolation/invented_islands.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace scansurf {
namespace {

struct Run {
  int begin = 0, end = 0;  // columns [begin, end)
  Label label = 0;
};

// Runs of equal labels, row by row and layer by layer; start[layer * ny + row] is a row's first.
struct Runs {
  std::vector<Run> runs;
  std::vector<std::uint32_t> start;
};

Label labelAt(const std::uint32_t* words, const Label* planeB, std::size_t plane, int layer, int factor, std::size_t i) {
  return layer < factor ? static_cast<Label>(words[plane * static_cast<std::size_t>(layer) + i] & 0xFFFFu) : planeB[i];
}

Runs runsOf(const std::uint32_t* words, const Label* planeB, int nx, int ny, int factor) {
  Runs out;
  const std::size_t plane = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  for (int layer = 0; layer <= factor; ++layer)
    for (int row = 0; row < ny; ++row) {
      out.start.push_back(static_cast<std::uint32_t>(out.runs.size()));
      const std::size_t base = static_cast<std::size_t>(row) * static_cast<std::size_t>(nx);
      for (int x = 0; x < nx;) {
        const Label label = labelAt(words, planeB, plane, layer, factor, base + static_cast<std::size_t>(x));
        int end = x + 1;
        while (end < nx && labelAt(words, planeB, plane, layer, factor, base + static_cast<std::size_t>(end)) == label) ++end;
        out.runs.push_back({x, end, label});
        x = end;
      }
    }
  out.start.push_back(static_cast<std::uint32_t>(out.runs.size()));
  return out;
}

std::uint32_t find(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// Unites runs of one label in rows a and b that touch (share a column or a corner).
void uniteRows(const Runs& r, std::size_t a, std::size_t b, std::vector<std::uint32_t>& parent) {
  for (std::uint32_t i = r.start[a], j = r.start[b]; i < r.start[a + 1] && j < r.start[b + 1];) {
    const Run& p = r.runs[i];
    const Run& q = r.runs[j];
    if (p.label == q.label && p.begin <= q.end && q.begin <= p.end) {
      const std::uint32_t ri = find(parent, i), rj = find(parent, j);
      if (ri != rj) parent[std::max(ri, rj)] = std::min(ri, rj);
    }
    (p.end < q.end ? i : j)++;
  }
}

// The label around a part: the most voxels of the labels beside its runs in their rows.
Label surroundingLabel(const Runs& r, const std::vector<std::uint32_t>& members) {
  std::vector<std::pair<Label, long>> votes;
  const auto vote = [&](const Run& run) {
    auto it = std::find_if(votes.begin(), votes.end(), [&](const auto& v) { return v.first == run.label; });
    if (it == votes.end())
      votes.push_back({run.label, run.end - run.begin});
    else
      it->second += run.end - run.begin;
  };
  for (std::uint32_t i : members) {
    const std::size_t row = static_cast<std::size_t>(std::upper_bound(r.start.begin(), r.start.end(), i) - r.start.begin()) - 1;
    if (i > r.start[row]) vote(r.runs[i - 1]);
    if (i + 1 < r.start[row + 1]) vote(r.runs[i + 1]);
  }
  if (votes.empty()) return kBackground;
  return std::max_element(votes.begin(), votes.end(), [](const auto& a, const auto& b) { return a.second < b.second; })->first;
}

}  // namespace

std::size_t removeInventedIslands(std::uint32_t* words, const Label* planeB, int nx, int ny, int factor,
                                  std::uint16_t clearance) {
  if (factor < 2 || nx < 1 || ny < 1) return 0;
  const Runs r = runsOf(words, planeB, nx, ny, factor);
  std::vector<std::uint32_t> parent(r.runs.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const std::size_t rows = static_cast<std::size_t>(ny);
  for (int layer = 0; layer <= factor; ++layer)
    for (std::size_t row = 0; row < rows; ++row) {
      const std::size_t here = static_cast<std::size_t>(layer) * rows + row;
      if (row + 1 < rows) uniteRows(r, here, here + 1, parent);
      if (layer == factor) continue;
      const std::size_t above = here + rows;
      uniteRows(r, here, above, parent);
      if (row > 0) uniteRows(r, here, above - 1, parent);
      if (row + 1 < rows) uniteRows(r, here, above + 1, parent);
    }
  // A part reaches a plane when any of its runs lies on layer 0 or layer `factor`.
  std::vector<char> onPlane(r.runs.size(), 0);
  const std::uint32_t firstInner = r.start[rows], firstB = r.start[static_cast<std::size_t>(factor) * rows];
  for (std::uint32_t i = 0; i < r.runs.size(); ++i)
    if (i < firstInner || i >= firstB) onPlane[find(parent, i)] = 1;
  std::vector<std::vector<std::uint32_t>> islands;
  std::vector<std::int32_t> islandOf(r.runs.size(), -1);
  for (std::uint32_t i = firstInner; i < firstB; ++i) {
    const std::uint32_t root = find(parent, i);
    if (onPlane[root]) continue;
    if (islandOf[root] < 0) islandOf[root] = static_cast<std::int32_t>(islands.size()), islands.emplace_back();
    islands[static_cast<std::size_t>(islandOf[root])].push_back(i);
  }
  const std::size_t plane = static_cast<std::size_t>(nx) * rows;
  std::size_t changed = 0;
  for (const std::vector<std::uint32_t>& members : islands) {
    const Label label = surroundingLabel(r, members);
    for (std::uint32_t i : members) {
      const std::size_t row = static_cast<std::size_t>(std::upper_bound(r.start.begin(), r.start.end(), i) - r.start.begin()) - 1;
      std::uint32_t* line = words + plane * (row / rows) + (row % rows) * static_cast<std::size_t>(nx);
      for (int x = r.runs[i].begin; x < r.runs[i].end; ++x) line[x] = label | (static_cast<std::uint32_t>(clearance) << 16);
      changed += static_cast<std::size_t>(r.runs[i].end - r.runs[i].begin);
    }
  }
  return changed;
}

}  // namespace scansurf
