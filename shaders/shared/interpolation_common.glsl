// Shared by the interpolation compute shaders: the slab's buffers and integer helpers. The
// arithmetic is the CPU reference's (engine/geometry/interpolation/interpolation_reference.cpp) exactly.
#include "interpolation_types.h"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

layout(std430, binding = 0) readonly buffer Planes { uint words[]; } planes;  // 16-bit labels, two per word
layout(std430, binding = 1) readonly buffer Fields { DistanceField fields[]; } fieldTable;
layout(std430, binding = 2) buffer Values { int values[]; } fieldValues;
layout(std430, binding = 3) buffer Scratch { int ints[]; } scratch;
layout(std430, binding = 4) readonly buffer Entries { PairEntry entries[]; } entryTable;
layout(std430, binding = 5) readonly buffer Pairs { PairPlan pairs[]; } pairTable;
layout(std430, binding = 6) readonly buffer TileRanges { int ranges[]; } tileRanges;
layout(std430, binding = 7) readonly buffer TileEntries { int entries[]; } tileEntries;
layout(std430, binding = 8) writeonly buffer Output { uint labels[]; } outputLabels;
layout(std430, binding = 9) readonly buffer LayerTable { int value[]; } layerTable;  // [PairEntry::layerTable + m]
// Contour crossings of the +x (low byte) and +y (high byte) edge of each voxel, in 1/256.
layout(std430, binding = 10) readonly buffer Crossings { uint words[]; } crossings;

const int kFarAway = 1 << 28;
const int kMovingTile = 1 << 30;  // in a tile's count: a label there shifts
const int kIntMin = -2147483647 - 1;
const int kIntMax = 2147483647;

uint planeLabel(int plane, int x, int y) {
  const uint n = uint(x) + push.nx * (uint(y) + push.ny * uint(plane));
  return (planes.words[n >> 1] >> ((n & 1u) * 16u)) & 0xFFFFu;
}

// The crossing of edge (x, y) -> (x + 1, y) (shift 0) or -> (x, y + 1) (shift 8), in 1/256.
int crossingAt(int plane, int x, int y, uint shift) {
  const uint n = uint(x) + push.nx * (uint(y) + push.ny * uint(plane));
  return int((((crossings.words[n >> 1] >> ((n & 1u) * 16u)) & 0xFFFFu) >> shift) & 0xFFu);
}

// Window-relative crossing point of edge i of a line, in 1/unit pixel.
int crossingPoint(int i, int crossing) { return i * push.unit + (crossing * push.unit + 128) / 256; }

bool insideField(DistanceField f, int x, int y) {
  const uint l = planeLabel(f.plane, f.x0 + x, f.y0 + y);
  return f.label == 0 ? l != 0u : l == uint(f.label);
}

int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int roundDiv(int a, int n) { return a >= 0 ? (2 * a + n) / (2 * n) : -((-2 * a + n) / (2 * n)); }

// isqrt(min(fixedScale * d2, 2^32 - 1)), exactly.
int fixedDistance(int d2) {
  const uint s = uint(d2) > 0xFFFFFFFFu / push.fixedScale ? 0xFFFFFFFFu : uint(d2) * push.fixedScale;
  uint r = min(uint(sqrt(float(s))), 65535u);
  while (r * r > s) --r;
  while (r < 65535u && (r + 1u) * (r + 1u) <= s) ++r;
  return int(r);
}
