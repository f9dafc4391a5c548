#version 450
// Tetrahedral classification (Nielson & Franke 1997, as used by the scanline surfacing
// paper §3.5): for every cell of the label volume, the partition code of each of its six
// Freudenthal tetrahedra; cells holding a surface are appended to a compact record list.
#extension GL_GOOGLE_include_directive : require
#include "cell_case.h"
#include "classify_push.h"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

layout(std430, binding = 0) readonly buffer Labels { uint words[]; } labels;  // 16-bit labels two per word, or 32-bit
// count: records appended; largestLabel: the largest 32-bit label seen above 65535 (0: none),
// which the host reports (records hold 16-bit labels).
layout(std430, binding = 1) buffer Counter { uint count; uint largestLabel; } counter;
layout(std430, binding = 2) writeonly buffer Cases { CellCase records[]; } cases;
// With push.tiled: the tiles of cell columns the dispatch covers, one per workgroup; the others
// lie where the volume is background (geometry/grid/content_tiles.h).
layout(std430, binding = 3) readonly buffer Tiles { uint origins[]; } tiles;

// Corners of the six tetrahedra; same order as kCellTets in engine/geometry/extraction/cell_cases.h.
const uint kTets[24] = uint[24](0, 1, 3, 7,  0, 1, 5, 7,  0, 2, 3, 7,  0, 2, 6, 7,  0, 4, 5, 7,  0, 4, 6, 7);

uint labelAt(uint i, uint j, uint k) {
  const uint n = push.labelOffset + i + push.nx * (j + push.ny * k);
  if (push.labelBits == 32u) {
    const uint label = labels.words[n];
    if (label > 0xFFFFu && push.upperIsData == 0u) atomicMax(counter.largestLabel, label);
    return label & 0xFFFFu;
  }
  return (labels.words[n >> 1] >> ((n & 1u) * 16u)) & 0xFFFFu;
}

// r_i = smallest j <= i with l_j == l_i, packed r1 | r2 << 1 | r3 << 3.
uint partitionCode(uint a, uint b, uint c, uint d) {
  const uint r1 = b == a ? 0u : 1u;
  const uint r2 = c == a ? 0u : (c == b ? 1u : 2u);
  const uint r3 = d == a ? 0u : (d == b ? 1u : (d == c ? 2u : 3u));
  return r1 | (r2 << 1) | (r3 << 3);
}

// One invocation per (x, y) column of cells, up through the batch's layers: each layer's four
// labels are read once and serve the cells below and above it (a cell per invocation read all
// eight corners, every label eight times).
void main() {
  uvec2 g = gl_GlobalInvocationID.xy;
  if (push.tiled != 0u) {  // rows of kTileRow workgroups: a dispatch's width is limited
    const uint i = gl_WorkGroupID.x + gl_WorkGroupID.y * kTileRow;
    if (i >= push.tileCount) return;
    const uint t = tiles.origins[i];
    g = uvec2(t & 0xFFFFu, t >> 16) * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy;
  }
  if (g.x >= push.nx - 1u || g.y >= push.ny - 1u) return;

  uint l[8];  // corner c at (x + (c & 1), y + (c >> 1 & 1), z + (c >> 2))
  for (uint c = 0u; c < 4u; ++c) l[c] = labelAt(g.x + (c & 1u), g.y + ((c >> 1) & 1u), 0u);
  for (uint z = 0u; z < push.cellLayers; ++z) {
    for (uint c = 4u; c < 8u; ++c) l[c] = labelAt(g.x + (c & 1u), g.y + ((c >> 1) & 1u), z + 1u);
    bool uniformCell = true;
    for (uint c = 1u; c < 8u; ++c) uniformCell = uniformCell && l[c] == l[0];
    if (!uniformCell) {
      uint codes = 0u;
      for (uint t = 0u; t < 6u; ++t)
        codes |= partitionCode(l[kTets[4u * t]], l[kTets[4u * t + 1u]], l[kTets[4u * t + 2u]], l[kTets[4u * t + 3u]])
                 << (SCANSURF_TET_CODE_BITS * t);
      const uint slot = atomicAdd(counter.count, 1u);
      if (slot < push.capacity) {  // else the host sees count > capacity and runs the batch again
        CellCase record;
        record.cell = g.x + (push.nx - 1u) * (g.y + (push.ny - 1u) * (push.firstCellLayer + z));
        record.tetCodes = codes;
        for (uint w = 0u; w < 4u; ++w) record.labels[w] = l[2u * w] | (l[2u * w + 1u] << 16);
        cases.records[slot] = record;
      }
    }
    for (uint c = 0u; c < 4u; ++c) l[c] = l[c + 4u];
  }
}
