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
#else
#define int_t int
#define SCANSURF_STRUCT(name) struct name
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
// overlap, the whole-pixel shift from A to B that the interpolation follows. Round caps
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

#ifdef __cplusplus
static_assert(sizeof(DistanceField) == 32 && sizeof(PairEntry) == 44 && sizeof(PairPlan) == 20);
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
#else
#undef SCANSURF_STRUCT
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
