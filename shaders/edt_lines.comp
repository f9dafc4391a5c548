#version 450
// Shape-based interpolation, pass 1 of 4 (engine/geometry/interpolation/interpolation_plan.h): along one
// row and one column of one distance field, the distance to the nearest point where a
// contour crosses a grid edge between the field's label and another (its row's x edges, its
// column's y edges); the first dimension of Felzenszwalb & Huttenlocher's transform, twice.
#extension GL_GOOGLE_include_directive : require
#include "interpolation_common.glsl"

void main() {
  const int line = int(gl_GlobalInvocationID.x);
  const int index = int(gl_GlobalInvocationID.y + push.pair);  // push.pair: first field of the dispatch
  if (index >= int(push.count)) return;
  const DistanceField f = fieldTable.fields[index];
  const int area = f.w * f.h;
  if (line < f.h) {  // row `line`: x-edge points into gx, row-major
    const int y = line, row = f.scratch + y * f.w;
    int point = 0;
    bool have = false;
    for (int x = 0; x < f.w; ++x) {
      if (x >= 1 && insideField(f, x - 1, y) != insideField(f, x, y))
        point = crossingPoint(x - 1, crossingAt(f.plane, f.x0 + x - 1, f.y0 + y, 0u)), have = true;
      scratch.ints[row + x] = have ? x * push.unit - point : push.far;
    }
    have = false;
    for (int x = f.w - 1; x >= 0; --x) {
      if (x + 1 < f.w && insideField(f, x, y) != insideField(f, x + 1, y))
        point = crossingPoint(x, crossingAt(f.plane, f.x0 + x, f.y0 + y, 0u)), have = true;
      if (have) scratch.ints[row + x] = min(scratch.ints[row + x], point - x * push.unit);
    }
  }
  if (line < f.w) {  // column `line`: y-edge points into gy, row-major
    const int x = line, column = f.scratch + area + x;
    int point = 0;
    bool have = false;
    for (int y = 0; y < f.h; ++y) {
      if (y >= 1 && insideField(f, x, y - 1) != insideField(f, x, y))
        point = crossingPoint(y - 1, crossingAt(f.plane, f.x0 + x, f.y0 + y - 1, 8u)), have = true;
      scratch.ints[column + y * f.w] = have ? y * push.unit - point : push.far;
    }
    have = false;
    for (int y = f.h - 1; y >= 0; --y) {
      if (y + 1 < f.h && insideField(f, x, y) != insideField(f, x, y + 1))
        point = crossingPoint(y, crossingAt(f.plane, f.x0 + x, f.y0 + y, 8u)), have = true;
      if (have) scratch.ints[column + y * f.w] = min(scratch.ints[column + y * f.w], point - y * push.unit);
    }
  }
}
