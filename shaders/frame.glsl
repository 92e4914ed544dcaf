// Per-frame uniforms shared by every pass (std140; mirrors FrameUniforms in renderer.cpp).
layout(set = 0, binding = 0) uniform Frame {
  mat4 viewProj[2];   // one per view (gl_ViewIndex), mono uses [0]
  vec4 toLight;       // xyz: unit vector towards the light (world)
  vec4 lightColor;    // rgb: direct light, w: ambient fraction
  vec4 overlay;       // x: vibration overlay opacity
} frame;

vec3 shade(vec3 albedo, vec3 normal) {
  const float diffuse = max(dot(normalize(normal), frame.toLight.xyz), 0.0);
  return albedo * (frame.lightColor.rgb * diffuse + vec3(frame.lightColor.w));
}
