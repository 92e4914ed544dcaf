#version 450
#extension GL_GOOGLE_include_directive : require
// Vibration-map overlay: the map value as an unlit heat colour, alpha-blended over the textured
// surface so researchers can check that the map lines up with the picture.
#include "frame.glsl"

layout(set = 1, binding = 1) uniform sampler2D vibration;

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec2 inTexcoord;
layout(location = 0) out vec4 outColor;

// Black -> red -> yellow -> white as vibration grows from 0 to 1.
vec3 heat(float t) {
  return clamp(vec3(3.0 * t, 3.0 * t - 1.0, 3.0 * t - 2.0), 0.0, 1.0);
}

void main() {
  const float value = texture(vibration, inTexcoord).r;
  outColor = vec4(heat(value), frame.overlay.x);
}
