// scansurf: overlap analysis and layer assignment: each feature's own region as the GPU draws
// it, shared and touching pairs, volumes three ways, and the fewest layers (DSatur, Brélaz
// 1979, exact for small components); see overlap_analysis.h.
#include "geometry/overlaps/overlap_analysis.h"

#include <algorithm>
#include <functional>
#include <map>

#include "core/parallel.h"
#include "geometry/contours/polygon.h"
#include "geometry/overlaps/overlap_split.h"

namespace scansurf {
namespace {

FeatureRegion rasterizeFeature(const Feature& feature, const Grid& grid, int bits) {
  FeatureRegion region;
  region.minRow = grid.ny, region.minColumn = grid.nx;
  for (const FeatureSlice& slice : feature.slices) {
    const int k = grid.layerOfPlane(slice.z);
    if (k < 0) continue;
    std::vector<PixelRun> runs = rasterizeSlice(slice.contours, grid, bits);
    for (const PixelRun& r : runs) {
      region.minRow = std::min(region.minRow, r.row), region.maxRow = std::max(region.maxRow, r.row);
      region.minColumn = std::min(region.minColumn, r.begin), region.maxColumn = std::max(region.maxColumn, r.end - 1);
    }
    if (!region.layers.empty() && region.layers.back() == k) {  // two slices on one layer (a wide tolerance): their union
      region.runs.back() = unitePixelRuns(region.runs.back(), runs);
      continue;
    }
    region.layers.push_back(k);
    region.runs.push_back(std::move(runs));
  }
  return region;
}

bool boxesNear(const FeatureRegion& a, const FeatureRegion& b, int margin) {
  if (a.maxRow < a.minRow || b.maxRow < b.minRow) return false;
  return a.minRow <= b.maxRow + margin && b.minRow <= a.maxRow + margin && a.minColumn <= b.maxColumn + margin &&
         b.minColumn <= a.maxColumn + margin;
}

// Voxels two regions share, and their volume.
std::pair<std::size_t, double> sharedVoxels(const FeatureRegion& a, const FeatureRegion& b, const Grid& grid) {
  std::size_t voxels = 0;
  double volume = 0;
  forEachCommonLayer(a, b, [&](int k, const std::vector<PixelRun>& ra, const std::vector<PixelRun>& rb) {
    const std::size_t n = sharedPixels(ra, rb);
    voxels += n;
    volume += static_cast<double>(n) * voxelVolume(grid, k);
    return true;
  });
  return {voxels, volume};
}

// Whether two regions that share no voxel have voxels sharing a face (in a layer or across
// neighbouring layers).
bool regionsTouch(const FeatureRegion& a, const FeatureRegion& b) {
  // Both layer lists are sorted: for each layer of a, only b's layers within one of it.
  std::size_t first = 0;
  for (std::size_t i = 0; i < a.layers.size(); ++i) {
    while (first < b.layers.size() && b.layers[first] < a.layers[i] - 1) ++first;
    for (std::size_t j = first; j < b.layers.size() && b.layers[j] <= a.layers[i] + 1; ++j) {
      const int d = a.layers[i] - b.layers[j];
      if (d == 0 && touchInPlane(a.runs[i], b.runs[j])) return true;
      if (d != 0 && sharedPixels(a.runs[i], b.runs[j]) > 0) return true;
    }
  }
  return false;
}

double slab(const Grid& grid, int k) {
  return 0.5 * (grid.layerZ[static_cast<std::size_t>(k + 1)] - grid.layerZ[static_cast<std::size_t>(k - 1)]);
}

}  // namespace

double slabVolume(const Feature& feature, const Grid& grid) {
  double volume = 0;
  for (const FeatureSlice& slice : feature.slices) {
    const int k = grid.layerOfPlane(slice.z);
    if (k > 0 && k < grid.nz - 1) volume += std::abs(regionArea(slice.contours)) * slab(grid, k);
  }
  return volume;
}

namespace {

FeatureVolumes volumesOf(const Feature& feature, const FeatureRegion& region, const Grid& grid) {
  FeatureVolumes v;
  v.contour = slabVolume(feature, grid);
  for (std::size_t s = 0; s < region.layers.size(); ++s) {
    const std::size_t n = pixelCount(region.runs[s]);
    v.ownVoxels += n;
    v.ownVolume += static_cast<double>(n) * voxelVolume(grid, region.layers[s]);
  }
  return v;
}

// ---- layer assignment ----

struct Colouring {
  const std::vector<std::vector<int>>& conflicts;
  const std::vector<std::vector<int>>& affinity;
  std::vector<int>& colour;

  // Colours to try for v: those of its affinity neighbours first, then ascending.
  std::vector<int> preferences(int v, int k) const {
    std::vector<int> order;
    for (int u : affinity[static_cast<std::size_t>(v)])
      if (int c = colour[static_cast<std::size_t>(u)]; c >= 0 && c < k && std::find(order.begin(), order.end(), c) == order.end())
        order.push_back(c);
    for (int c = 0; c < k; ++c)
      if (std::find(order.begin(), order.end(), c) == order.end()) order.push_back(c);
    return order;
  }
  bool allowed(int v, int c) const {
    for (int u : conflicts[static_cast<std::size_t>(v)])
      if (colour[static_cast<std::size_t>(u)] == c) return false;
    return true;
  }
  // Backtracking over `order` with k colours; gives up after `budget` steps.
  bool search(const std::vector<int>& order, std::size_t at, int k, long& budget) {
    if (at == order.size()) return true;
    if (--budget < 0) return false;
    const int v = order[at];
    for (int c : preferences(v, k)) {
      if (!allowed(v, c)) continue;
      colour[static_cast<std::size_t>(v)] = c;
      if (search(order, at + 1, k, budget)) return true;
    }
    colour[static_cast<std::size_t>(v)] = -1;
    return false;
  }
};

// DSatur order of a component: most distinct neighbour colours first (ties: degree, then
// component order), with its greedy colouring (the upper bound). Each vertex keeps the set of
// its neighbours' colours, updated as they are coloured: O(n^2 + edges), so a component of
// thousands of mutually overlapping features (nested rings) colours in moments.
std::pair<std::vector<int>, int> dsatur(const std::vector<int>& component, Colouring& colouring) {
  const std::size_t m = component.size();
  std::vector<int> localOf(colouring.colour.size(), -1);
  for (std::size_t i = 0; i < m; ++i) localOf[static_cast<std::size_t>(component[i])] = static_cast<int>(i);
  std::vector<std::vector<char>> neighbourColours(m);
  std::vector<int> saturation(m, 0);
  std::vector<char> done(m, 0);
  std::vector<int> order;
  int colours = 0;
  auto taken = [&](std::size_t i, int c) {
    return static_cast<std::size_t>(c) < neighbourColours[i].size() && neighbourColours[i][static_cast<std::size_t>(c)];
  };
  for (std::size_t step = 0; step < m; ++step) {
    std::size_t best = m;
    for (std::size_t i = 0; i < m; ++i) {
      if (done[i]) continue;
      const auto degree = [&](std::size_t j) { return colouring.conflicts[static_cast<std::size_t>(component[j])].size(); };
      if (best == m || saturation[i] > saturation[best] || (saturation[i] == saturation[best] && degree(i) > degree(best)))
        best = i;
    }
    done[best] = 1;
    const int v = component[best];
    order.push_back(v);
    // Affinity neighbours' colours first, then ascending: the first one no neighbour has.
    int chosen = -1;
    for (int u : colouring.affinity[static_cast<std::size_t>(v)])
      if (int c = colouring.colour[static_cast<std::size_t>(u)]; chosen < 0 && c >= 0 && c <= colours && !taken(best, c))
        chosen = c;
    for (int c = 0; chosen < 0; ++c)
      if (!taken(best, c)) chosen = c;
    colouring.colour[static_cast<std::size_t>(v)] = chosen;
    colours = std::max(colours, chosen + 1);
    for (int u : colouring.conflicts[static_cast<std::size_t>(v)]) {
      const int lu = localOf[static_cast<std::size_t>(u)];
      if (lu < 0 || done[static_cast<std::size_t>(lu)] || taken(static_cast<std::size_t>(lu), chosen)) continue;
      auto& seen = neighbourColours[static_cast<std::size_t>(lu)];
      if (seen.size() <= static_cast<std::size_t>(chosen)) seen.resize(static_cast<std::size_t>(chosen) + 1, 0);
      seen[static_cast<std::size_t>(chosen)] = 1;
      ++saturation[static_cast<std::size_t>(lu)];
    }
  }
  return {order, colours};
}

std::vector<std::vector<int>> components(int n, const std::vector<std::vector<int>>& conflicts) {
  std::vector<int> seen(static_cast<std::size_t>(n), 0);
  std::vector<std::vector<int>> out;
  for (int s = 0; s < n; ++s) {
    if (seen[static_cast<std::size_t>(s)]) continue;
    std::vector<int> component{s};
    seen[static_cast<std::size_t>(s)] = 1;
    for (std::size_t i = 0; i < component.size(); ++i)
      for (int u : conflicts[static_cast<std::size_t>(component[i])])
        if (!seen[static_cast<std::size_t>(u)]) seen[static_cast<std::size_t>(u)] = 1, component.push_back(u);
    std::sort(component.begin(), component.end());
    out.push_back(std::move(component));
  }
  return out;
}

}  // namespace

std::vector<FeatureRegion> rasterizeFeatures(const ContourSet& contours, const Grid& grid, int subPixelBits, int threads) {
  std::vector<FeatureRegion> regions(contours.features.size());
  parallelChunks(regions.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) regions[f] = rasterizeFeature(contours.features[f], grid, subPixelBits);
  });
  return regions;
}

double voxelVolume(const Grid& grid, int k) { return grid.spacingX * grid.spacingY * slab(grid, k); }

std::vector<int> assignLayers(int n, const std::vector<std::pair<int, int>>& conflictPairs,
                              const std::vector<std::pair<int, int>>& affinityPairs) {
  std::vector<std::vector<int>> conflicts(static_cast<std::size_t>(n)), affinity(static_cast<std::size_t>(n));
  for (auto [a, b] : conflictPairs)
    conflicts[static_cast<std::size_t>(a)].push_back(b), conflicts[static_cast<std::size_t>(b)].push_back(a);
  for (auto [a, b] : affinityPairs)
    affinity[static_cast<std::size_t>(a)].push_back(b), affinity[static_cast<std::size_t>(b)].push_back(a);
  std::vector<int> colour(static_cast<std::size_t>(n), -1);
  Colouring colouring{conflicts, affinity, colour};
  constexpr std::size_t kExactUpTo = 24;
  for (const std::vector<int>& component : components(n, conflicts)) {
    auto [order, upper] = dsatur(component, colouring);
    if (component.size() > kExactUpTo || upper <= 2) continue;  // 1 or 2 colours are optimal once found
    const std::vector<int> greedy = colour;
    for (int k = 2; k < upper; ++k) {
      for (int v : component) colour[static_cast<std::size_t>(v)] = -1;
      long budget = 200000;
      if (colouring.search(order, 0, k, budget)) break;
      for (int v : component) colour[static_cast<std::size_t>(v)] = greedy[static_cast<std::size_t>(v)];
    }
  }
  return colour;
}

// Entry and exit times of a depth-first walk of the nesting forest: a is inside b exactly when
// b's interval holds a's. O(1) per pair where isInside walks the parent chain (thousands deep
// for thousands of nested rings).
struct NestingIntervals {
  std::vector<int> enter, exit;
  explicit NestingIntervals(const Nesting& nesting) {
    const int n = static_cast<int>(nesting.parent.size());
    std::vector<std::vector<int>> children(static_cast<std::size_t>(n));
    std::vector<int> stack;
    for (int f = 0; f < n; ++f) {
      const int p = nesting.parent[static_cast<std::size_t>(f)];
      if (p >= 0 && p < n)
        children[static_cast<std::size_t>(p)].push_back(f);
      else
        stack.push_back(f);
    }
    enter.assign(static_cast<std::size_t>(n), 0), exit.assign(static_cast<std::size_t>(n), 0);
    std::vector<std::size_t> next(static_cast<std::size_t>(n), 0);  // next child to visit
    int clock = 0;
    std::vector<int> path;
    for (int root : stack) {
      path.push_back(root);
      enter[static_cast<std::size_t>(root)] = clock++;
      while (!path.empty()) {
        const auto v = static_cast<std::size_t>(path.back());
        if (next[v] < children[v].size()) {
          const int c = children[v][next[v]++];
          enter[static_cast<std::size_t>(c)] = clock++;
          path.push_back(c);
        } else {
          exit[v] = clock++;
          path.pop_back();
        }
      }
    }
  }
  bool inside(int a, int b) const {
    const auto i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
    return a != b && enter[j] < enter[i] && exit[i] < exit[j];
  }
};

OverlapReport analyzeOverlaps(const ContourSet& contours, const Grid& grid, const Nesting& nesting,
                              const std::vector<FeatureRegion>& regions, const OverlapTolerance& tolerance) {
  const NestingIntervals intervals(nesting);
  OverlapReport report;
  const int n = static_cast<int>(contours.features.size());
  for (int f = 0; f < n; ++f)
    report.features.push_back(
        volumesOf(contours.features[static_cast<std::size_t>(f)], regions[static_cast<std::size_t>(f)], grid));
  std::vector<std::pair<int, int>> anyShared, affinity;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const FeatureRegion &ra = regions[static_cast<std::size_t>(a)], &rb = regions[static_cast<std::size_t>(b)];
      if (!boxesNear(ra, rb, 1)) continue;
      const auto [voxels, volume] = sharedVoxels(ra, rb, grid);
      const bool nested = intervals.inside(a, b) || intervals.inside(b, a);
      if (voxels > 0) {
        report.shared.push_back({a, b, voxels, volume, nested});
        anyShared.emplace_back(a, b);
      } else if (regionsTouch(ra, rb)) {
        report.touching.emplace_back(a, b);
        affinity.emplace_back(a, b);
      }
    }
  // Real partial overlaps keep their features apart; nested and incidental pairs and abutting
  // ones would rather share a layer.
  judgeOverlaps(contours, grid, regions, tolerance, report);
  std::vector<std::pair<int, int>> real;
  for (const SharedVolume& s : report.shared) {
    if (s.nested || s.incidental)
      affinity.emplace_back(s.a, s.b);
    else
      real.emplace_back(s.a, s.b);
  }
  const std::vector<int> layers = assignLayers(n, real, affinity);
  const std::vector<int> maskLayers = assignLayers(n, anyShared, report.touching);
  for (int f = 0; f < n; ++f) {
    report.features[static_cast<std::size_t>(f)].layer = layers[static_cast<std::size_t>(f)];
    report.features[static_cast<std::size_t>(f)].maskLayer = maskLayers[static_cast<std::size_t>(f)];
    report.layers = std::max(report.layers, layers[static_cast<std::size_t>(f)] + 1);
    report.maskLayers = std::max(report.maskLayers, maskLayers[static_cast<std::size_t>(f)] + 1);
  }
  return report;
}

std::vector<VolumeLoss> volumeLosses(const std::vector<FeatureRegion>& regions, const LabelVolume& partition,
                                     const Nesting& nesting) {
  std::vector<VolumeLoss> losses;
  const Grid& grid = partition.grid;
  for (std::size_t f = 0; f < regions.size(); ++f) {
    std::map<int, std::pair<std::size_t, double>> lost;  // by feature: voxels, volume
    const FeatureRegion& region = regions[f];
    for (std::size_t s = 0; s < region.layers.size(); ++s) {
      const int k = region.layers[s];
      for (const PixelRun& r : region.runs[s])
        for (int i = r.begin; i < r.end; ++i) {
          const Label label = partition.at(i, r.row, k);
          if (label == labelOfFeature(static_cast<int>(f))) continue;
          auto& entry = lost[featureOfLabel(label)];
          ++entry.first;
          entry.second += voxelVolume(grid, k);
        }
    }
    for (const auto& [to, amount] : lost)
      losses.push_back(
          {static_cast<int>(f), to, amount.first, amount.second, to >= 0 && isInside(nesting, to, static_cast<int>(f))});
  }
  return losses;
}

}  // namespace scansurf

namespace scansurf {

std::optional<OverlapMode> parseOverlapMode(std::string_view name) {
  if (name == "layers") return OverlapMode::Layers;
  if (name == "partition") return OverlapMode::Partition;
  return std::nullopt;
}

const char* overlapModeName(OverlapMode mode) { return mode == OverlapMode::Layers ? "layers" : "partition"; }

}  // namespace scansurf
