// The hand's shadow on the surfaces that receive it (include after frame.glsl): the shadow map is
// the hand's depth seen from the directional light, compared with a 3x3 grid of bilinear
// (hardware 2x2) comparisons 1.5 texels apart for a soft edge. The world position comes from the
// fragment's own depth, not from an extra varying: on lavapipe another varying changes how depth
// is interpolated, and the receiving and plain pipelines must write identical depth (renderer.cpp).
layout(set = 0, binding = 1) uniform sampler2DShadow shadowMap;

// 1 where the light reaches the fragment, 0 in the full shadow, between at the edges.
float lightVisibility() {
  if (frame.shadow.x <= 0.0) return 1.0;
  const vec2 ndc = gl_FragCoord.xy * frame.viewport.xy * 2.0 - 1.0;
  const vec4 position = frame.invViewProj[gl_ViewIndex] * vec4(ndc, gl_FragCoord.z, 1.0);
  const vec3 world = position.xyz / position.w;
  const vec4 clip = frame.lightViewProj * vec4(world, 1.0);
  const vec2 uv = clip.xy * 0.5 + 0.5;
  // Outside the casters' reach (the screen rectangle drawn with this is wider): no taps.
  if (any(lessThan(uv, frame.shadowRect.xy)) || any(greaterThan(uv, frame.shadowRect.zw))) return 1.0;
  const float reference = clip.z - frame.shadow.z;
  float lit = 0.0;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) lit += texture(shadowMap, vec3(uv + vec2(x, y) * frame.shadow.y, reference));
  }
  return 1.0 - frame.shadow.x * (1.0 - lit / 9.0);
}
