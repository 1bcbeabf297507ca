// Shadow-atlas lookups. The including shader declares, before including this file:
//   sampler2DArrayShadow shadowAtlas;      (depth compare: LESS_OR_EQUAL, linear filter = 2×2 PCF)
//   mat4 shadowMatrices[…];                (one light view-projection per atlas layer; a uniform
//                                           block of kMaxShadowLayers or a storage buffer)
// Point lights own six consecutive layers, one per cube face in cubeFace() order.
#ifndef BOUNCE_SHADOW_GLSL
#define BOUNCE_SHADOW_GLSL
#include "lights.glsl"

// Visibility in [0, 1] of light from p (unit normal n): the 3×3 grid of hardware-PCF taps (each a
// 2×2 bilinear compare, together a 4×4 texel footprint) computed as 4 bilinear compare taps.
// Along one axis, with the lookup at texel coordinate s = b + f (b integer, texel centres at
// integers), the 3 taps at s − 1, s, s + 1 weight texels b − 1 … b + 2 by (1 − f, 1, 1, f)/3: one
// tap between b − 1 and b at fraction 1/(2 − f) with weight (2 − f)/3 and one between b + 1 and
// b + 2 at fraction f/(1 + f) with weight (1 + f)/3 give the same weights (the compare happens per
// texel before the bilinear weights, so the regrouping is exact up to filtering precision).
// Receivers are pushed along n by ~1.5 shadow texels at their distance (normal-offset bias):
// slope-scaled rasteriser bias alone leaves acne on walls at grazing angles to the light.
float shadowVisibility(Light light, vec3 p, vec3 n, float dist) {
  if (light.shadow.x < 0.0) return 1.0;
  uint type = uint(light.positionType.w + 0.5);
  float texel = light.shadow.y * (type == kLightDirectional ? 0.0 : dist) + light.shadow.z;
  vec3 q = p + n * (1.5 * texel);
  uint layer = uint(light.shadow.x + 0.5);
  if (type == kLightPoint) layer += cubeFace(q - light.positionType.xyz);
  vec4 clip = shadowMatrices[layer] * vec4(q, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  if (any(greaterThan(abs(ndc.xy), vec2(1.0))) || ndc.z > 1.0) return 1.0;  // outside: unshadowed
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float ref = ndc.z - light.shadow.w;
  vec2 size = vec2(textureSize(shadowAtlas, 0).xy);
  vec2 s = uv * size - 0.5;  // texel coordinate, texel centres at integers
  vec2 b = floor(s);
  vec2 f = s - b;
  vec2 wA = 2.0 - f, wB = 1.0 + f;                // per-axis weights ×3
  vec2 uvA = (b - 0.5 + 1.0 / wA) / size;         // b − 1 + 1/(2 − f), back to uv (+0.5)
  vec2 uvB = (b + 1.5 + f / wB) / size;           // b + 1 + f/(1 + f), back to uv (+0.5)
  float l = float(layer);
  float sum = wA.x * wA.y * texture(shadowAtlas, vec4(uvA.x, uvA.y, l, ref)) +
              wB.x * wA.y * texture(shadowAtlas, vec4(uvB.x, uvA.y, l, ref)) +
              wA.x * wB.y * texture(shadowAtlas, vec4(uvA.x, uvB.y, l, ref)) +
              wB.x * wB.y * texture(shadowAtlas, vec4(uvB.x, uvB.y, l, ref));
  return sum / 9.0;
}

#endif
