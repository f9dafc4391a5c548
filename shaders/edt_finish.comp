#version 450
// Shape-based interpolation, pass 3 of 4 (engine/geometry/interpolation_plan.h): one column of
// one distance field becomes signed fixed-point distances (the nearer of the two squared
// distances, negative inside), and the field's largest depth.
#extension GL_GOOGLE_include_directive : require
#include "interpolation_common.glsl"

void main() {
  const int x = int(gl_GlobalInvocationID.x);
  const int index = int(gl_GlobalInvocationID.y + push.pair);  // push.pair: first field of the dispatch
  if (index >= int(push.count)) return;
  const DistanceField f = fieldTable.fields[index];
  if (x >= f.w) return;
  const int d2y = f.scratch + 2 * f.w * f.h;
  int depth = 0;
  for (int y = 0; y < f.h; ++y) {
    const int at = y * f.w + x;
    const int d = fixedDistance(min(fieldValues.values[f.offset + at], scratch.ints[d2y + at]));
    const bool inside = insideField(f, x, y);
    fieldValues.values[f.offset + at] = inside ? -d : d;
    if (inside) depth = max(depth, d);
  }
  atomicMax(fieldRadii.radii[index], depth);
}
