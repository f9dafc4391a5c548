#version 450
// Shape-based interpolation, pass 4 of 4 (engine/geometry/interpolation/interpolation_plan.h): the label of
// every voxel of the layers m = 0 .. n of one pair of planes, from the distance fields of the
// labels that may win in its tile, with its clearance (how far its value is from losing the
// label) for placing surface vertices between voxels.
#extension GL_GOOGLE_include_directive : require
#include "interpolation_common.glsl"

int fieldAt(int index, int x, int y) {
  const DistanceField f = fieldTable.fields[index];
  if (x < f.x0 || y < f.y0 || x >= f.x0 + f.w || y >= f.y0 + f.h) return kFarAway;
  return fieldValues.values[f.offset + (x - f.x0) + f.w * (y - f.y0)];
}

const int kFlatLidSlope = 256;

// The entry's value at layer m of n, scaled by n (kFarAway: it cannot win here); `wins`
// false: it only counts as runner-up (a flat cap beyond its lid). As Sampler::value in
// engine/geometry/interpolation/interpolation_reference.cpp.
int entryValue(PairEntry e, int m, int n, int x, int y, out bool wins) {
  wins = true;
  if (e.fieldA >= 0 && e.fieldB >= 0) {
    const int sx = roundDiv(m * e.shiftX, n), sy = roundDiv(m * e.shiftY, n);
    const int a = fieldAt(e.fieldA, x - sx, y - sy), b = fieldAt(e.fieldB, x + e.shiftX - sx, y + e.shiftY - sy);
    if (a == kFarAway || b == kFarAway) return kFarAway;
    const int chord = b - a;
    int tangentA = chord, tangentB = chord;  // bent across the planes (hermiteBend)
    if (e.fieldBefore >= 0) {
      const int before = fieldAt(e.fieldBefore, x, y);
      if (before != kFarAway) tangentA = bendTangent(a - before, chord);
    }
    if (e.fieldAfter >= 0) {
      const int after = fieldAt(e.fieldAfter, x, y);
      if (after != kFarAway) tangentB = bendTangent(chord, after - b);
    }
    const int bend = hermiteBend(tangentA, tangentB, chord, m, n);
    return (n - m) * a + m * b + bend - (e.layerTable >= 0 ? layerTable.value[e.layerTable + m] : 0);  // area-keeping
  }
  if (e.label == 0) return kFarAway;  // the union caps nothing
  const int field = e.fieldA >= 0 ? e.fieldA : e.fieldB;
  const int fromPlane = e.fieldA >= 0 ? m : n - m;
  const int d = fieldAt(field, x, y);
  if (d == kFarAway) return kFarAway;
  if (push.roundCaps == 0u || e.flatCap != 0) {
    wins = 2 * fromPlane <= n;
    return max(n * d, kFlatLidSlope * (2 * fromPlane - n));
  }
  const int erosion = layerTable.value[e.layerTable + fromPlane];  // a dome 3/4 of the gap high
  if (erosion < 0) return kFarAway;                                // no layer between: no dome
  return n * (d + erosion);
}

// Deep inside one label on both planes (see interpolation_plan.h): that label, no competition.
bool deepInside(PairPlan pair, int x, int y, int first, int count) {
  const uint a = planeLabel(pair.planeA, x, y), b = planeLabel(pair.planeA + 1, x, y);
  if (a != b) return false;
  for (int i = first; i < first + count; ++i) {
    const PairEntry e = entryTable.entries[tileEntries.entries[i]];
    if (uint(e.label) != a) continue;
    if (e.fieldA < 0 || e.fieldB < 0) return false;
    return abs(fieldAt(e.fieldA, x, y)) >= push.deep && abs(fieldAt(e.fieldB, x, y)) >= push.deep;
  }
  return false;
}

// The word of a voxel: its label and clearance. On the contour planes (m = 0, and m = n for the
// volume's last plane) the label is the plane's own, so the words of every pair, copied side
// by side, are the whole interpolated label volume (classified on the device).
void store(PairPlan pair, int m, int x, int y, int slot, uint label, uint clearance) {
  if (m == 0)
    label = planeLabel(pair.planeA, x, y);
  else if (m == pair.factor)
    label = planeLabel(pair.planeA + 1, x, y);
  else if (x == 0 || y == 0 || x == int(push.nx) - 1 || y == int(push.ny) - 1)
    label = 0u, clearance = 0u;  // the border stays background, as on the planes: every surface closes inside
  outputLabels.labels[slot] = label | (clearance << 16);
}

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= int(push.nx) || y >= int(push.ny)) return;
  const PairPlan pair = pairTable.pairs[push.pair];
  const int m = int(gl_GlobalInvocationID.z);
  const int tile = pair.tileStart + x / int(push.tileSize) + int(push.tilesX) * (y / int(push.tileSize));
  const int first = tileRanges.ranges[2 * tile], flagged = tileRanges.ranges[2 * tile + 1];
  const int count = flagged & ~kMovingTile;
  const int slot = (pair.firstLayer + m) * int(push.nx * push.ny) + y * int(push.nx) + x;
  if ((flagged & kMovingTile) == 0 && deepInside(pair, x, y, first, count)) {
    store(pair, m, x, y, slot, planeLabel(pair.planeA, x, y), 0xFFFFu);
    return;
  }
  int best = kFarAway, second = kFarAway, united = kFarAway, winner = 0, extruded = 0, extrudedLabel = 0, capMargin = kFarAway;
  for (int i = first; i < first + count; ++i) {
    const PairEntry e = entryTable.entries[tileEntries.entries[i]];
    if (x < e.x0 || y < e.y0 || x > e.x1 || y > e.y1) continue;
    bool wins;
    const int v = entryValue(e, m, pair.factor, x, y, wins);
    if (e.label == 0)
      united = v;
    else if (wins && v < best)
      second = best, best = v, winner = e.label;
    else if (v < second)
      second = v;
    const bool capped = e.label != 0 && (e.fieldA < 0 || e.fieldB < 0);
    if (wins && v < 0 && capped && (extrudedLabel == 0 || v < extruded)) extruded = v, extrudedLabel = e.label;
    if (v >= 0 && capped) capMargin = min(capMargin, v);  // how far a cap (or a lid) is from taking the voxel
  }
  if (extrudedLabel != 0) {  // a cap keeps its region (a flat cap up to its lid, a dome as it narrows)
    const uint c = uint(min((-extruded + pair.factor / 2) / pair.factor, 65535));
    store(pair, m, x, y, slot, uint(extrudedLabel), c);
    return;
  }
  // The union only closes gaps between features (a runner-up near): alone, a feature keeps its
  // own area-keeping boundary.
  const int level = second < pair.factor * push.deep ? min(best, united) : best;
  const bool labelled = winner != 0 && level < 0;
  const int clearance = min(labelled ? min(second - best, -level) : level, capMargin);
  const uint c = uint(min((clearance + pair.factor / 2) / pair.factor, 65535));
  const uint label = labelled ? uint(winner) : 0u;
  store(pair, m, x, y, slot, label, c);
}
