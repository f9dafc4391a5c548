// scansurf: the plan of multi-label shape-based interpolation (see interpolation_plan.h;
// Raya & Udupa 1990, Grevera & Udupa 1996).
#include "geometry/interpolation/interpolation_plan.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "core/blend_rules.h"
#include "core/parallel.h"

namespace scansurf {

std::vector<int> interpolationFactors(const Grid& grid, const InterpolationOptions& options) {
  const std::size_t gaps = grid.nz > 1 ? static_cast<std::size_t>(grid.nz - 1) : 0;
  if (options.factor != InterpolationOptions::kAuto)
    return std::vector<int>(gaps, std::clamp(options.factor, 1, InterpolationOptions::kMaxFactor));
  const double pixel = std::min(grid.spacingX, grid.spacingY);
  std::vector<int> wanted(gaps);
  for (std::size_t k = 0; k < gaps; ++k) {
    const double n = std::round((grid.layerZ[k + 1] - grid.layerZ[k]) / pixel);
    // Below three pixels a gap gains too little for the larger volume: one layer in gaps of two
    // pixels made the benchmark pelvis at 512 pixels (2 mm slices) 6 times slower for 4.9 ->
    // 4.1 degrees of the sphere's normals at 1.5 mm pixels.
    wanted[k] =
        n < InterpolationOptions::kAutoMinimum ? 1 : static_cast<int>(std::min(n, double{InterpolationOptions::kMaxFactor}));
  }
  // Lower the largest factors until the volume fits the limit; below kAutoMinimum, none.
  const std::uint64_t plane = static_cast<std::uint64_t>(grid.nx) * static_cast<std::uint64_t>(grid.ny);
  for (int cap = InterpolationOptions::kMaxFactor; cap >= InterpolationOptions::kAutoMinimum; --cap) {
    std::uint64_t layers = 1;
    for (int n : wanted) layers += static_cast<std::uint64_t>(std::min(n, cap));
    if (layers * plane <= options.autoVoxelLimit) {
      for (int& n : wanted) n = std::min(n, cap);
      return wanted;
    }
  }
  return std::vector<int>(gaps, 1);
}

bool interpolates(const std::vector<int>& factors) {
  return std::any_of(factors.begin(), factors.end(), [](int n) { return n > 1; });
}

std::vector<int> fineLayerOfPlane(const std::vector<int>& factors) {
  std::vector<int> fine(factors.size() + 1, 0);
  for (std::size_t k = 0; k < factors.size(); ++k) fine[k + 1] = fine[k] + factors[k];
  return fine;
}

Grid interpolatedGrid(const Grid& grid, const std::vector<int>& factors) {
  Grid fine = grid;
  fine.layerZ.clear();
  for (std::size_t k = 0; k < factors.size(); ++k)
    for (int m = 0; m < factors[k]; ++m)
      fine.layerZ.push_back(m == 0 ? grid.layerZ[k] : grid.layerZ[k] + (grid.layerZ[k + 1] - grid.layerZ[k]) * m / factors[k]);
  if (!grid.layerZ.empty()) fine.layerZ.push_back(grid.layerZ.back());
  fine.nz = static_cast<int>(fine.layerZ.size());
  return fine;
}

Result<DistanceWeights> distanceWeights(const Grid& grid) {
  const double s = std::min(grid.spacingX, grid.spacingY);
  const bool square = std::abs(grid.spacingX - grid.spacingY) <= 1e-9 * std::max(grid.spacingX, grid.spacingY);
  const double rx = square ? 1.0 : (grid.spacingX / s) * (grid.spacingX / s),
               ry = square ? 1.0 : (grid.spacingY / s) * (grid.spacingY / s);
  // Every distance along a line is at most `side` pixels; every squared term must stay below 2^30.
  const double side = std::max(grid.nx, grid.ny) + 1.0;
  for (std::int32_t k = square ? 1 : 64; k >= 1; k /= 2)
    for (std::int32_t unit = 16; unit >= 1; unit /= 2) {
      if (unit * unit * k > 256) continue;
      DistanceWeights w;
      w.x = static_cast<std::int32_t>(std::max(1.0, std::round(k * rx)));
      w.y = static_cast<std::int32_t>(std::max(1.0, std::round(k * ry)));
      w.unit = unit;
      w.fixedScale = static_cast<std::uint32_t>(256 / (unit * unit * k));
      if (std::max(w.x, w.y) * std::pow(unit * side, 2.0) < static_cast<double>(1 << 30)) return w;
    }
  return makeError(Errc::InvalidArgument, "interpolation: pixels of " + std::to_string(grid.spacingX) + " x " +
                                              std::to_string(grid.spacingY) + " on a grid of " + std::to_string(grid.nx) + " x " +
                                              std::to_string(grid.ny) +
                                              " are too elongated for exact distances; turn interpolation off");
}

std::int32_t deepDistance(const Grid& grid) {
  const double ratio = std::max(grid.spacingX, grid.spacingY) / std::min(grid.spacingX, grid.spacingY);
  return static_cast<std::int32_t>(4 * kFieldPixel * std::ceil(ratio - 1e-9));
}

std::size_t InterpolationBatch::deviceBytes(const Grid& grid) const {
  const std::size_t plane = static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny);
  return plane * static_cast<std::size_t>(planes) * sizeof(Label) + (fieldValues + scratchInts + fields.size()) * 4 +
         plane * static_cast<std::size_t>(outputLayers) * 4 + (tileRanges.size() + tileEntries.size()) * 4 +
         entries.size() * sizeof(shared::PairEntry);
}

namespace {

void include(LabelCensus& c, int x, int y) {
  c.x0 = std::min(c.x0, x), c.y0 = std::min(c.y0, y), c.x1 = std::max(c.x1, x), c.y1 = std::max(c.y1, y);
  ++c.count, c.sumX += x, c.sumY += y;
}

std::vector<LabelCensus> censusOfLayer(const LabelVolume& volume, int k, std::vector<int>& slot) {
  const Grid& g = volume.grid;
  std::vector<LabelCensus> found(1);
  found[0].x0 = g.nx, found[0].y0 = g.ny;
  const Label* labels = volume.labels.data() + g.index(0, 0, k);
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) {
      const Label l = labels[x + static_cast<std::size_t>(g.nx) * y];
      if (l == kBackground) continue;
      if (slot[l] < 0) {
        slot[l] = static_cast<int>(found.size());
        found.push_back({l, g.nx, g.ny, -1, -1, 0, 0, 0});
      }
      include(found[static_cast<std::size_t>(slot[l])], x, y);
      include(found[0], x, y);
    }
  for (const LabelCensus& c : found)
    if (c.label != kBackground) slot[c.label] = -1;
  std::sort(found.begin() + 1, found.end(), [](const LabelCensus& a, const LabelCensus& b) { return a.label < b.label; });
  if (found[0].count == 0) found.clear();
  return found;
}

const LabelCensus* find(const std::vector<LabelCensus>& layer, Label label) {
  auto it = std::lower_bound(layer.begin(), layer.end(), label, [](const LabelCensus& c, Label l) { return c.label < l; });
  return it != layer.end() && it->label == label ? &*it : nullptr;
}

struct Box {
  int x0, y0, x1, y1;
  void add(const LabelCensus& c) {
    x0 = std::min(x0, c.x0), y0 = std::min(y0, c.y0), x1 = std::max(x1, c.x1), y1 = std::max(y1, c.y1);
  }
};

// The window of label's field on layer k: its pixels on k and both neighbours, with a margin.
Box fieldWindow(const Grid& g, const PlaneCensus& census, int k, Label label) {
  Box b{g.nx, g.ny, -1, -1};
  for (int j = std::max(0, k - 1); j <= std::min(g.nz - 1, k + 1); ++j)
    if (const LabelCensus* c = find(census[static_cast<std::size_t>(j)], label)) b.add(*c);
  return {std::max(0, b.x0 - kWindowMargin), std::max(0, b.y0 - kWindowMargin), std::min(g.nx - 1, b.x1 + kWindowMargin),
          std::min(g.ny - 1, b.y1 + kWindowMargin)};
}

// Whether `label` has a pixel on both layers a and a+1.
std::vector<bool> overlappingLabels(const LabelVolume& volume, int a) {
  const Grid& g = volume.grid;
  std::vector<bool> overlap(65536, false);
  const Label* la = volume.labels.data() + g.index(0, 0, a);
  const Label* lb = la + static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  for (std::size_t i = 0, n = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny); i < n; ++i)
    if (la[i] == lb[i]) overlap[la[i]] = true;
  return overlap;
}

int roundHalfAway(double v) { return static_cast<int>(std::lround(v)); }

// Gap j alike in length to gap k (layers k, k + 1): within a quarter of it either way, where the
// same tangents fit both sides of their common plane.
bool alikeGap(const Grid& g, int k, int j) {
  if (j < 0 || j + 1 >= g.nz) return false;
  const double gap = g.layerZ[static_cast<std::size_t>(k + 1)] - g.layerZ[static_cast<std::size_t>(k)];
  const double other = g.layerZ[static_cast<std::size_t>(j + 1)] - g.layerZ[static_cast<std::size_t>(j)];
  return alikeGaps(gap, other);
}

class BatchPlanner {
 public:
  BatchPlanner(const LabelVolume& volume, const PlaneCensus& census, const std::vector<bool>& containers,
               InterpolationBatch& batch)
      : g_(volume.grid), volume_(volume), census_(census), containers_(containers), batch_(batch) {}

  // Every label's field on each plane; on a halo plane, only those of labels on its neighbour.
  void addFields() {
    for (int p = 0; p < batch_.planes; ++p) {
      const int k = batch_.firstPlane + p;
      const bool halo = p < batch_.haloBefore || p >= batch_.planes - batch_.haloAfter;
      // Only a halo plane has a neighbour to consult; an inner first plane (k = 0) has none below.
      const std::vector<LabelCensus>* neighbour =
          halo ? &census_[static_cast<std::size_t>(p < batch_.haloBefore ? k + 1 : k - 1)] : nullptr;
      planeFields_.push_back(batch_.fields.size());
      for (const LabelCensus& c : census_[static_cast<std::size_t>(k)]) {
        if (neighbour && !find(*neighbour, c.label)) continue;
        const Box b = fieldWindow(g_, census_, k, c.label);
        shared::DistanceField f{b.x0, b.y0, b.x1 - b.x0 + 1, b.y1 - b.y0 + 1, p, c.label, 0, 0};
        const std::size_t area = static_cast<std::size_t>(f.w) * static_cast<std::size_t>(f.h);
        f.offset = static_cast<std::int32_t>(batch_.fieldValues);
        f.scratch = static_cast<std::int32_t>(batch_.scratchInts);
        batch_.fieldValues += area;
        batch_.scratchInts += 7 * area + static_cast<std::size_t>(f.w + f.h);
        batch_.fields.push_back(f);
      }
    }
  }

  void addPair(int p, int factor) {
    const int k = batch_.firstPlane + p;
    const bool last = k + 2 == g_.nz;  // plane B is the volume's last layer: its clearance too
    shared::PairPlan pair{p, factor, batch_.outputLayers, static_cast<std::int32_t>(batch_.tileRanges.size() / 2),
                          factor + (last ? 1 : 0)};
    batch_.outputLayers += pair.layers;
    const std::size_t firstEntry = batch_.entries.size();
    addEntries(p, k);
    markTouchingCaps(k, firstEntry);
    addLayerTables(firstEntry, k, factor);
    addTiles(firstEntry);
    batch_.pairs.push_back(pair);
  }

 private:
  // Fields are in plane order, each plane's by label.
  int fieldOf(int p, Label label) const {
    const auto first = batch_.fields.begin() + static_cast<std::ptrdiff_t>(planeFields_[static_cast<std::size_t>(p)]);
    const auto last = static_cast<std::size_t>(p + 1) < planeFields_.size()
                          ? batch_.fields.begin() + static_cast<std::ptrdiff_t>(planeFields_[static_cast<std::size_t>(p + 1)])
                          : batch_.fields.end();
    const auto it = std::lower_bound(first, last, label, [](const shared::DistanceField& f, Label l) { return f.label < l; });
    return it != last && it->label == label ? static_cast<int>(it - batch_.fields.begin()) : -1;
  }

  void addEntries(int p, int k) {
    const auto& a = census_[static_cast<std::size_t>(k)];
    const auto& b = census_[static_cast<std::size_t>(k + 1)];
    std::vector<Label> labels;
    for (const LabelCensus& c : a) labels.push_back(c.label);
    for (const LabelCensus& c : b) labels.push_back(c.label);
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    std::vector<bool> overlap;
    for (Label label : labels) {
      shared::PairEntry e{label, fieldOf(p, label), fieldOf(p + 1, label), 0, 0, g_.nx, g_.ny, -1, -1, 0, -1, -1, -1};
      for (int f : {e.fieldA, e.fieldB}) {
        if (f < 0) continue;
        const shared::DistanceField& d = batch_.fields[static_cast<std::size_t>(f)];
        e.x0 = std::min(e.x0, d.x0), e.y0 = std::min(e.y0, d.y0);
        e.x1 = std::max(e.x1, d.x0 + d.w - 1), e.y1 = std::max(e.y1, d.y0 + d.h - 1);
      }
      if (label != kBackground && e.fieldA >= 0 && e.fieldB >= 0) {
        if (overlap.empty()) overlap = overlappingLabels(volume_, k);
        if (!overlap[label]) {
          const LabelCensus& ca = *find(a, label);
          const LabelCensus& cb = *find(b, label);
          e.shiftX = roundHalfAway(static_cast<double>(cb.sumX) / static_cast<double>(cb.count) -
                                   static_cast<double>(ca.sumX) / static_cast<double>(ca.count));
          e.shiftY = roundHalfAway(static_cast<double>(cb.sumY) / static_cast<double>(cb.count) -
                                   static_cast<double>(ca.sumY) / static_cast<double>(ca.count));
        }
      }
      addBends(e, p, k);
      batch_.entries.push_back(e);
    }
  }

  // The fields before plane A and after plane B that bend a label's blend across its planes.
  void addBends(shared::PairEntry& e, int p, int k) const {
    e.fieldBefore = e.fieldAfter = -1;
    if (e.fieldA < 0 || e.fieldB < 0 || e.shiftX != 0 || e.shiftY != 0) return;
    if (p > 0 && alikeGap(g_, k, k - 1)) e.fieldBefore = fieldOf(p - 1, static_cast<Label>(e.label));
    if (p + 2 < batch_.planes && alikeGap(g_, k, k + 1)) e.fieldAfter = fieldOf(p + 2, static_cast<Label>(e.label));
  }

  // Each feature's entry gets its place for factor + 1 values in the layer table: area-keeping
  // offsets on both planes (not for a container: see planInterpolationBatch), dome erosions on
  // one plane only. The union has none: one offset for several features grew one at another's
  // cost, and a union's dome, sized by every feature's area together, grew the largest cap.
  void addLayerTables(std::size_t first, int k, int factor) {
    for (std::size_t i = first; i < batch_.entries.size(); ++i) {
      shared::PairEntry& e = batch_.entries[i];
      const bool both = e.fieldA >= 0 && e.fieldB >= 0;
      if (e.label == kBackground || (both && (factor < 2 || contains(static_cast<Label>(e.label))))) continue;
      e.layerTable = static_cast<std::int32_t>(batch_.layerInts);
      if (both)
        batch_.blendedEntries.push_back({i, factor, batch_.layerInts});
      else
        batch_.cappedEntries.push_back({e.fieldA >= 0 ? e.fieldA : e.fieldB, factor, batch_.layerInts,
                                        e.fieldA >= 0 ? capTaper(g_, census_, static_cast<Label>(e.label), k, k - 1, k + 1)
                                                      : capTaper(g_, census_, static_cast<Label>(e.label), k + 1, k + 2, k)});
      batch_.layerInts += static_cast<std::size_t>(factor) + 1;
    }
  }

  // Labels that end at this pair (present on one plane only) and touch another such label on
  // their plane get flat caps; so do a label that ends on plane A and one that begins on plane
  // B over it, whose domes (each as high as the whole gap) would overlap: flat caps meet at
  // half the gap, each keeping its own half slab.
  void markTouchingCaps(int k, std::size_t first) {
    std::vector<char> endsA(65536, 0), endsB(65536, 0);
    bool any = false;
    for (std::size_t i = first; i < batch_.entries.size(); ++i) {
      const shared::PairEntry& e = batch_.entries[i];
      if (e.label == kBackground) continue;
      if (e.fieldB < 0) endsA[static_cast<std::size_t>(e.label)] = 1, any = true;
      if (e.fieldA < 0) endsB[static_cast<std::size_t>(e.label)] = 1, any = true;
    }
    if (!any) return;
    std::vector<char> touching(65536, 0);
    markTouching(k, endsA, touching);
    markTouching(k + 1, endsB, touching);
    for (int y = 0; y < g_.ny; ++y)
      for (int x = 0; x < g_.nx; ++x) {
        const Label a = volume_.at(x, y, k), b = volume_.at(x, y, k + 1);
        if (endsA[a] && endsB[b]) touching[a] = touching[b] = 1;
      }
    for (std::size_t i = first; i < batch_.entries.size(); ++i)
      if (touching[static_cast<std::size_t>(batch_.entries[i].label)]) batch_.entries[i].flatCap = 1;
  }

  void markTouching(int k, const std::vector<char>& ends, std::vector<char>& touching) const {
    for (int y = 0; y + 1 < g_.ny; ++y)
      for (int x = 0; x + 1 < g_.nx; ++x) {
        const Label a = volume_.at(x, y, k);
        if (!ends[a]) continue;
        for (const Label b : {volume_.at(x + 1, y, k), volume_.at(x, y + 1, k)})
          if (b != a && ends[b]) touching[a] = touching[b] = 1;
      }
  }

  void addTiles(std::size_t firstEntry) {
    const int tiles = batch_.tilesX * batch_.tilesY;
    std::vector<std::vector<std::int32_t>> lists(static_cast<std::size_t>(tiles));
    for (std::size_t i = firstEntry; i < batch_.entries.size(); ++i) {
      const shared::PairEntry& e = batch_.entries[i];
      for (int ty = e.y0 / kTileSize; ty <= e.y1 / kTileSize; ++ty)
        for (int tx = e.x0 / kTileSize; tx <= e.x1 / kTileSize; ++tx)
          lists[static_cast<std::size_t>(tx + batch_.tilesX * ty)].push_back(static_cast<std::int32_t>(i));
    }
    for (const auto& list : lists) {
      const bool moving = std::any_of(list.begin(), list.end(), [&](std::int32_t i) {
        const shared::PairEntry& e = batch_.entries[static_cast<std::size_t>(i)];
        return e.shiftX != 0 || e.shiftY != 0;
      });
      batch_.tileRanges.push_back(static_cast<std::int32_t>(batch_.tileEntries.size()));
      batch_.tileRanges.push_back(static_cast<std::int32_t>(list.size()) | (moving ? kMovingTile : 0));
      batch_.tileEntries.insert(batch_.tileEntries.end(), list.begin(), list.end());
    }
  }

  const Grid& g_;
  const LabelVolume& volume_;
  const PlaneCensus& census_;
  const std::vector<bool>& containers_;
  InterpolationBatch& batch_;
  std::vector<std::size_t> planeFields_;  // first field of each plane

  bool contains(Label label) const { return label < containers_.size() && containers_[label]; }
};

}  // namespace

std::size_t estimatePlaneBytes(const LabelVolume& volume, const PlaneCensus& census, int k, int factor) {
  const Grid& g = volume.grid;
  const std::size_t plane = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  std::size_t bytes = plane * (sizeof(Label) + sizeof(std::uint16_t)) + plane * static_cast<std::size_t>(factor + 1) * 4;
  for (const LabelCensus& c : census[static_cast<std::size_t>(k)]) {
    const Box b = fieldWindow(g, census, k, c.label);
    const std::size_t w = static_cast<std::size_t>(b.x1 - b.x0 + 1), h = static_cast<std::size_t>(b.y1 - b.y0 + 1);
    bytes += (8 * w * h + w + h) * 4 + 64;  // values and scratch, plus entries and tiles
  }
  return bytes;
}

PlaneCensus takePlaneCensus(const LabelVolume& volume, int threads) {
  PlaneCensus census(static_cast<std::size_t>(std::max(0, volume.grid.nz)));
  parallelChunks(census.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    std::vector<int> slot(65536, -1);
    for (std::size_t k = begin; k < end; ++k) census[k] = censusOfLayer(volume, static_cast<int>(k), slot);
  });
  return census;
}

InterpolationBatch planInterpolationBatch(const LabelVolume& volume, const PlaneCensus& census, int firstPlane, int planes,
                                          const std::vector<int>& factors, const std::vector<bool>& containers) {
  InterpolationBatch batch;
  batch.haloBefore = firstPlane > 0 ? 1 : 0;
  batch.haloAfter = firstPlane + planes < volume.grid.nz ? 1 : 0;
  batch.firstPlane = firstPlane - batch.haloBefore;
  batch.planes = planes + batch.haloBefore + batch.haloAfter;
  batch.tilesX = (volume.grid.nx + kTileSize - 1) / kTileSize;
  batch.tilesY = (volume.grid.ny + kTileSize - 1) / kTileSize;
  batch.blendLimits = {deepDistance(volume.grid) * 3 / 4, deepDistance(volume.grid) * 4};
  BatchPlanner planner(volume, census, containers, batch);
  planner.addFields();
  for (int p = batch.haloBefore; p + 1 < batch.planes - batch.haloAfter; ++p)
    planner.addPair(p, factors[static_cast<std::size_t>(batch.firstPlane + p)]);
  return batch;
}

namespace {

// The dome's layers follow the round cap's profile (core/blend_rules.h). A paraboloid holds the
// half slab too but must stand a whole gap high: a sphere's pole, which lies less than half a
// gap beyond its last plane, was overshot twice as far, so only a structure that tapered as fast
// toward its end plane gets it.
double domeFraction(const RoundCapProfile& dome, int m, int factor) {
  const double u = m / (dome.height * factor);
  return std::max(0.0, 1 - dome.slope * u - (1 - dome.slope) * u * u);
}

// The last layer a dome of n layers is open on, and how far beyond it its tip stands (in
// layers, at most 1): at H, not on the next layer.
int domeTop(const RoundCapProfile& dome, int factor) { return static_cast<int>(std::ceil(dome.height * factor)) - 1; }
double domeTipHeight(const RoundCapProfile& dome, int factor) { return dome.height * factor - domeTop(dome, factor); }

// The surface between two layers of a dome is close to a frustum (its cross-sections are the
// label's region eroded, alike in shape): h (a + sqrt(a b) + b) / 3, less than the trapezoid
// h (a + b) / 2 that the fractions integrate. The areas of the dome's layers are scaled by the
// factor that makes the frusta and the tip's cone hold half a gap, the flat half slab (a few
// per cent).
double domeAreaScale(const RoundCapProfile& dome, int factor) {
  const int top = domeTop(dome, factor);
  const auto volume = [&](double scale) {
    double v = 0;
    for (int m = 0; m < top; ++m) {
      const double a = m == 0 ? 1.0 : std::min(1.0, scale * domeFraction(dome, m, factor));
      const double b = std::min(1.0, scale * domeFraction(dome, m + 1, factor));
      v += (a + std::sqrt(a * b) + b) / 3;
    }
    const double last = top == 0 ? 1.0 : std::min(1.0, scale * domeFraction(dome, top, factor));
    return v + domeTipHeight(dome, factor) * last / 3;  // in layer spacings, with the tip's cone
  };
  double lo = 0.5, hi = 2;
  for (int i = 0; i < 50; ++i) (volume(0.5 * (lo + hi)) < 0.5 * factor ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

// A label's area in pixels read off its signed distances v less `shift` (1/unit pixel), each
// pixel's cover clamp(1/2 - d, 0, 1): the contours' sub-pixel crossings count, where a pixel
// count is a few per cent short on thin or lattice-aligned outlines.
double coveredArea(const std::int32_t* values, std::size_t count, double unit, std::int32_t shift = 0) {
  double area = 0;
  for (std::size_t i = 0; i < count; ++i) area += std::clamp(0.5 - (values[i] - shift) / unit, 0.0, 1.0);
  return area;
}

// The offset in [-shrink, grow] at which the band's values less the offset cover `want`
// pixels (values in 1/unit pixel): the cover grows with the offset, so bisect.
std::int32_t offsetCovering(const std::vector<std::int32_t>& band, double want, double unit, std::int32_t shrink,
                            std::int32_t grow) {
  std::int32_t lo = -shrink, hi = grow;
  while (hi - lo > 1) {
    const std::int32_t mid = lo + (hi - lo) / 2;
    (coveredArea(band.data(), band.size(), unit, mid) < want ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace

std::int32_t blendedValue(const shared::PairEntry& e, const BlendFields& f, int m, int n, int x, int y) {
  const std::int32_t sx = roundDiv(m * e.shiftX, n), sy = roundDiv(m * e.shiftY, n);
  const std::int32_t a = fieldValue(*f.field[1], f.values[1], x - sx, y - sy);
  const std::int32_t b = fieldValue(*f.field[2], f.values[2], x + e.shiftX - sx, y + e.shiftY - sy);
  if (a == kFarAway || b == kFarAway) return kFarAway;
  const std::int32_t chord = b - a;
  std::int32_t tangentA = chord, tangentB = chord;
  if (f.field[0]) {
    const std::int32_t before = fieldValue(*f.field[0], f.values[0], x, y);
    if (before != kFarAway) tangentA = shared::bendTangent(a - before, chord);
  }
  if (f.field[3]) {
    const std::int32_t after = fieldValue(*f.field[3], f.values[3], x, y);
    if (after != kFarAway) tangentB = shared::bendTangent(chord, after - b);
  }
  return (n - m) * a + m * b + shared::hermiteBend(tangentA, tangentB, chord, m, n);
}

namespace {

// The area at layer m of n on the monotone cubic through the areas before A, on A, on B and
// after B (negative: no such plane, linear at that end), as blendedValue bends the fields.
double blendedArea(const double (&area)[4], int m, int n) {
  const double chord = area[2] - area[1];
  const double tangentA = area[0] >= 0 ? monotoneTangent(area[1] - area[0], chord) : chord;
  const double tangentB = area[3] >= 0 ? monotoneTangent(chord, area[3] - area[2]) : chord;
  const double t = static_cast<double>(m) / n;
  const double cubic = hermiteBlend(area[1], area[2], tangentA, tangentB, t);
  // The cubic holds (tangentA - tangentB) / 12 of an area over the gap beyond the trapezoid;
  // 30 t^2 (1 - t)^2 holds 1 and leaves the ends' values and slopes as they are.
  return cubic - 30 * t * t * (1 - t) * (1 - t) * (tangentA - tangentB) / 12;
}

double fieldArea(const shared::DistanceField* f, const std::int32_t* values) {
  if (!f || !values) return -1;
  return coveredArea(values, static_cast<std::size_t>(f->w) * static_cast<std::size_t>(f->h), kFieldPixel);
}

}  // namespace

void blendOffsets(const shared::PairEntry& e, const BlendFields& fields, int factor, InterpolationBatch::OffsetLimits limits,
                  std::int32_t* out) {
  const int n = factor;
  constexpr double unit = kFieldPixel;
  out[0] = out[n] = 0;
  double area[4];
  for (int i = 0; i < 4; ++i) area[i] = fieldArea(fields.field[i], fields.values[i]);
  const shared::DistanceField &fieldA = *fields.field[1], &fieldB = *fields.field[2];
  const std::int32_t sure = std::max(limits.shrink, limits.grow) + kFieldPixel;  // beyond: covered, or not, whatever the offset
  std::vector<std::int32_t> band;
  for (int m = 1; m < n; ++m) {
    // As the interpolation samples a shifting label (interpolate.comp, entryValue).
    const std::int32_t sx = roundDiv(m * e.shiftX, n), sy = roundDiv(m * e.shiftY, n);
    std::int64_t inside = 0;
    band.clear();
    for (int y = e.y0; y <= e.y1; ++y)
      for (int x = e.x0; x <= e.x1; ++x) {
        const std::int32_t a = fieldValue(fieldA, fields.values[1], x - sx, y - sy);
        const std::int32_t b = fieldValue(fieldB, fields.values[2], x + e.shiftX - sx, y + e.shiftY - sy);
        if (a == kFarAway || b == kFarAway || std::min(a, b) > sure) continue;
        if (std::max(a, b) < -sure)  // the bent blend stays between a and b
          ++inside;
        else
          band.push_back(blendedValue(e, fields, m, n, x, y));
      }
    const double want = blendedArea(area, m, n) - static_cast<double>(inside);
    out[m] = offsetCovering(band, want, n * unit, n * limits.shrink, n * limits.grow);
  }
}

BlendFields blendFields(const InterpolationBatch& batch, const shared::PairEntry& e,
                        const std::vector<const std::int32_t*>& fieldValues) {
  BlendFields out;
  const int fields[4] = {e.fieldBefore, e.fieldA, e.fieldB, e.fieldAfter};
  for (int i = 0; i < 4; ++i) {
    if (fields[i] < 0) continue;
    out.field[i] = &batch.fields[static_cast<std::size_t>(fields[i])];
    out.values[i] = fieldValues[static_cast<std::size_t>(fields[i])];
  }
  return out;
}

std::vector<std::int32_t> buildLayerTable(const InterpolationBatch& batch, const std::vector<const std::int32_t*>& fieldValues,
                                          int threads) {
  std::vector<std::int32_t> table(batch.layerInts, -1);
  const std::size_t caps = batch.cappedEntries.size();
  parallelChunks(caps + batch.blendedEntries.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (i < caps) {
        const InterpolationBatch::CappedEntry& ref = batch.cappedEntries[i];
        const shared::DistanceField& f = batch.fields[static_cast<std::size_t>(ref.field)];
        domeErosions(fieldValues[static_cast<std::size_t>(ref.field)],
                     static_cast<std::size_t>(f.w) * static_cast<std::size_t>(f.h), ref.factor, ref.taper,
                     table.data() + ref.table);
        continue;
      }
      const InterpolationBatch::BlendedEntry& ref = batch.blendedEntries[i - caps];
      const shared::PairEntry& e = batch.entries[ref.entry];
      blendOffsets(e, blendFields(batch, e, fieldValues), ref.factor, batch.blendLimits, table.data() + ref.table);
    }
  });
  return table;
}

double capTaper(const Grid& grid, const PlaneCensus& census, Label label, int end, int before, int next) {
  if (before < 0 || before >= grid.nz) return 0;
  const auto count = [&](int k) -> double {
    const LabelCensus* c = find(census[static_cast<std::size_t>(k)], label);
    return c ? static_cast<double>(c->count) : 0;
  };
  const auto z = [&](int k) { return grid.layerZ[static_cast<std::size_t>(k)]; };
  return taperOfAreas(count(before), count(end), std::abs(z(next) - z(end)), std::abs(z(end) - z(before)));
}

void domeErosions(const std::int32_t* values, std::size_t count, int factor, double taper, std::int32_t* out) {
  std::vector<std::int32_t> near;  // what an erosion can uncover: inside, or within half a pixel outside
  for (std::size_t i = 0; i < count; ++i)
    if (values[i] < kFieldPixel / 2) near.push_back(values[i]);
  const std::int32_t deepest = near.empty() ? 0 : -*std::min_element(near.begin(), near.end());
  auto cover = [&](std::int32_t erosion) { return coveredArea(near.data(), near.size(), kFieldPixel, -erosion); };
  const double area = cover(0);
  out[0] = 0;
  const RoundCapProfile dome = roundCapProfile(taper);
  const double scale = domeAreaScale(dome, factor);
  const int top = domeTop(dome, factor);
  for (int m = 1; m <= top; ++m) {
    // The least erosion that leaves at most the dome's area covered.
    const double want = area * std::min(1.0, scale * domeFraction(dome, m, factor));
    std::int32_t lo = -1, hi = deepest + kFieldPixel;
    while (hi - lo > 1) {
      const std::int32_t mid = lo + (hi - lo) / 2;
      (cover(mid) <= want ? hi : lo) = mid;
    }
    out[m] = hi;
  }
  // Closed beyond: an erosion that puts the deepest pixel's level through zero at the tip's
  // height between the top layer and the next, so the dome ends in a tip there.
  const double t = domeTipHeight(dome, factor);
  const double depth = deepest - out[top];
  const auto closed = static_cast<std::int32_t>(std::lround(deepest + depth * (1 - t) / t));
  for (int m = top + 1; m <= factor; ++m) out[m] = factor == 1 ? -1 : closed;
}

}  // namespace scansurf
