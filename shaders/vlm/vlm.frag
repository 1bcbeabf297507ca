#version 450
#extension GL_GOOGLE_include_directive : require
// VLM phase 2 (thesis §3.3 bottom, §4.3): one bounce of diffuse light from the virtual lights,
// added to "lighting.hdr":
//   E(x) = Σ_k π L_k F_k(x, n),   L_o += ρ(x)/π · E(x)
// over the candidates of x's cell in the static and the dynamic grid (K slots each, kNullLight
// ends a list), skipping lights whose tag equals the pixel's (§3.4). Each draw shades one range of
// lights (push constant lightRange): the static ones, or one dynamic VLM's. F_k is Eq. 3.1 with horizon
// clipping (vlm/form_factor.glsl); L_k comes from phase 1 (vlm_lights.frag).
#include "frame.glsl"
#include "vlm/form_factor.glsl"
#include "vlm/vlm_common.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 3) uniform usampler2D gEntity;  // entity id + 1, 0 = background
layout(std430, set = 1, binding = 4) readonly buffer VlmLights { VlmLight vlmLights[]; };
layout(set = 1, binding = 5) uniform sampler2D vlmRadiance;  // phase 1: texel i = L_i
layout(std430, set = 1, binding = 6) readonly buffer Slots { uint slots[]; };  // static grid, then dynamic
layout(std430, set = 1, binding = 7) readonly buffer Tags { uint entityTags[]; };  // per entity index

struct GridGpu {
  vec4 originK;  // xyz world minimum corner (m), w K (candidates per cell)
  vec4 cellBase; // xyz cell size (m), w first slot of this grid in `slots`
  ivec4 dims;    // xyz cells per axis, w 0 = grid empty
};
layout(push_constant) uniform Push {
  GridGpu grids[2];  // 0 static, 1 dynamic
  uvec4 counts;      // x virtual lights, y entity tags, z radiance texels per row
  uvec4 lightRange;  // x first, y end: this draw shades lights [first, end) only (node.cpp: the
                     // static grid's draw, then one draw per dynamic VLM)
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outRadiance;

const uint kNullLight = 0xFFFFFFFFu;
const float kPi = 3.14159265358979;

vec3 gridIrradiance(GridGpu g, vec3 x, vec3 n, uint tag) {
  if (g.dims.w == 0) return vec3(0.0);
  ivec3 c = ivec3(floor((x - g.originK.xyz) / g.cellBase.xyz));
  if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, g.dims.xyz))) return vec3(0.0);
  uint k = uint(g.originK.w);
  uint base = uint(g.cellBase.w) + (uint(c.x) + uint(g.dims.x) * (uint(c.y) + uint(g.dims.y) * uint(c.z))) * k;
  vec3 e = vec3(0.0);
  // do-while, not for: llvmpipe tests "is any lane still looping" only at the end of an iteration,
  // so a top-tested loop runs one more body with every lane masked (k + 1 for a full list; README
  // "What costs what on lavapipe"). The body therefore also runs once for k = 0: `s >= k` leaves.
  uint s = 0u;
  do {
    if (s >= k) break;
    uint i = slots[base + s];
    ++s;  // before the `continue`s, which jump to the test
    if (i == kNullLight || i >= pc.counts.x) break;  // lists are packed: the rest are null lights
    if (i < pc.lightRange.x || i >= pc.lightRange.y) continue;
    VlmLight vl = vlmLights[i];
    if (tag != 0u && uint(vl.v0.w + 0.5) == tag) continue;
    // Cheap rejections before the clip (same answer as vlmFormFactor's: it returns 0 for both):
    // the receiver behind the one-sided light, or the whole triangle below the horizon.
    vec3 r0 = vl.v0.xyz - x, r1 = vl.v1.xyz - x, r2 = vl.v2.xyz - x;
    if (!(dot(cross(vl.v1.xyz - vl.v0.xyz, vl.v2.xyz - vl.v0.xyz), -r0) > 0.0)) continue;
    if (max(dot(n, r0), max(dot(n, r1), dot(n, r2))) < 0.0) continue;
    float f = vlmFormFactor(x, n, vl.v0.xyz, vl.v1.xyz, vl.v2.xyz);
    if (f <= 0.0) continue;
    vec3 L = texelFetch(vlmRadiance, ivec2(i % pc.counts.z, i / pc.counts.z), 0).rgb;
    e += kPi * L * f;
  } while (s < k);
  return e;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) {
    outRadiance = vec4(0.0);
    return;
  }
  uint entity = texelFetch(gEntity, pixel, 0).r;
  uint tag = entity != 0u && entity - 1u < pc.counts.y ? entityTags[entity - 1u] : 0u;
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  vec3 n = texelFetch(gNormal, pixel, 0).xyz;
  vec3 x = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  vec3 e = gridIrradiance(pc.grids[0], x, n, tag) + gridIrradiance(pc.grids[1], x, n, tag);
  outRadiance = vec4(albedo / kPi * e, 0.0);
}
