#version 450
// Writes the feature's label into the integer label image.
#extension GL_GOOGLE_include_directive : require
#include "scan_push.h"

layout(location = 0) out uint outLabel;

void main() {
  outLabel = push.label;
}
