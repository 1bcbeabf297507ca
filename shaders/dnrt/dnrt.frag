#version 450
#extension GL_GOOGLE_include_directive : require
// DNRT: adds one object's L_DNRT (dnrt.glsl) to "lighting.hdr" with additive blending.
#include "frame.glsl"
#include "dnrt/dnrt.glsl"
#include "dnrt/intrusion.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(std430, set = 1, binding = 3) readonly buffer Objects { DnrtObject objects[]; };
layout(set = 1, binding = 4) uniform usampler2D gEntity;
// Table 2: 0..2 (m_0..m_3) of R, G, B; 3..5 (m_4..m_7) of R, G, B; 6 (m_8.rgb). 4-SH fields bind
// texture 0 in slots 3..6 (never read: the SH count is checked first).
layout(set = 2, binding = 0) uniform sampler3D field0;
layout(set = 2, binding = 1) uniform sampler3D field1;
layout(set = 2, binding = 2) uniform sampler3D field2;
layout(set = 2, binding = 3) uniform sampler3D field3;
layout(set = 2, binding = 4) uniform sampler3D field4;
layout(set = 2, binding = 5) uniform sampler3D field5;
layout(set = 2, binding = 6) uniform sampler3D field6;
// Intrusion map (intrusion.glsl); a 1×1 "nothing near" map for objects without intrusion.
layout(set = 2, binding = 7) uniform sampler2DArray intrusion;
layout(push_constant) uniform Push { uint object; uint fullScreen; } pc;

layout(location = 0) out vec4 outRadiance;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) discard;
  DnrtObject ob = objects[pc.object];
  vec3 r = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  vec3 q = ((ob.worldToLocal * vec4(r, 1.0)).xyz - ob.centreLocal.xyz) / ob.centreLocal.w;
  float s = dnrtFalloff(q, ob.extents.x, ob.extents.y);
  if (s <= 0.0) discard;
  vec3 toO = ob.centreWorld.xyz - r;
  float len = length(toO);
  if (!(len > 1e-6 * ob.centreWorld.w)) discard;  // at o: n_o undefined
  if (ob.ids.y != 0u) {
    // Something between o and r: r does not see the object (§5.2.3). Bias: 2% of R plus 2% of the
    // distance, the size of a 128² texel at 90° and the receiver's own surface in the map.
    float nearest = texture(intrusion, intrusionCoord(-toO)).r;
    if (len > nearest + 0.02 * ob.centreWorld.w + 0.02 * len) discard;
  }
  vec3 nr = texelFetch(gNormal, pixel, 0).xyz;
  float lamb = max(dot(toO / len, nr), 0.0);
  if (lamb <= 0.0) discard;
  // The object's own surface: its field holds filled (interior) values there, not a transfer.
  if (ob.ids.x != 0u && texelFetch(gEntity, pixel, 0).r == ob.ids.x) discard;
  vec3 uvw = dnrtUvw(q, ob.extents.x, ob.extents.w);
  vec4 m0 = ob.lo[0] + (ob.hi[0] - ob.lo[0]) * texture(field0, uvw);
  vec4 m1 = ob.lo[1] + (ob.hi[1] - ob.lo[1]) * texture(field1, uvw);
  vec4 m2 = ob.lo[2] + (ob.hi[2] - ob.lo[2]) * texture(field2, uvw);
  // Three dot products for 4 SH (§5.1.2): channel k's m_0..3 against c_0..3 of channel k.
  vec3 sum = vec3(dot(m0, vec4(ob.c[0].r, ob.c[1].r, ob.c[2].r, ob.c[3].r)),
                  dot(m1, vec4(ob.c[0].g, ob.c[1].g, ob.c[2].g, ob.c[3].g)),
                  dot(m2, vec4(ob.c[0].b, ob.c[1].b, ob.c[2].b, ob.c[3].b)));
  if (ob.extents.z > 4.5) {
    vec4 m3 = ob.lo[3] + (ob.hi[3] - ob.lo[3]) * texture(field3, uvw);
    vec4 m4 = ob.lo[4] + (ob.hi[4] - ob.lo[4]) * texture(field4, uvw);
    vec4 m5 = ob.lo[5] + (ob.hi[5] - ob.lo[5]) * texture(field5, uvw);
    vec4 m6 = ob.lo[6] + (ob.hi[6] - ob.lo[6]) * texture(field6, uvw);
    sum += vec3(dot(m3, vec4(ob.c[4].r, ob.c[5].r, ob.c[6].r, ob.c[7].r)),
                dot(m4, vec4(ob.c[4].g, ob.c[5].g, ob.c[6].g, ob.c[7].g)),
                dot(m5, vec4(ob.c[4].b, ob.c[5].b, ob.c[6].b, ob.c[7].b)));
    sum += m6.rgb * ob.c[8].rgb;
  }
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  outRadiance = vec4(albedo * (lamb * s) * sum, 0.0);
}
