#version 450
// Preview: vertices in the input's coordinates, an orthographic camera in push.clip.
#extension GL_GOOGLE_include_directive : require
#include "preview_push.h"

layout(location = 0) in vec3 position;
layout(location = 0) out vec3 worldPosition;

void main() {
  worldPosition = position;
  gl_Position = push.clip * vec4(position, 1.0);
}
