// scansurf: the plan of multi-label shape-based interpolation between the layers of a label
// volume (Raya & Udupa 1990; Herman, Zheng & Bucholtz 1992; Grevera & Udupa 1996), shared by
// the GPU passes (passes/interpolator.cpp) and the CPU reference (interpolation_reference.h).
//
// The rule, for a voxel at x on layer m of n between grid layers A and B (t = m/n):
//  - every label L present on A or B has a signed distance field on each plane where it is
//    present: the exact Euclidean distance (negative inside, in 1/16 of the smaller pixel
//    spacing) to the points where the contours cross the grid edges between L and other
//    labels (edge_crossings.h), so the field keeps the contours' sub-pixel positions; within
//    two pixels of the boundary, to the segments joining those points cell by cell (marching
//    squares), where the points alone would leave a pattern of stripes;
//  - value(L) = (1-t) dA(x) + t dB(x) - offset(L, m), the offset keeping L's area on the
//    linear blend of its areas on A and B (blendOffsets; none for the union or a label that
//    contains others). When L's regions on A and B share no pixel (a vessel
//    that moved further than its width) both fields are sampled along L's centroid shift
//    (x - t*shift on A, x + (1-t)*shift on B), so L moves instead of vanishing midway;
//  - where L is on one plane only, it closes with a cap (CapShape) that takes its voxels from
//    any label that goes on: flat keeps its region on that plane up to half the gap (an
//    extrusion and a lid, as planning systems count volume; beyond the lid L only counts as
//    runner-up, for the lid's clearance); round erodes it layer by layer to a dome holding
//    the flat half slab's volume that leaves the plane at the structure's taper there
//    (domeErosions, capTaper): half an ellipsoid 3/4 of the gap high where it did not taper. A voxel outside a
//    cap (or a lid) keeps the cap's value as its clearance when that is smaller, so the
//    surface between them lies where the cap's level crosses zero;
//  - the union of all features gets a value of its own where it is on both planes (it caps
//    nothing);
//  - a voxel with one label on both planes, at least deepDistance from that label's boundary
//    on both and in no tile of a shifting label, keeps that label without the competition
//    below (it would win it: every field is 1-Lipschitz), with the largest clearance (no
//    surface vertex comes within four pixels of it);
//  - the voxel takes the label of smallest value (ties: the smaller label) if that value is
//    negative, or the union's is and a runner-up label's value is within n * deepDistance,
//    else background. Its clearance is how far its value is from
//    losing the label (to the runner-up label or to the background), which places the surface
//    vertex between two voxels of different labels (clearance-weighted, as marching cubes). The
//    union keeps abutting features together where each alone would pull back (no background
//    gap opens between them), and a feature nested in another stays inside it; alone, a
//    feature keeps its own area-keeping boundary.
// A label only competes in a window around its pixels on its plane and both neighbours
// (kWindowMargin pixels around): elsewhere its value is kFarAway.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "interpolation_types.h"
#include "scansurf/interpolation.h"
#include "scansurf/label_volume.h"
#include "scansurf/result.h"

namespace scansurf {

// factors[k]: the volume gets factors[k] - 1 layers between grid layers k and k+1.
std::vector<int> interpolationFactors(const Grid& grid, const InterpolationOptions& options);
bool interpolates(const std::vector<int>& factors);
// The layer of the interpolated grid that grid layer k becomes.
std::vector<int> fineLayerOfPlane(const std::vector<int>& factors);
// The grid with the interpolated layers, evenly spaced between the original ones (which stay
// layers, with exactly their z).
Grid interpolatedGrid(const Grid& grid, const std::vector<int>& factors);

// Distances are measured in 1/unit pixel; the squared distance of a step (dx, dy) in those
// units is x dx^2 + y dy^2, and the distance in 1/16 of the smaller spacing is
// isqrt(fixedScale * squared distance). Square pixels: unit 16 up to 2048 pixels a side (less
// beyond), weights 1, 1: exact. Otherwise the weights' ratio is rounded (to 1/64 at best) so
// that every intermediate fits 32-bit integers. Errors: a grid too large for its pixel
// aspect ratio.
struct DistanceWeights {
  std::int32_t x = 1, y = 1;
  std::int32_t unit = 16;
  std::uint32_t fixedScale = 1;
};
Result<DistanceWeights> distanceWeights(const Grid& grid);

inline constexpr int kTileSize = 16;
inline constexpr std::int32_t kFieldPixel = 16;  // a field's values are in 1/16 of the smaller pixel spacing
inline constexpr int kWindowMargin = 4;
inline constexpr std::int32_t kFarAway = 1 << 28;
inline constexpr int kRefineBand = 2;                 // pixels from the boundary where segments refine distances
inline constexpr std::int32_t kMovingTile = 1 << 30;  // tile flag: a label that shifts (in its count)

// Four pixels of the larger spacing in 1/16 of the smaller: how far from its label's boundary a
// voxel must be to skip the competition.
std::int32_t deepDistance(const Grid& grid);

// Pairs of planes [firstPlane + haloBefore, firstPlane + planes - haloAfter) of the volume: the
// distance fields of planes [firstPlane, firstPlane + planes), each pair's entries and their tile
// lists. A halo plane (the one before the first pair, the one after the last, where the volume
// has them) only lends its fields to bend the blends of its neighbouring pair.
struct InterpolationBatch {
  int firstPlane = 0;
  int planes = 0;
  int haloBefore = 0, haloAfter = 0;
  int firstPairPlane() const { return firstPlane + haloBefore; }
  int lastPairPlane() const { return firstPlane + planes - 1 - haloAfter; }
  int outputLayers = 0;  // layers m = 0 .. factor of each of its pairs
  int tilesX = 0, tilesY = 0;
  std::vector<shared::DistanceField> fields;
  std::vector<shared::PairEntry> entries;
  std::vector<shared::PairPlan> pairs;
  std::vector<std::int32_t> tileRanges;  // {first, count | kMovingTile?} per tile of every pair
  std::vector<std::int32_t> tileEntries;
  std::size_t fieldValues = 0;  // ints of the field buffer
  std::size_t scratchInts = 0;  // ints of the scratch buffer
  // Entries of a feature on one plane only (round caps), with their dome erosions' place in the
  // layer table, filled from the fields once they are computed (buildLayerTable).
  struct CappedEntry {
    int field = 0;
    int factor = 1;
    std::size_t table = 0;
    double taper = 0;  // capTaper: how the dome leaves its plane
  };
  std::vector<CappedEntry> cappedEntries;
  // Entries of a feature on both planes, with their area-keeping offsets' place in the table.
  struct BlendedEntry {
    std::size_t entry = 0;
    int factor = 1;
    std::size_t table = 0;
  };
  std::vector<BlendedEntry> blendedEntries;
  // How far an offset may move a boundary (1/16 of the smaller pixel): inward (shrinking) and
  // outward (growing). Shrinking stops short of deepDistance, where a voxel inside one label
  // on both planes keeps it unasked; growing may go further, within the label's window, as
  // where the outline turns or winds between the planes the blended fields lose most of it.
  struct OffsetLimits {
    std::int32_t shrink = 0, grow = 0;
  };
  OffsetLimits blendLimits;
  std::size_t layerInts = 0;  // ints of the layer table (PairEntry::layerTable)
  std::size_t deviceBytes(const Grid& grid) const;
};

// Where each label lies on each layer of a volume, read once; every batch's plan uses it.
struct LabelCensus {
  Label label = 0;  // 0: the union of every non-background label
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  std::int64_t count = 0, sumX = 0, sumY = 0;
};
using PlaneCensus = std::vector<std::vector<LabelCensus>>;  // per layer, by label (union first)
PlaneCensus takePlaneCensus(const LabelVolume& volume, int threads);

// About what plane k adds to a batch's device memory (its fields, labels and output layers).
std::size_t estimatePlaneBytes(const LabelVolume& volume, const PlaneCensus& census, int k, int factor);

// The pairs of planes [firstPlane, firstPlane + planes) with their halo planes.
// containers[label]: the label's feature contains another (Nesting::parent); its boundary
// with what it contains is that feature's, so it keeps no area of its own between planes (its
// own region has holes that come and go with its contents' caps).
InterpolationBatch planInterpolationBatch(const LabelVolume& volume, const PlaneCensus& census, int firstPlane, int planes,
                                          const std::vector<int>& factors, const std::vector<bool>& containers = {});

// Round caps: a dome that holds what a flat half slab holds, whatever the outline's shape, and
// leaves its plane at the taper the structure had there. Its cross-section at height s (in
// gaps) keeps f(s) = 1 - a s - b s^2 of the label's area on its plane, closed at H, with
// f' (0) = -taper (= a) and the integral of f over [0, H] = 1/2: H = 6 / (4 + sqrt(16 - 12 a)),
// from 3/4 of the gap (taper 0: half an ellipsoid over a disc) to the whole gap (taper 1: the
// area shrinks linearly to the next plane). Its region at
// layer m is {d < -erosion(m)}, d the label's field on its plane, the areas its pixels' covers
// (coveredArea) and scaled a little so that the frusta between the layers, not the trapezoids,
// hold the half slab: out gets factor + 1 erosions (1/16 pixel), the deepest depth where the
// dome is closed, so that it closes in a tip on its first closed layer (a fully eroded layer
// left the top flat, a third of a layer's frustum short: -3 % of a cap at 5 layers a gap).
// values: the field's window values (negative inside).
void domeErosions(const std::int32_t* values, std::size_t count, int factor, double taper, std::int32_t* out);

// A round cap's taper in [0, 1]: how fast the label's area shrank toward its end plane `end`
// over the gap before it (from layer `before`), as a share of its area on the end plane per
// cap gap (`next`: the layer the cap closes toward), so that the dome goes on as the structure
// went (a sphere's cap, not a wall and a lid; docs/method.md, "Caps"). A structure that grew
// or kept its area toward its end, or that has no plane before it, gets 0 (half an
// ellipsoid). Beyond 1 the trend ends the structure within the gap, which no dome holding
// the half slab can follow without standing taller still: the taper falls back to 0 by 1.25.
double capTaper(const Grid& grid, const PlaneCensus& census, Label label, int end, int before, int next);

// The fields of one entry that a blend reads: before A, A, B, after B (null where absent), each
// with its window's values.
struct BlendFields {
  const shared::DistanceField* field[4] = {};
  const std::int32_t* values[4] = {};
};

// The entry's blended value at layer m of n and pixel (x, y), scaled by n, before its area
// offset: (n - m) dA + m dB bent by the fields before and after (hermiteBend), kFarAway
// outside A's or B's window. As interpolate.comp's entryValue.
std::int32_t blendedValue(const shared::PairEntry& e, const BlendFields& f, int m, int n, int x, int y);

// Area-keeping blends: a feature on both planes of a pair keeps, at layer m of n, an area on
// the monotone cubic through its areas on the planes before A, A, B and after B (linear
// where it has no such plane), so that its volume follows the slab rule without a kink in its
// area at a contour plane (the blended fields alone lose area wherever the outline changes
// between the planes: 15 % of the volume of an ellipse turned a quarter turn). Its region at
// layer m is {value < offset(m)}, value the blend as the interpolation samples it
// (blendedValue); areas are the pixels' covers read off the signed distances, the offsets
// solved near the boundary and bounded by n * limits (shrinking by limits.shrink, so that a
// voxel deep inside one label on both planes still belongs to it). out gets factor + 1
// offsets, the first and last 0 (the planes are the contours).
void blendOffsets(const shared::PairEntry& e, const BlendFields& fields, int factor, InterpolationBatch::OffsetLimits limits,
                  std::int32_t* out);

// A field's value at grid pixel (x, y), kFarAway outside its window (values: the window).
inline std::int32_t fieldValue(const shared::DistanceField& f, const std::int32_t* values, int x, int y) {
  if (x < f.x0 || y < f.y0 || x >= f.x0 + f.w || y >= f.y0 + f.h) return kFarAway;
  return values[static_cast<std::size_t>(x - f.x0) + static_cast<std::size_t>(f.w) * static_cast<std::size_t>(y - f.y0)];
}

// The entry's blend fields from the batch's field values (as buildLayerTable takes them).
BlendFields blendFields(const InterpolationBatch& batch, const shared::PairEntry& e,
                        const std::vector<const std::int32_t*>& fieldValues);

// The layer table (PairEntry::layerTable) of batch.layerInts: every round-capped entry's dome
// erosions and every blended entry's offsets, from the fields' values (fieldValues[field]:
// its window, as DistanceField::offset addresses; null for a field no entry needs), the
// entries shared among threads (the same table for any count).
std::vector<std::int32_t> buildLayerTable(const InterpolationBatch& batch, const std::vector<const std::int32_t*>& fieldValues,
                                          int threads);

// round(a / n), halves away from zero, for n > 0: how far a shifting label has moved at layer a of n.
inline std::int32_t roundDiv(std::int32_t a, std::int32_t n) {
  return a >= 0 ? (2 * a + n) / (2 * n) : -((-2 * a + n) / (2 * n));
}

// Flat caps: whether the label may still win at layer m of n counted from its plane, and its
// value there: its plane's distance, but at least a ramp through zero at half the gap, so that
// the lid's clearance puts it at half the gap, whatever the depth below it.
inline bool flatCapOpen(int factor, int m) { return 2 * m <= factor; }
inline constexpr std::int32_t kFlatLidSlope = 256;  // 16 pixels per unit of 2m - n
inline std::int32_t flatCapValue(std::int32_t d, int factor, int m) {
  return std::max(factor * d, kFlatLidSlope * (2 * m - factor));
}

}  // namespace scansurf
