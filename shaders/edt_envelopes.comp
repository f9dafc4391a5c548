#version 450
// Shape-based interpolation, pass 2 of 4 (engine/geometry/interpolation/interpolation_plan.h): the exact
// squared distances of one column (to the rows' points) and of one row (to the columns'
// points) of one distance field, through the lower envelope of parabolas (Felzenszwalb &
// Huttenlocher 2012, in integers: crossings rounded down decide every integer sample).
#extension GL_GOOGLE_include_directive : require
#include "interpolation_common.glsl"

// Over n samples at g + i * stride (scratch), min over q of weightRow g[q]^2 + weightLine (i - q)^2
// into target + i * outStride (the field's values when intoField, else scratch); v, z: scratch.
void lowerEnvelope(int g, int stride, int n, int weightRow, int weightLine, bool intoField, int target, int outStride, int v, int z) {
  int k = 0;
  scratch.ints[v] = 0, scratch.ints[z] = kIntMin, scratch.ints[z + 1] = kIntMax;
  for (int q = 1; q < n; ++q) {
    const int gq = scratch.ints[g + q * stride];
    const int hq = weightRow * gq * gq + weightLine * q * q;
    for (;;) {
      const int p = scratch.ints[v + k];
      const int gp = scratch.ints[g + p * stride];
      const int s = floorDiv(hq - (weightRow * gp * gp + weightLine * p * p), 2 * weightLine * (q - p));
      if (s <= scratch.ints[z + k]) { --k; continue; }
      ++k;
      scratch.ints[v + k] = q, scratch.ints[z + k] = s, scratch.ints[z + k + 1] = kIntMax;
      break;
    }
  }
  k = 0;
  for (int i = 0; i < n; ++i) {
    while (scratch.ints[z + k + 1] < i) ++k;
    const int p = scratch.ints[v + k];
    const int gp = scratch.ints[g + p * stride];
    const int d2 = weightRow * gp * gp + weightLine * (i - p) * (i - p);
    if (intoField) fieldValues.values[target + i * outStride] = d2;
    else scratch.ints[target + i * outStride] = d2;
  }
}

void main() {
  const int line = int(gl_GlobalInvocationID.x);
  const int index = int(gl_GlobalInvocationID.y + push.pair);  // push.pair: first field of the dispatch
  if (index >= int(push.count)) return;
  const DistanceField f = fieldTable.fields[index];
  const int area = f.w * f.h, unit2 = push.unit * push.unit;
  // Scratch: gx, gy, d2y (an area each), then v, z of every column, then of every row.
  const int columnsScratch = f.scratch + 3 * area, rowsScratch = columnsScratch + 2 * area + f.w;
  if (line < f.w) {  // column `line` of gx: squared distances into the field's values
    const int v = columnsScratch + line * (2 * f.h + 1);
    lowerEnvelope(f.scratch + line, f.w, f.h, push.weightX, push.weightY * unit2, true, f.offset + line, f.w, v, v + f.h);
  }
  if (line < f.h) {  // row `line` of gy: squared distances into d2y
    const int v = rowsScratch + line * (2 * f.w + 1);
    lowerEnvelope(f.scratch + area + line * f.w, 1, f.w, push.weightY, push.weightX * unit2, false, f.scratch + 2 * area + line * f.w, 1,
                  v, v + f.w);
  }
}
