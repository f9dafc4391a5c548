#version 450
// Shape-based interpolation, pass 3 of 4 (engine/geometry/interpolation/interpolation_plan.h): one column of
// one distance field becomes signed fixed-point distances (the nearer of the two squared
// distances, refined near the boundary by the marching-squares segments between the crossing
// points; negative inside), and the field's largest depth.
#extension GL_GOOGLE_include_directive : require
#include "interpolation_common.glsl"

const int kRefineBand = 2;

int segmentDistance2(int px, int py, int qx, int qy) {
  const int ax = qx - px, ay = qy - py, len2 = ax * ax + ay * ay, p2 = px * px + py * py;
  const int along = -px * ax - py * ay;
  if (len2 == 0 || along <= 0) return p2;
  if (along >= len2) return qx * qx + qy * qy;
  return (p2 * len2 - along * along) / len2;
}

int crossingOffset(DistanceField f, int cx, int cy, uint shift) {
  return (crossingAt(f.plane, f.x0 + cx, f.y0 + cy, shift) * push.unit + 128) / 256;
}

// As refinedDistance2 in engine/geometry/interpolation/interpolation_reference.cpp.
int refinedDistance2(DistanceField f, int x, int y, int d2) {
  const int unit = push.unit;
  if (d2 >= kRefineBand * kRefineBand * unit * unit) return d2;
  for (int cy = y - kRefineBand; cy < y + kRefineBand; ++cy)
    for (int cx = x - kRefineBand; cx < x + kRefineBand; ++cx) {
      if (cx < 0 || cy < 0 || cx + 1 >= f.w || cy + 1 >= f.h) continue;
      const bool a = insideField(f, cx, cy), b = insideField(f, cx + 1, cy), c = insideField(f, cx, cy + 1),
                 d = insideField(f, cx + 1, cy + 1);
      const int ox = (cx - x) * unit, oy = (cy - y) * unit;
      int px[4], py[4];
      const bool cut[4] = bool[4](a != b, c != d, a != c, b != d);
      px[0] = ox + crossingOffset(f, cx, cy, 0u), py[0] = oy;
      px[1] = ox + crossingOffset(f, cx, cy + 1, 0u), py[1] = oy + unit;
      px[2] = ox, py[2] = oy + crossingOffset(f, cx, cy, 8u);
      px[3] = ox + unit, py[3] = oy + crossingOffset(f, cx + 1, cy, 8u);
      if (cut[0] && cut[1] && cut[2] && cut[3]) {
        if (a) {
          d2 = min(d2, segmentDistance2(px[0], py[0], px[2], py[2]));
          d2 = min(d2, segmentDistance2(px[1], py[1], px[3], py[3]));
        } else {
          d2 = min(d2, segmentDistance2(px[0], py[0], px[3], py[3]));
          d2 = min(d2, segmentDistance2(px[1], py[1], px[2], py[2]));
        }
      } else {
        int first = -1;
        for (int i = 0; i < 4; ++i)
          if (cut[i]) {
            if (first < 0) first = i;
            else d2 = min(d2, segmentDistance2(px[first], py[first], px[i], py[i]));
          }
      }
    }
  return d2;
}

void main() {
  const int x = int(gl_GlobalInvocationID.x);
  const int index = int(gl_GlobalInvocationID.y + push.pair);  // push.pair: first field of the dispatch
  if (index >= int(push.count)) return;
  const DistanceField f = fieldTable.fields[index];
  if (x >= f.w) return;
  const int d2y = f.scratch + 2 * f.w * f.h;
  const bool square = push.weightX == 1 && push.weightY == 1;
  for (int y = 0; y < f.h; ++y) {
    const int at = y * f.w + x;
    int d2 = min(fieldValues.values[f.offset + at], scratch.ints[d2y + at]);
    if (square) d2 = refinedDistance2(f, x, y, d2);
    const int d = fixedDistance(d2);
    const bool inside = insideField(f, x, y);
    fieldValues.values[f.offset + at] = inside ? -d : d;
  }
}
