#version 450
#extension GL_GOOGLE_include_directive : require
// Lit, textured surface. The albedo texture is sRGB (decoded to linear by the sampler), lighting is
// linear, and the sRGB colour attachment encodes the result.
#include "frame.glsl"

layout(set = 1, binding = 0) uniform sampler2D albedo;

layout(push_constant) uniform Object {
  mat4 T_world_object;
  vec4 baseColor;
  vec4 uvRow0;
  vec4 uvRow1;
} object;

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec2 inTexcoord;
layout(location = 0) out vec4 outColor;

void main() {
  const vec3 color = texture(albedo, inTexcoord).rgb * object.baseColor.rgb;
  outColor = vec4(shade(color, inNormal), 1.0);
}
