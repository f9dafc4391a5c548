// Shared by GLSL (edt_rows.comp, edt_columns.comp, interpolate.comp) and C++
// (geometry/interpolation/interpolation_plan.h, passes/interpolator.cpp): the records that describe one
// slab of shape-based interpolation. All members are 32-bit ints (std430 and C++ agree).
#ifndef SCANSURF_SHARED_INTERPOLATION_TYPES_H
#define SCANSURF_SHARED_INTERPOLATION_TYPES_H

#ifdef __cplusplus
#include <cstdint>
namespace scansurf::shared {
using int_t = std::int32_t;
#define SCANSURF_STRUCT(name) struct name
#define SCANSURF_FN inline
#else
#define int_t int
#define SCANSURF_STRUCT(name) struct name
#define SCANSURF_FN
#endif

// A signed distance field of one label (0: the union of all features) on one plane of the
// slab, over a window of the plane; values at offset + x + w * y (fixed point, 1/16 of the
// smaller pixel spacing; negative inside).
SCANSURF_STRUCT(DistanceField) {
  int_t x0, y0, w, h;
  int_t plane;    // plane of the slab (0 = its first)
  int_t label;    // 0: every non-background label
  int_t offset;   // first value in the field buffer
  int_t scratch;  // first int of this field's scratch (rows, then envelopes)
};

// One label that may appear between two planes A and B, with its fields (-1: absent on that
// plane, the label ends there and gets a cap) and, when its regions on A and B do not
// overlap, the whole-pixel shift from A to B that the interpolation follows. A label on both
// planes that does not shift also has its fields on the plane before A and the one after B
// where it is there and the gap is alike (-1: none), which bend its blend (hermiteBend). Round caps
// become flat where two labels that end together touch: domes of different sizes would let
// the slower one grow into the other.
SCANSURF_STRUCT(PairEntry) {
  int_t label;
  int_t fieldA, fieldB;
  int_t shiftX, shiftY;
  int_t x0, y0, x1, y1;  // where the label may win (inclusive pixel box)
  int_t flatCap;         // 1: the label ends here touching another that ends: a flat cap
  int_t layerTable;      // its first of factor + 1 values in the layer table (-1: none): on one plane
                         // only, the dome's erosions; on both (a feature), the area-keeping offsets
  int_t fieldBefore, fieldAfter;
};

// Two consecutive planes of the slab, the interpolated layers between them and the entries
// of each tile of the plane (tileRanges[tileStart + tile] = {first, count} into tileEntries).
// Every pair of an interpolated volume has one, factor 1 included: plane A's clearance
// (output layer m = 0) places the vertices between it and its neighbouring layers.
SCANSURF_STRUCT(PairPlan) {
  int_t planeA;      // plane B = planeA + 1
  int_t factor;      // layers m = 1 .. factor-1 lie between A and B (m = 0: A, m = factor: B)
  int_t firstLayer;  // output layer of m = 0
  int_t tileStart;
  int_t layers;  // output layers m = 0 .. layers-1: factor, or factor + 1 for the volume's last pair
};

// Monotone cubic blending across the planes (Fritsch & Carlson 1980; the tangents of Fritsch &
// Butland 1984): a field's value at a pixel, followed through planes 0..3 (A = 1, B = 2), is the
// cubic Hermite curve through its values on A and B whose slope at each plane is the harmonic
// mean of the changes over the gaps on either side, 0 where they differ in sign, so the blended
// surface has no kink at a contour plane and never overshoots: between A and B the value stays
// between its values there (a region between the planes is never larger than both planes'
// regions together, nor smaller than what they share). Integers only, so that the shader and
// the CPU reference agree exactly.
#define SCANSURF_BEND_LIMIT 16384  // changes are clamped here (1024 pixels a gap) so products fit 32 bits
SCANSURF_FN int_t bendTangent(int_t before, int_t after) {
  const int_t s0 =
      before < -SCANSURF_BEND_LIMIT ? -SCANSURF_BEND_LIMIT : (before > SCANSURF_BEND_LIMIT ? SCANSURF_BEND_LIMIT : before);
  const int_t s1 =
      after < -SCANSURF_BEND_LIMIT ? -SCANSURF_BEND_LIMIT : (after > SCANSURF_BEND_LIMIT ? SCANSURF_BEND_LIMIT : after);
  if (s0 == 0 || s1 == 0 || (s0 > 0) != (s1 > 0)) return 0;
  return 2 * s0 * s1 / (s0 + s1);
}
// What the cubic adds to the linear blend (n - m) a + m b at layer m of n (scaled by n as it
// is), from the tangents at A and B (in value per gap) and the chord b - a: n t (1 - t)
// ((1 - t)(tangentA - chord) - t (tangentB - chord)), t = m / n, rounded half away from zero.
SCANSURF_FN int_t hermiteBend(int_t tangentA, int_t tangentB, int_t chord, int_t m, int_t n) {
  const int_t num = m * (n - m) * ((n - m) * (tangentA - chord) - m * (tangentB - chord));
  const int_t den = n * n;
  return num >= 0 ? (2 * num + den) / (2 * den) : -((-2 * num + den) / (2 * den));
}
#ifdef __cplusplus
static_assert(sizeof(DistanceField) == 32 && sizeof(PairEntry) == 52 && sizeof(PairPlan) == 20);
struct InterpolatePush {
  std::uint32_t nx, ny;
  std::uint32_t count;            // fields (EDT passes) or entries (unused by interpolate)
  std::uint32_t pair;             // interpolate: the pair of this dispatch
  std::int32_t weightX, weightY;  // squared-distance weights of a pixel step along x and y
  std::uint32_t fixedScale;       // distance in 1/16 units = isqrt(fixedScale * squared distance)
  std::uint32_t roundCaps;        // 1: round caps, 0: flat
  std::uint32_t tileSize, tilesX;
  std::int32_t unit;  // distances in 1/unit pixel
  std::int32_t far;   // farther than any distance on the grid
  std::int32_t deep;  // deepDistance (geometry/interpolation/interpolation_plan.h)
};
static_assert(sizeof(InterpolatePush) == 52, "InterpolatePush must match the GLSL block");
}  // namespace scansurf::shared
#undef SCANSURF_STRUCT
#undef SCANSURF_FN
#else
#undef SCANSURF_STRUCT
#undef SCANSURF_FN
#undef int_t
layout(push_constant) uniform InterpolatePush {
  uint nx;
  uint ny;
  uint count;
  uint pair;
  int weightX;
  int weightY;
  uint fixedScale;
  uint roundCaps;
  uint tileSize;
  uint tilesX;
  int unit;
  int far;
  int deep;
}
push;
#endif

#endif
