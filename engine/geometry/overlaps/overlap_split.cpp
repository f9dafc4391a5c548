// scansurf: the medial split of incidental overlaps: each shared voxel to the feature whose
// drawn outline is farther (exact in-plane distances to the contours), and the interface on
// the line where the two signed outline distances are equal (see overlap_split.h).
#include "geometry/overlaps/overlap_split.h"

#include "geometry/contours/polygon.h"

#include <algorithm>
#include <cmath>
#include <compare>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

namespace scansurf {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

// The segments of one feature's contours on one layer, filed under every grid row whose band
// (row centre ± half a pixel) they cross: the nearest segment to a point is then found by
// widening rings of rows until the rows left lie farther than the best distance found.
class OutlineIndex {
 public:
  OutlineIndex(const Feature& feature, const Grid& grid, int layer)
      : originY_(grid.originY), spacingY_(grid.spacingY), rows_(grid.ny) {
    std::vector<Segment> segments;
    for (const FeatureSlice& slice : feature.slices) {
      if (grid.layerOfPlane(slice.z) != layer) continue;
      contours_.insert(contours_.end(), slice.contours.begin(), slice.contours.end());
      for (const Contour& c : slice.contours)
        for (std::size_t p = 0; p < c.points.size(); ++p) segments.push_back({c.points[p], c.points[(p + 1) % c.points.size()]});
    }
    first_.assign(static_cast<std::size_t>(rows_) + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {  // count, then fill
      std::vector<std::size_t> at(first_.begin(), first_.end() - 1);
      for (const Segment& s : segments)
        for (int r = rowOf(std::min(s.a.y, s.b.y)); r <= rowOf(std::max(s.a.y, s.b.y)); ++r) {
          if (pass == 0)
            ++first_[static_cast<std::size_t>(r) + 1];
          else
            filed_[at[static_cast<std::size_t>(r)]++] = s;
        }
      if (pass == 0) {
        for (std::size_t r = 1; r < first_.size(); ++r) first_[r] += first_[r - 1];
        filed_.resize(first_.back());
      }
    }
  }

  // Distance from p (on row `row`) to the nearest segment, or kFar when none is within limit.
  double distance(Point2 p, double limit) const { return distance(p, rowOf(p.y), limit); }
  double distance(Point2 p, int row, double limit) const {
    double best = kFar;
    const auto scanRow = [&](int r) {
      if (r < 0 || r >= rows_) return;
      for (std::size_t s = first_[static_cast<std::size_t>(r)]; s < first_[static_cast<std::size_t>(r) + 1]; ++s)
        best = std::min(best, pointSegment(p, filed_[s]));
    };
    // Rows `ring` away from p's hold only points at least (ring - 0.5) pixels from it in y.
    for (int ring = 0; (ring - 0.5) * spacingY_ <= std::min(best, limit); ++ring) {
      if (row - ring < 0 && row + ring >= rows_) break;
      scanRow(row - ring);
      if (ring > 0) scanRow(row + ring);
    }
    return best <= limit ? best : kFar;
  }
  // Distance to the outline, positive inside the region (even-odd), negative outside.
  double signedDistance(Point2 p) const {
    const double d = distance(p, kFar);
    return insideRegion(contours_, p) ? d : -d;
  }

 private:
  struct Segment {
    Point2 a, b;
  };
  int rowOf(double y) const {
    // Clamped as a double first: a far point's row must not overflow an int.
    return static_cast<int>(std::clamp(std::floor((y - originY_) / spacingY_ + 0.5), 0.0, rows_ - 1.0));
  }
  static double pointSegment(Point2 p, const Segment& s) {
    const double dx = s.b.x - s.a.x, dy = s.b.y - s.a.y;
    const double length2 = dx * dx + dy * dy;
    double t = length2 > 0 ? ((p.x - s.a.x) * dx + (p.y - s.a.y) * dy) / length2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(p.x - (s.a.x + t * dx), p.y - (s.a.y + t * dy));
  }

  std::vector<Contour> contours_;
  double originY_, spacingY_;
  int rows_;
  std::vector<std::size_t> first_;  // per row, its first filed segment; rows_ + 1 entries
  std::vector<Segment> filed_;
};

// Outline indices built on first use, one per (feature, layer).
class Outlines {
 public:
  Outlines(const ContourSet& contours, const Grid& grid) : contours_(contours), grid_(grid) {}
  const OutlineIndex& of(int feature, int layer) {
    auto it = built_.find({feature, layer});
    if (it == built_.end())
      it = built_
               .emplace(std::pair{feature, layer},
                        OutlineIndex(contours_.features[static_cast<std::size_t>(feature)], grid_, layer))
               .first;
    return it->second;
  }
  Point2 centre(int i, int j) const { return {grid_.originX + i * grid_.spacingX, grid_.originY + j * grid_.spacingY}; }
  // The index if built, else null (for readers on several threads once all are built).
  const OutlineIndex* find(int feature, int layer) const {
    const auto it = built_.find({feature, layer});
    return it == built_.end() ? nullptr : &it->second;
  }

 private:
  const ContourSet& contours_;
  const Grid& grid_;
  std::map<std::pair<int, int>, OutlineIndex> built_;
};

// Calls visit(k, row, column) for every voxel two regions share, layer by layer.
template <typename Visit>
void forEachSharedVoxel(const FeatureRegion& a, const FeatureRegion& b, Visit&& visit) {
  forEachCommonLayer(a, b, [&](int k, const std::vector<PixelRun>& ra, const std::vector<PixelRun>& rb) {
    for (const PixelRun& r : intersectPixelRuns(ra, rb))
      for (int c = r.begin; c < r.end; ++c)
        if (!visit(k, r.row, c)) return false;
    return true;
  });
}

struct Voxel {
  int k = 0, row = 0, column = 0;
  auto operator<=>(const Voxel&) const = default;
};

// One connected region of a pair's shared voxels: face neighbours in a layer, and the same
// pixel on grid layers k and k + 1.
struct SharedRegion {
  std::vector<Voxel> voxels;
  double volume = 0;
};

std::size_t findRoot(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The connected regions of the voxels two features share, largest first (ties by first voxel).
std::vector<SharedRegion> sharedRegions(const FeatureRegion& a, const FeatureRegion& b, const Grid& grid) {
  std::vector<Voxel> voxels;
  forEachSharedVoxel(a, b, [&](int k, int row, int column) {
    voxels.push_back({k, row, column});
    return true;
  });
  std::sort(voxels.begin(), voxels.end());
  std::vector<std::size_t> parent(voxels.size());
  for (std::size_t i = 0; i < voxels.size(); ++i) parent[i] = i;
  for (std::size_t i = 0; i < voxels.size(); ++i) {
    const Voxel v = voxels[i];
    for (const Voxel n : {Voxel{v.k, v.row, v.column - 1}, Voxel{v.k, v.row - 1, v.column}, Voxel{v.k - 1, v.row, v.column}}) {
      const auto it = std::lower_bound(voxels.begin(), voxels.begin() + static_cast<std::ptrdiff_t>(i), n);
      if (it != voxels.begin() + static_cast<std::ptrdiff_t>(i) && *it == n)
        parent[findRoot(parent, static_cast<std::size_t>(it - voxels.begin()))] = findRoot(parent, i);
    }
  }
  std::map<std::size_t, std::size_t> regionOfRoot;
  std::vector<SharedRegion> out;
  for (std::size_t i = 0; i < voxels.size(); ++i) {
    const auto [it, added] = regionOfRoot.try_emplace(findRoot(parent, i), out.size());
    if (added) out.emplace_back();
    SharedRegion& r = out[it->second];
    r.voxels.push_back(voxels[i]);
    r.volume += voxelVolume(grid, voxels[i].k);
  }
  std::stable_sort(out.begin(), out.end(), [](const SharedRegion& x, const SharedRegion& y) { return x.volume > y.volume; });
  return out;
}

// The deepest voxel's distance to the nearer of the pair's outlines, when every one is within limit.
std::optional<double> depthWithin(const SharedVolume& pair, const SharedRegion& region, Outlines& outlines, double limit) {
  double depth = 0;
  for (const Voxel& v : region.voxels) {
    const Point2 p = outlines.centre(v.column, v.row);
    const double toA = outlines.of(pair.a, v.k).distance(p, v.row, limit);
    const double toB = outlines.of(pair.b, v.k).distance(p, v.row, std::min(toA, limit));
    const double nearer = std::min(toA, toB);
    if (nearer > limit) return std::nullopt;
    depth = std::max(depth, nearer);
  }
  return depth;
}

// The features of one surface layer per grid layer, for the covering test of a voxel.
std::vector<std::vector<int>> featuresByGridLayer(const std::vector<FeatureRegion>& regions, const OverlapReport& report,
                                                  int surfaceLayer, int gridLayers) {
  std::vector<std::vector<int>> out(static_cast<std::size_t>(gridLayers));
  for (std::size_t f = 0; f < regions.size(); ++f)
    if (report.features[f].layer == surfaceLayer)
      for (int k : regions[f].layers) out[static_cast<std::size_t>(k)].push_back(static_cast<int>(f));
  return out;
}

// Features of `candidates` whose region holds voxel (column, row, k).
std::vector<int> coveringFeatures(const std::vector<int>& candidates, const std::vector<FeatureRegion>& regions, int k, int row,
                                  int column) {
  std::vector<int> out;
  for (int f : candidates) {
    const FeatureRegion& r = regions[static_cast<std::size_t>(f)];
    if (row < r.minRow || row > r.maxRow || column < r.minColumn || column > r.maxColumn) continue;
    const auto at = std::lower_bound(r.layers.begin(), r.layers.end(), k);
    if (coversPixel(r.runs[static_cast<std::size_t>(at - r.layers.begin())], column, row)) out.push_back(f);
  }
  return out;
}

// Per unordered pair, the shared volume each side gave up, by record.
class GivenUp {
 public:
  explicit GivenUp(OverlapReport& report) : report_(report) {
    for (std::size_t s = 0; s < report.shared.size(); ++s) recordOf_[{report.shared[s].a, report.shared[s].b}] = s;
  }
  void add(int from, int to, double volume) {
    const auto it = recordOf_.find({std::min(from, to), std::max(from, to)});
    if (it == recordOf_.end()) return;
    SharedVolume& s = report_.shared[it->second];
    (from == s.a ? s.givenUpByA : s.givenUpByB) += volume;
  }

 private:
  OverlapReport& report_;
  std::map<std::pair<int, int>, std::size_t> recordOf_;
};

// One shared voxel of an incidental pair: the split's owner among the features holding it,
// appended to `overrides` when it is not the one scan conversion's priority picks.
struct VoxelSplit {
  const std::vector<FeatureRegion>& regions;
  const Nesting& nesting;
  const std::vector<int>& rank;  // position in nesting.order
  Outlines& outlines;
  GivenUp& givenUp;
  const Grid& grid;

  void operator()(const std::vector<int>& candidates, int k, int row, int column, std::vector<LabelOverride>& overrides) {
    const std::vector<int> holding = coveringFeatures(candidates, regions, k, row, column);
    const int painted = *std::min_element(holding.begin(), holding.end(), [&](int a, int b) { return rankOf(a) < rankOf(b); });
    // A feature holding another that holds the voxel leaves it to the inner one (the enclosing
    // convention); the others compete.
    std::vector<int> rivals;
    for (int f : holding)
      if (std::none_of(holding.begin(), holding.end(), [&](int g) { return g != f && isInside(nesting, g, f); }))
        rivals.push_back(f);
    if (rivals.size() < 2 || std::find(rivals.begin(), rivals.end(), painted) == rivals.end()) return;
    const Point2 p = outlines.centre(column, row);
    int owner = -1;
    double ownerDepth = -1;
    for (int f : rivals) {
      const double depth = outlines.of(f, k).distance(p, row, kFar);
      if (depth > ownerDepth || (depth == ownerDepth && rankOf(f) < rankOf(owner))) owner = f, ownerDepth = depth;
    }
    for (int f : rivals)
      if (f != owner) givenUp.add(f, owner, voxelVolume(grid, k));
    if (owner != painted) overrides.push_back({column, row, k, labelOfFeature(owner)});
  }
  int rankOf(int f) const { return rank[static_cast<std::size_t>(f)]; }
};

// The median distance between neighbouring layers (padding included: it repeats its neighbour's).
double medianLayerSpacing(const Grid& grid) {
  std::vector<double> gaps;
  for (std::size_t k = 1; k < grid.layerZ.size(); ++k) gaps.push_back(grid.layerZ[k] - grid.layerZ[k - 1]);
  if (gaps.empty()) return 0;
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  return gaps[gaps.size() / 2];
}

}  // namespace

double incidentalDepthLimit(const OverlapTolerance& tolerance, const Grid& grid) {
  if (tolerance.depth > 0) return tolerance.depth;
  return std::max(2.0 * std::max(grid.spacingX, grid.spacingY), 0.5 * medianLayerSpacing(grid));
}

void judgeOverlaps(const ContourSet& contours, const Grid& grid, const std::vector<FeatureRegion>& regions,
                   const OverlapTolerance& tolerance, OverlapReport& report) {
  report.tolerance = tolerance;
  if (!tolerance.enabled) return;
  Outlines outlines(contours, grid);
  const double limit = incidentalDepthLimit(tolerance, grid);
  for (SharedVolume& s : report.shared) {
    if (s.nested) continue;
    const double smaller = std::min(report.features[static_cast<std::size_t>(s.a)].ownVolume,
                                    report.features[static_cast<std::size_t>(s.b)].ownVolume);
    const double thin = 0.01 * tolerance.percent * smaller, tiny = thin / 2;
    const std::vector<SharedRegion> parts =
        sharedRegions(regions[static_cast<std::size_t>(s.a)], regions[static_cast<std::size_t>(s.b)], grid);
    s.regions = static_cast<int>(parts.size());
    s.largestRegion = parts.empty() ? 0 : parts.front().volume;
    s.incidental = s.depthMeasured = !parts.empty() && s.volume <= thin;
    s.depth = 0;
    for (std::size_t r = 0; r < parts.size() && s.incidental; ++r) {
      const std::optional<double> depth = depthWithin(s, parts[r], outlines, limit);
      s.depth = std::max(s.depth, depth.value_or(0));
      s.depthMeasured = s.depthMeasured && depth.has_value();
      s.incidental = depth.has_value() || parts[r].volume <= tiny;
    }
    if (!s.incidental) s.depthMeasured = false, s.depth = 0;
  }
}

std::vector<std::vector<LabelOverride>> splitIncidentalOverlaps(const ContourSet& contours, const Grid& grid,
                                                                const Nesting& nesting, const std::vector<FeatureRegion>& regions,
                                                                OverlapReport& report) {
  std::vector<std::vector<LabelOverride>> overrides(static_cast<std::size_t>(report.layers));
  // The shared voxels of incidental pairs per surface layer, once each (a voxel three
  // features share is in three pairs).
  std::vector<std::vector<std::tuple<int, int, int>>> voxels(overrides.size());
  for (const SharedVolume& s : report.shared) {
    const int layer = report.features[static_cast<std::size_t>(s.a)].layer;
    if (!s.incidental || report.features[static_cast<std::size_t>(s.b)].layer != layer) continue;
    forEachSharedVoxel(regions[static_cast<std::size_t>(s.a)], regions[static_cast<std::size_t>(s.b)],
                       [&](int k, int row, int column) {
                         voxels[static_cast<std::size_t>(layer)].emplace_back(k, row, column);
                         return true;
                       });
  }
  std::vector<int> rank(regions.size(), 0);
  for (std::size_t p = 0; p < nesting.order.size(); ++p) rank[static_cast<std::size_t>(nesting.order[p])] = static_cast<int>(p);
  Outlines outlines(contours, grid);
  GivenUp givenUp(report);
  VoxelSplit split{regions, nesting, rank, outlines, givenUp, grid};
  for (std::size_t layer = 0; layer < voxels.size(); ++layer) {
    if (voxels[layer].empty()) continue;
    std::sort(voxels[layer].begin(), voxels[layer].end());
    voxels[layer].erase(std::unique(voxels[layer].begin(), voxels[layer].end()), voxels[layer].end());
    const std::vector<std::vector<int>> candidates = featuresByGridLayer(regions, report, static_cast<int>(layer), grid.nz);
    for (const auto& [k, row, column] : voxels[layer])
      split(candidates[static_cast<std::size_t>(k)], k, row, column, overrides[layer]);
  }
  return overrides;
}

std::vector<std::pair<std::size_t, Label>> overridesOnGrid(const Grid& sub, const Grid& grid,
                                                           const std::vector<LabelOverride>& overrides) {
  const int i0 = static_cast<int>(std::lround((sub.originX - grid.originX) / grid.spacingX));
  const int j0 = static_cast<int>(std::lround((sub.originY - grid.originY) / grid.spacingY));
  const int k0 = static_cast<int>(std::find(grid.layerZ.begin(), grid.layerZ.end(), sub.layerZ.front()) - grid.layerZ.begin());
  std::vector<std::pair<std::size_t, Label>> out;
  for (const LabelOverride& o : overrides) {
    const int i = o.i - i0, j = o.j - j0, k = o.k - k0;
    if (i >= 0 && j >= 0 && k >= 0 && i < sub.nx && j < sub.ny && k < sub.nz) out.emplace_back(sub.index(i, j, k), o.label);
  }
  return out;
}

struct MedialCrossings::State {
  Grid grid;
  Outlines outlines;
  std::set<std::pair<Label, Label>> pairs;  // label pairs, smaller first
  State(const ContourSet& contours, const Grid& g) : grid(g), outlines(contours, grid) {}
};

MedialCrossings::MedialCrossings() = default;
MedialCrossings::MedialCrossings(MedialCrossings&&) noexcept = default;
MedialCrossings& MedialCrossings::operator=(MedialCrossings&&) noexcept = default;
MedialCrossings::~MedialCrossings() = default;

MedialCrossings::MedialCrossings(const ContourSet& contours, const Grid& grid, const OverlapReport& report) {
  auto state = std::make_unique<State>(contours, grid);
  for (const SharedVolume& s : report.shared) {
    if (!s.incidental ||
        report.features[static_cast<std::size_t>(s.a)].layer != report.features[static_cast<std::size_t>(s.b)].layer)
      continue;
    state->pairs.insert({labelOfFeature(s.a), labelOfFeature(s.b)});
    for (int f : {s.a, s.b})  // built now: read by several threads later
      for (const FeatureSlice& slice : contours.features[static_cast<std::size_t>(f)].slices)
        if (const int k = state->grid.layerOfPlane(slice.z); k >= 0) state->outlines.of(f, k);
  }
  if (!state->pairs.empty()) state_ = std::move(state);
}

bool MedialCrossings::empty() const { return !state_; }

bool MedialCrossings::separates(Label a, Label b) const {
  return state_ && a != b && state_->pairs.count({std::min(a, b), std::max(a, b)}) > 0;
}

double MedialCrossings::crossing(Label a, Label b, double z, Point2 p, Point2 q) const {
  if (!separates(a, b)) return -1;
  const int k = state_->grid.layerOfPlane(z);
  const OutlineIndex* outlineA = k < 0 ? nullptr : state_->outlines.find(featureOfLabel(a), k);
  const OutlineIndex* outlineB = k < 0 ? nullptr : state_->outlines.find(featureOfLabel(b), k);
  if (!outlineA || !outlineB) return -1;
  const double mp = outlineA->signedDistance(p) - outlineB->signedDistance(p);
  const double mq = outlineA->signedDistance(q) - outlineB->signedDistance(q);
  if ((mp > 0 && mq > 0) || (mp < 0 && mq < 0)) return -1;
  return mp == mq ? 0.5 : mp / (mp - mq);
}

}  // namespace scansurf
