#version 450
#extension GL_GOOGLE_include_directive : require
// Hand primitives: flat colour, lit like the scene.
#include "frame.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inColor;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = vec4(shade(inColor, inNormal), 1.0);
}
