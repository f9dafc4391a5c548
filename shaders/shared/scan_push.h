// Shared by GLSL (scan.vert, scan_label.frag) and C++ (passes/scan_conversion.cpp): the push
// constants of the scan-conversion pipelines.
#ifndef SCANSURF_SHARED_SCAN_PUSH_H
#define SCANSURF_SHARED_SCAN_PUSH_H

#ifdef __cplusplus
#include <cstdint>
namespace scansurf::shared {
struct ScanPush {
  float ndcScale[2];  // 2 / viewport size: a power of two, so pixel -> NDC is exact
  float depth;        // the feature's rank mapped into (0, 1): inner features are nearer
  std::uint32_t label;
};
static_assert(sizeof(ScanPush) == 16, "ScanPush must match the GLSL push-constant block");
}  // namespace scansurf::shared
#else
layout(push_constant) uniform ScanPush {
  vec2 ndcScale;
  float depth;
  uint label;
}
push;
#endif

#endif
