// scansurf: the nesting order of features (paper §3.3). The paper sorts features with an
// inside/outside comparison of their contours; here containment is tested per feature pair
// (every contour point of the inner feature within the outer's even-odd region on each of its
// slices; a container's containers contain too), then features are ordered by the length of
// their chain of containers, deepest first.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/contours/polygon.h"
#include "scansurf/nesting.h"

namespace scansurf {

namespace {

struct FeatureInfo {
  Box2 box;  // over all slices
  double zMin = 0, zMax = 0;
  std::vector<double> z;         // slice planes, sorted (validated input)
  std::vector<Box2> sliceBoxes;  // per slice
  double area = 0;               // summed even-odd area over slices, the size used for ties
  double tolerance = 0;          // slice z values closer than this are one plane
};

FeatureInfo describe(const Feature& feature, double tolerance) {
  FeatureInfo info;
  info.tolerance = tolerance;
  for (const FeatureSlice& slice : feature.slices) {
    info.z.push_back(slice.z);
    info.sliceBoxes.push_back(boundingBox(slice.contours));
    info.box.add(info.sliceBoxes.back());
    info.area += std::abs(regionArea(slice.contours));
  }
  if (!info.z.empty()) {
    info.zMin = *std::min_element(info.z.begin(), info.z.end());
    info.zMax = *std::max_element(info.z.begin(), info.z.end());
  }
  return info;
}

// The slice of `info` within tolerance of z, or -1.
int sliceAt(const FeatureInfo& info, double z) {
  for (std::size_t s = 0; s < info.z.size(); ++s)
    if (std::abs(info.z[s] - z) <= info.tolerance) return static_cast<int>(s);
  return -1;
}

// Whether, beside each edge of contour c, the inner region's side lies in `outer`: a contour
// drawn on the outline of a hole of the outer region (an organ in an opening of a structure
// drawn around it) has every point on that outline, yet its region is the hole, outside.
bool insideAlongEdges(const RegionIndex& innerRegion, const Contour& c, const RegionIndex& outer) {
  const std::size_t n = c.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 a = c.points[i], b = c.points[(i + 1) % n];
    const double dx = b.x - a.x, dy = b.y - a.y, length = std::hypot(dx, dy);
    if (!(length > 0)) continue;
    const double step = 1e-3 * length;
    const Point2 mid{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
    Point2 side{mid.x - step * dy / length, mid.y + step * dx / length};
    if (!innerRegion.inside(side)) side = {mid.x + step * dy / length, mid.y - step * dx / length};
    if (!innerRegion.inside(side)) continue;  // a sliver thinner than the step: no side to test
    if (!outer.inside(side)) return false;
  }
  return true;
}

// Whether every contour point of `inner` lies in `outer`'s region on every slice of inner.
// Points on the outer boundary count as inside, so a feature drawn along its container's edge,
// or identical to it, is contained.
bool contains(const Feature& outer, const FeatureInfo& outerInfo, const Feature& inner, const FeatureInfo& innerInfo) {
  if (inner.slices.empty()) return false;
  if (!outerInfo.box.contains(innerInfo.box)) return false;
  if (innerInfo.zMin < outerInfo.zMin - outerInfo.tolerance || innerInfo.zMax > outerInfo.zMax + outerInfo.tolerance)
    return false;
  const Box2& box = outerInfo.box;
  const double boundaryTolerance = 1e-9 * std::max({1.0, box.width(), box.height(), std::abs(box.minX), std::abs(box.minY),
                                                    std::abs(box.maxX), std::abs(box.maxY)});
  for (std::size_t s = 0; s < inner.slices.size(); ++s) {
    const int o = sliceAt(outerInfo, inner.slices[s].z);
    if (o < 0) return false;
    if (!outerInfo.sliceBoxes[o].contains(innerInfo.sliceBoxes[s])) return false;
  }
  for (std::size_t s = 0; s < inner.slices.size(); ++s) {
    const auto& region = outer.slices[sliceAt(outerInfo, inner.slices[s].z)].contours;
    const RegionIndex outerIndex(region), innerIndex(inner.slices[s].contours);
    for (const Contour& c : inner.slices[s].contours) {
      for (const Point2& p : c.points)
        if (!outerIndex.inside(p) && !onBoundary(region, p, boundaryTolerance)) return false;
      if (!insideAlongEdges(innerIndex, c, outerIndex)) return false;
    }
  }
  return true;
}

}  // namespace

Nesting computeNesting(const ContourSet& contours, double requestedTolerance) {
  const double sliceTolerance = sliceToleranceOf(contours, requestedTolerance);
  const int n = static_cast<int>(contours.features.size());
  std::vector<FeatureInfo> info;
  info.reserve(n);
  for (const Feature& f : contours.features) info.push_back(describe(f, sliceTolerance));

  // A total order on (area, index): a container must rank above what it contains. This breaks
  // mutual containment of identical features by index and keeps the relation acyclic even for
  // shapes where point containment alone is not.
  auto ranksAbove = [&](int a, int b) { return info[a].area != info[b].area ? info[a].area > info[b].area : a > b; };
  std::vector<int> byRank(n);
  std::iota(byRank.begin(), byRank.end(), 0);
  std::sort(byRank.begin(), byRank.end(), [&](int a, int b) { return ranksAbove(a, b); });

  // containers[f]: every feature containing f.
  std::vector<std::vector<int>> containers(n);
  // Candidates sorted by box minX let each feature skip boxes that cannot hold it.
  std::vector<int> byMinX(n);
  std::iota(byMinX.begin(), byMinX.end(), 0);
  std::sort(byMinX.begin(), byMinX.end(),
            [&](int a, int b) { return info[a].box.minX != info[b].box.minX ? info[a].box.minX < info[b].box.minX : a < b; });
  // Containment is taken as transitive: candidates are tested smallest first, and once g is
  // found to contain f, every container of g contains f without a test of its own. Features are
  // visited largest first, so containers[g] is complete when f needs it. Deeply nested sets
  // (thousands of rings) then cost one polygon test per feature instead of one per pair.
  std::vector<int> candidates;
  std::vector<int> seenFor(n, -1);  // seenFor[g] == f: g already judged for f
  for (int f : byRank) {
    if (info[f].box.empty()) continue;
    candidates.clear();
    for (int g : byMinX) {
      if (info[g].box.minX > info[f].box.minX) break;  // no later box starts left of f's
      if (g != f && ranksAbove(g, f) && info[g].box.contains(info[f].box)) candidates.push_back(g);
    }
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) { return ranksAbove(b, a); });
    for (int g : candidates) {
      if (seenFor[g] == f) continue;
      seenFor[g] = f;
      if (!contains(contours.features[g], info[g], contours.features[f], info[f])) continue;
      containers[f].push_back(g);
      for (int h : containers[g])
        if (seenFor[h] != f) seenFor[h] = f, containers[f].push_back(h);
    }
  }

  Nesting nesting;
  nesting.parent.assign(n, -1);
  std::vector<int> depth(n, 0);
  // Containers rank above, so visiting in rank order sees every container's depth first.
  for (int f : byRank) {
    int parent = -1;
    for (int g : containers[f]) {
      depth[f] = std::max(depth[f], depth[g] + 1);
      if (parent < 0 || ranksAbove(parent, g)) parent = g;  // the smallest container
    }
    nesting.parent[f] = parent;
  }

  if (!contours.order.empty()) {
    nesting.order = contours.order;
    nesting.userOrder = true;
  } else {
    nesting.order.resize(n);
    std::iota(nesting.order.begin(), nesting.order.end(), 0);
    std::stable_sort(nesting.order.begin(), nesting.order.end(), [&](int a, int b) { return depth[a] > depth[b]; });
  }
  return nesting;
}

bool isInside(const Nesting& nesting, int inner, int outer) {
  const int n = static_cast<int>(nesting.parent.size());
  if (inner < 0 || inner >= n || outer < 0 || outer >= n) return false;
  // Bounded walk: parent links are acyclic, the bound only guards a hand-made Nesting.
  int f = nesting.parent[inner];
  for (int steps = 0; f >= 0 && steps < n; ++steps, f = nesting.parent[f])
    if (f == outer) return true;
  return false;
}

}  // namespace scansurf

namespace scansurf {

Nesting flatNesting(int featureCount) {
  Nesting nesting;
  for (int f = 0; f < featureCount; ++f) nesting.order.push_back(f);
  nesting.parent.assign(static_cast<std::size_t>(std::max(featureCount, 0)), -1);
  return nesting;
}

}  // namespace scansurf
