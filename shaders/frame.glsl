// Per-frame uniforms shared by every pass (std140; mirrors FrameUniforms in renderer.cpp).
layout(set = 0, binding = 0) uniform Frame {
  mat4 viewProj[2];   // one per view (gl_ViewIndex), mono uses [0]; the shadow pass's copy: the light's
  vec4 toLight;       // xyz: unit vector towards the light (world)
  vec4 lightColor;    // rgb: direct light, w: ambient fraction
  vec4 overlay;       // x: vibration overlay opacity
  mat4 lightViewProj; // world -> the shadow map's clip space (orthographic, Vulkan depth 0..1)
  vec4 shadow;        // x: strength (0: no shadow this frame), y: PCF tap spacing (map uv), z: depth bias
  vec4 shadowRect;    // the map uv rectangle the casters' shadow can reach (min xy, max zw)
  mat4 invViewProj[2]; // inverse of viewProj: fragments find their world position from their depth
  vec4 viewport;      // xy: 1 / target size in pixels
} frame;

vec3 shade(vec3 albedo, vec3 normal, float visibility) {
  const float diffuse = max(dot(normalize(normal), frame.toLight.xyz), 0.0) * visibility;
  return albedo * (frame.lightColor.rgb * diffuse + vec3(frame.lightColor.w));
}

vec3 shade(vec3 albedo, vec3 normal) { return shade(albedo, normal, 1.0); }
