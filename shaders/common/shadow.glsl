// Shadow-atlas lookups. The including shader declares, before including this file:
//   sampler2DArrayShadow shadowAtlas;      (depth compare: LESS_OR_EQUAL, linear filter = 2×2 PCF)
//   buffer { mat4 shadowMatrices[]; };     (one light view-projection per atlas layer)
// Point lights own six consecutive layers, one per cube face in cubeFace() order.
#ifndef BOUNCE_SHADOW_GLSL
#define BOUNCE_SHADOW_GLSL
#include "lights.glsl"

// Visibility in [0, 1] of light from p (unit normal n), with 3×3 hardware-PCF taps (a 4×4 texel
// footprint). Receivers are pushed along n by ~1.5 shadow texels at their distance (normal-offset
// bias): slope-scaled rasteriser bias alone leaves acne on walls at grazing angles to the light.
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
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x)
      sum += texture(shadowAtlas, vec4(uv + vec2(x, y) / size, float(layer), ref));
  return sum / 9.0;
}

#endif
