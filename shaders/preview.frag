#version 450
// Preview shading: flat facet normals from screen-space derivatives (the mesh carries no
// normals), lit two-sided by a light near the camera, plus ambient.
#extension GL_GOOGLE_include_directive : require
#include "preview_push.h"

layout(location = 0) in vec3 worldPosition;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 n = normalize(cross(dFdx(worldPosition), dFdy(worldPosition)));
  float diffuse = abs(dot(n, push.light.xyz));
  outColor = vec4(push.color.rgb * (0.28 + 0.72 * diffuse), push.color.a);
}
