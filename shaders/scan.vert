#version 450
// Scan conversion (paper §3.4): contour vertices arrive in framebuffer pixels, already
// snapped to the rasterizer's sub-pixel grid on the CPU; the viewport is a power of two in
// size so the mapping to NDC and back is exact.
#extension GL_GOOGLE_include_directive : require
#include "scan_push.h"

layout(location = 0) in vec2 pixel;

void main() {
  gl_Position = vec4(pixel * push.ndcScale - 1.0, push.depth, 1.0);
}
