#version 450
// A contact ring: an unlit bright band at the square's inscribed circle over a faint disc,
// brighter and more opaque as the touch's intensity grows; alpha-blended over the surface.
layout(location = 0) in vec2 inLocal;
layout(location = 1) in float inIntensity;
layout(location = 0) out vec4 outColor;

void main() {
  const float r = length(inLocal);
  const float edge = fwidth(r);
  // Band from 0.72 to 1.0 of the radius, anti-aliased on both sides.
  const float band = smoothstep(0.72 - edge, 0.72 + edge, r) * (1.0 - smoothstep(1.0 - edge, 1.0, r));
  const float disc = 1.0 - smoothstep(0.72 - edge, 0.72 + edge, r);
  const float alpha = band * (0.55 + 0.45 * inIntensity) + disc * 0.25 * inIntensity;
  if (alpha <= 0.0) discard;
  const vec3 color = mix(vec3(0.1, 0.55, 1.0), vec3(0.75, 1.0, 1.0), inIntensity);
  outColor = vec4(color, alpha);
}
