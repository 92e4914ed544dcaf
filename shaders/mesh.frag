#version 450
#extension GL_EXT_multiview : require
#extension GL_GOOGLE_include_directive : require
// Lit, textured surface. The albedo texture is sRGB (decoded to linear by the sampler), lighting
// is linear, and the sRGB colour attachment encodes the result. The pipeline built with
// kReceivesShadow draws the part of the screen the hand's shadow can reach; the other never
// samples the shadow map (a software rasteriser would pay for the taps on every pixel).
#include "frame.glsl"
#include "shadow.glsl"

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

layout(constant_id = 0) const bool kReceivesShadow = false;

void main() {
  const vec3 color = texture(albedo, inTexcoord).rgb * object.baseColor.rgb;
  outColor = vec4(shade(color, inNormal, kReceivesShadow ? lightVisibility() : 1.0), 1.0);
}
