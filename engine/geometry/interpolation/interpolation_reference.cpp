// scansurf: CPU reference of multi-label shape-based interpolation (rule in
// interpolation_plan.h; Grevera & Udupa 1996), with exact integer Euclidean distance
// transforms (Felzenszwalb & Huttenlocher, "Distance Transforms of Sampled Functions", 2012).
#include "geometry/interpolation/interpolation_reference.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace scansurf {
namespace {

// floor(a / b) for b > 0.
std::int32_t floorDiv(std::int32_t a, std::int32_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Distance, in 1/unit pixel, from each of n samples of a grid line to the nearest crossing
// point on it (far when there is none); boundary(i) says whether edge (i, i+1) has one, at
// crossing(i) / 256 of the edge.
template <typename Boundary, typename Crossing>
void lineDistances(int n, std::int32_t unit, std::int32_t far, Boundary boundary, Crossing crossing, std::int32_t* out,
                   std::size_t stride) {
  std::int32_t point = 0;
  bool have = false;
  for (int i = 0; i < n; ++i) {
    if (i >= 1 && boundary(i - 1)) point = (i - 1) * unit + (crossing(i - 1) * unit + 128) / 256, have = true;
    out[static_cast<std::size_t>(i) * stride] = have ? i * unit - point : far;
  }
  have = false;
  for (int i = n - 1; i >= 0; --i) {
    if (i + 1 < n && boundary(i)) point = i * unit + (crossing(i) * unit + 128) / 256, have = true;
    if (have) out[static_cast<std::size_t>(i) * stride] = std::min(out[static_cast<std::size_t>(i) * stride], point - i * unit);
  }
}

// Squared distance from the origin to segment p-q (integers; floor of the exact value).
std::int32_t segmentDistance2(std::int32_t px, std::int32_t py, std::int32_t qx, std::int32_t qy) {
  const std::int32_t ax = qx - px, ay = qy - py, len2 = ax * ax + ay * ay, p2 = px * px + py * py;
  const std::int32_t along = -px * ax - py * ay;
  if (len2 == 0 || along <= 0) return p2;
  if (along >= len2) return qx * qx + qy * qy;
  return (p2 * len2 - along * along) / len2;
}

// Near the boundary (kRefineBand pixels), the distance to the marching-squares segments that
// join the crossing points in the cells around the pixel, when shorter: exact for a straight
// boundary, where the crossing points alone err by up to a tenth of a pixel in a pattern that
// repeats along the boundary (stripes on the surface). Square pixels only.
template <typename Inside, typename Crossing>
std::int32_t refinedDistance2(int x, int y, int w, int h, std::int32_t unit, std::int32_t d2, Inside inside, Crossing crossing) {
  if (d2 >= kRefineBand * kRefineBand * unit * unit) return d2;
  auto at = [&](int cx, int cy, int shift) { return (crossing(cx, cy, shift) * unit + 128) / 256; };
  for (int cy = y - kRefineBand; cy < y + kRefineBand; ++cy)
    for (int cx = x - kRefineBand; cx < x + kRefineBand; ++cx) {
      if (cx < 0 || cy < 0 || cx + 1 >= w || cy + 1 >= h) continue;
      const bool a = inside(cx, cy), b = inside(cx + 1, cy), c = inside(cx, cy + 1), d = inside(cx + 1, cy + 1);
      const std::int32_t ox = (cx - x) * unit, oy = (cy - y) * unit;
      // Points on the bottom, top, left and right edges of the cell, where they are crossed.
      std::int32_t px[4], py[4];
      bool cut[4] = {a != b, c != d, a != c, b != d};
      px[0] = ox + at(cx, cy, 0), py[0] = oy;
      px[1] = ox + at(cx, cy + 1, 0), py[1] = oy + unit;
      px[2] = ox, py[2] = oy + at(cx, cy, 8);
      px[3] = ox + unit, py[3] = oy + at(cx + 1, cy, 8);
      auto join = [&](int i, int j) { d2 = std::min(d2, segmentDistance2(px[i], py[i], px[j], py[j])); };
      if (cut[0] && cut[1] && cut[2] && cut[3]) {
        if (a)
          join(0, 2), join(1, 3);  // a and d inside: cut their corners off
        else
          join(0, 3), join(1, 2);
      } else {
        int first = -1;
        for (int i = 0; i < 4; ++i)
          if (cut[i]) {
            if (first < 0)
              first = i;
            else
              join(first, i);
          }
      }
    }
  return d2;
}

void fieldReference(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings, int plane,
                    const shared::DistanceField& f, const DistanceWeights& weights, std::int32_t* values) {
  const Grid& g = volume.grid;
  const std::size_t w = static_cast<std::size_t>(f.w), area = w * static_cast<std::size_t>(f.h);
  const std::int32_t unit = weights.unit, far = farDistance(g, weights);
  auto inside = [&](int x, int y) {
    const Label l = volume.at(f.x0 + x, f.y0 + y, plane);
    return f.label == kBackground ? l != kBackground : l == f.label;
  };
  auto crossing = [&](int x, int y, int shift) { return (crossings[g.index(f.x0 + x, f.y0 + y, plane)] >> shift) & 0xFF; };
  std::vector<std::int32_t> gx(area), gy(area), d2x(area), d2y(area), v(std::max(w, static_cast<std::size_t>(f.h))),
      z(std::max(w, static_cast<std::size_t>(f.h)) + 1), line(std::max(w, static_cast<std::size_t>(f.h)));
  for (int y = 0; y < f.h; ++y)
    lineDistances(
        f.w, unit, far, [&](int x) { return inside(x, y) != inside(x + 1, y); }, [&](int x) { return crossing(x, y, 0); },
        gx.data() + y * w, 1);
  for (int x = 0; x < f.w; ++x)
    lineDistances(
        f.h, unit, far, [&](int y) { return inside(x, y) != inside(x, y + 1); }, [&](int y) { return crossing(x, y, 8); },
        gy.data() + x, w);
  for (int x = 0; x < f.w; ++x) {
    lowerEnvelope(gx.data() + x, w, f.h, weights.x, weights.y * unit * unit, v.data(), z.data(), line.data());
    for (int y = 0; y < f.h; ++y) d2x[x + w * static_cast<std::size_t>(y)] = line[static_cast<std::size_t>(y)];
  }
  for (int y = 0; y < f.h; ++y)
    lowerEnvelope(gy.data() + y * w, 1, f.w, weights.y, weights.x * unit * unit, v.data(), z.data(), d2y.data() + y * w);
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      const std::size_t at = x + w * static_cast<std::size_t>(y);
      std::int32_t d2 = std::min(d2x[at], d2y[at]);
      if (weights.x == 1 && weights.y == 1)
        d2 = refinedDistance2(x, y, f.w, f.h, unit, d2, inside,
                              [&](int cx, int cy, int shift) { return crossing(cx, cy, shift); });
      const std::int32_t d = fixedDistance(d2, weights.fixedScale);
      values[at] = inside(x, y) ? -d : d;
    }
}

struct Sampler {
  const LabelVolume& volume;
  const InterpolationBatch& batch;
  const BatchFields& fields;
  CapShape caps;
  std::int32_t deep;
  std::vector<const std::int32_t*> fieldStarts;  // each field's window values

  std::int32_t at(int field, int x, int y) const {
    const shared::DistanceField& f = batch.fields[static_cast<std::size_t>(field)];
    return fieldValue(f, fields.values.data() + f.offset, x, y);
  }

  // The entry's value at layer m of n, scaled by n (kFarAway: it cannot win here); `wins`
  // false: it only counts as runner-up (a flat cap beyond its lid).
  std::int32_t value(const shared::PairEntry& e, int m, int n, int x, int y, bool& wins) const {
    wins = true;
    if (e.fieldA >= 0 && e.fieldB >= 0) {
      const std::int32_t v = blendedValue(e, blendFields(batch, e, fieldStarts), m, n, x, y);
      if (v == kFarAway) return kFarAway;
      const std::int32_t offset = e.layerTable >= 0 ? fields.layerTable[static_cast<std::size_t>(e.layerTable + m)] : 0;
      return v - offset;  // area-keeping (blendOffsets)
    }
    if (e.label == kBackground) return kFarAway;  // the union caps nothing
    const int field = e.fieldA >= 0 ? e.fieldA : e.fieldB;
    const int fromPlane = e.fieldA >= 0 ? m : n - m;
    const std::int32_t d = at(field, x, y);
    if (d == kFarAway) return kFarAway;
    if (caps == CapShape::Flat || e.flatCap != 0) {
      wins = flatCapOpen(n, fromPlane);
      return flatCapValue(d, n, fromPlane);
    }
    const std::int32_t erosion = fields.layerTable[static_cast<std::size_t>(e.layerTable + fromPlane)];  // a dome
    if (erosion < 0) return kFarAway;  // no layer between: no dome
    return n * (d + erosion);
  }

  // A label that ends here (present on one plane only): its cap keeps its region.
  static bool capped(const shared::PairEntry& e) { return e.label != kBackground && (e.fieldA < 0 || e.fieldB < 0); }

  // Whether the voxel lies deep inside one label on both planes (see interpolation_plan.h).
  bool deepInside(const shared::PairPlan& pair, int x, int y, std::int32_t first, std::int32_t count) const {
    const Label a = volume.at(x, y, batch.firstPlane + pair.planeA), b = volume.at(x, y, batch.firstPlane + pair.planeA + 1);
    if (a != b) return false;
    for (std::int32_t i = first; i < first + count; ++i) {
      const shared::PairEntry& e = batch.entries[static_cast<std::size_t>(batch.tileEntries[static_cast<std::size_t>(i)])];
      if (e.label != a) continue;
      if (e.fieldA < 0 || e.fieldB < 0) return false;
      return std::abs(at(e.fieldA, x, y)) >= deep && std::abs(at(e.fieldB, x, y)) >= deep;
    }
    return false;
  }

  // The label | clearance << 16 word of the voxel (as interpolate.comp writes it).
  std::uint32_t word(const shared::PairPlan& pair, int m, int x, int y) const {
    const Grid& g = volume.grid;
    if (m > 0 && m < pair.factor && (x == 0 || y == 0 || x == g.nx - 1 || y == g.ny - 1)) return 0u;  // the border
    const int tile = x / kTileSize + batch.tilesX * (y / kTileSize);
    const std::int32_t first = batch.tileRanges[2 * static_cast<std::size_t>(pair.tileStart + tile)];
    const std::int32_t flagged = batch.tileRanges[2 * static_cast<std::size_t>(pair.tileStart + tile) + 1];
    const std::int32_t count = flagged & ~kMovingTile;
    if (!(flagged & kMovingTile) && deepInside(pair, x, y, first, count))
      return volume.at(x, y, batch.firstPlane + pair.planeA) | 0xFFFF0000u;
    std::int32_t best = kFarAway, second = kFarAway, united = kFarAway, extruded = 0, capMargin = kFarAway;
    Label winner = kBackground, extrudedLabel = kBackground;
    for (std::int32_t i = first; i < first + count; ++i) {
      const shared::PairEntry& e = batch.entries[static_cast<std::size_t>(batch.tileEntries[static_cast<std::size_t>(i)])];
      if (x < e.x0 || y < e.y0 || x > e.x1 || y > e.y1) continue;
      bool wins = true;
      const std::int32_t v = value(e, m, pair.factor, x, y, wins);
      if (e.label == kBackground)
        united = v;
      else if (wins && v < best)
        second = best, best = v, winner = static_cast<Label>(e.label);
      else if (v < second)
        second = v;
      if (wins && v < 0 && capped(e) && (extrudedLabel == kBackground || v < extruded))
        extruded = v, extrudedLabel = static_cast<Label>(e.label);
      if (v >= 0 && capped(e)) capMargin = std::min(capMargin, v);  // how far a cap (or a lid) is from taking the voxel
    }
    if (extrudedLabel != kBackground) {  // a cap keeps its region (a flat cap up to its lid, a dome as it narrows)
      const auto c = static_cast<std::uint32_t>(std::min((-extruded + pair.factor / 2) / pair.factor, 65535));
      return extrudedLabel | (c << 16);
    }
    // The union only closes gaps between features (a runner-up near): alone, a feature keeps its
    // own area-keeping boundary.
    const std::int32_t level = second < pair.factor * deep ? std::min(best, united) : best;
    const bool labelled = winner != kBackground && level < 0;
    const std::int32_t clearance = std::min(labelled ? std::min(second - best, -level) : level, capMargin);
    const auto c = static_cast<std::uint32_t>(std::min((clearance + pair.factor / 2) / pair.factor, 65535));
    return (labelled ? winner : 0u) | (c << 16);
  }
};

}  // namespace

void lowerEnvelope(const std::int32_t* g, std::size_t stride, int n, std::int32_t weightRow, std::int32_t weightColumn,
                   std::int32_t* v, std::int32_t* z, std::int32_t* out) {
  auto height = [&](std::int32_t q) {
    return weightRow * g[static_cast<std::size_t>(q) * stride] * g[static_cast<std::size_t>(q) * stride];
  };
  int k = 0;
  v[0] = 0, z[0] = INT_MIN, z[1] = INT_MAX;
  for (std::int32_t q = 1; q < n; ++q) {
    for (;;) {
      const std::int32_t p = v[k];
      const std::int32_t s =
          floorDiv((height(q) + weightColumn * q * q) - (height(p) + weightColumn * p * p), 2 * weightColumn * (q - p));
      if (s <= z[k]) {
        --k;
        continue;
      }
      ++k, v[k] = q, z[k] = s, z[k + 1] = INT_MAX;
      break;
    }
  }
  k = 0;
  for (std::int32_t y = 0; y < n; ++y) {
    while (z[k + 1] < y) ++k;
    out[y] = height(v[k]) + weightColumn * (y - v[k]) * (y - v[k]);
  }
}

std::int32_t fixedDistance(std::int64_t d2, std::uint32_t scale) {
  const std::uint64_t s = std::min<std::uint64_t>(static_cast<std::uint64_t>(d2) * scale, 0xFFFFFFFFull);
  auto r = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(s)));
  while (r * r > s) --r;
  while ((r + 1) * (r + 1) <= s) ++r;
  return static_cast<std::int32_t>(r);
}

std::int32_t farDistance(const Grid& grid, const DistanceWeights& weights) {
  return weights.unit * (std::max(grid.nx, grid.ny) + 1);
}

BatchFields distanceFieldsReference(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings,
                                    const InterpolationBatch& batch, const DistanceWeights& weights) {
  BatchFields out;
  out.values.resize(batch.fieldValues);
  for (std::size_t i = 0; i < batch.fields.size(); ++i) {
    const shared::DistanceField& f = batch.fields[i];
    fieldReference(volume, crossings, batch.firstPlane + f.plane, f, weights, out.values.data() + f.offset);
  }
  std::vector<const std::int32_t*> values;
  for (const shared::DistanceField& f : batch.fields) values.push_back(out.values.data() + f.offset);
  out.layerTable = buildLayerTable(batch, values, 1);
  return out;
}

std::vector<std::uint32_t> interpolateBatchReference(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings,
                                                     const InterpolationBatch& batch, const DistanceWeights& weights,
                                                     CapShape caps) {
  const Grid& g = volume.grid;
  const BatchFields fields = distanceFieldsReference(volume, crossings, batch, weights);
  std::vector<const std::int32_t*> starts;
  for (const shared::DistanceField& f : batch.fields) starts.push_back(fields.values.data() + f.offset);
  const Sampler sampler{volume, batch, fields, caps, deepDistance(g), std::move(starts)};
  const std::size_t plane = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  std::vector<std::uint32_t> out(plane * static_cast<std::size_t>(batch.outputLayers));
  for (const shared::PairPlan& pair : batch.pairs)
    for (int m = 0; m < pair.layers; ++m) {
      std::uint32_t* layer = out.data() + plane * static_cast<std::size_t>(pair.firstLayer + m);
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x) layer[x + static_cast<std::size_t>(g.nx) * y] = sampler.word(pair, m, x, y);
    }
  return out;
}

}  // namespace scansurf
