// Shared by GLSL (preview.vert, preview.frag) and C++ (passes/preview_renderer.cpp): the push
// constants of the preview pipelines.
#ifndef SCANSURF_SHARED_PREVIEW_PUSH_H
#define SCANSURF_SHARED_PREVIEW_PUSH_H

#ifdef __cplusplus
namespace scansurf::shared {
struct PreviewPush {
  float clip[16];  // input coordinates -> clip space, column-major
  float color[4];  // sRGB colour and opacity of the feature
  float light[4];  // unit direction towards the light, input coordinates
};
static_assert(sizeof(PreviewPush) == 96, "PreviewPush must match the GLSL push-constant block");
}  // namespace scansurf::shared
#else
layout(push_constant) uniform PreviewPush {
  mat4 clip;
  vec4 color;
  vec4 light;
}
push;
#endif

#endif
