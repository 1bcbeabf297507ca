#version 450
// SL pass 1 (Guerrero, Jeschke, Wimmer 2008, §5.1 and §8.1): the light intensity SH vector L^c of
// every SL for this frame. One workgroup per SL, one invocation per surface sample point (samples
// beyond 64 loop with stride 64):
//  1. the sample's world position and normal: its baked local position and normal moved with the
//     SL's pose (engine/gi/sl/update.hpp: rotation about the SL's centre, uniform scale
//     r_posed / r_rest, then the posed centre) — §7.1 moves the sample points with their SL;
//  2. L_p (Eq. 3 with ρ_n = the white Lambertian BRDF, no albedo: the paper factors it in at
//     Eq. 11): the light arriving there — the level's real lights projected into order-3 radiance
//     SH by incident.glsl (radius 0: a point receiver), each times its shadow-map visibility
//     (shadow.glsl), plus the probes' indirect radiance SH (sampled at the SL's centre on the CPU)
//     — cosine-convolved at the normal (sh.glsl shIrradiance9) — with that indirect light blocked
//     by the SLs (§5.1: "SLs act as blockers and environment lighting as light source", Eq. 3 and
//     6, when pc.blockers is set): ΔE of sl/probe_shadow.glsl, the same function (and exp, tables,
//     receiver rules) pass 2's sl.shadow uses, over every SL of the frame after the receiver rules
//     (the sample's own SL and the neighbours that contain it are shrunk or culled there); the
//     lights need no spheres, their shadow maps hold every object's real mesh — except with §7.3
//     local lights (pc.blockers bit 1): the point and spot lights' maps then leave the SL objects
//     out and the SLs block those lights here (sl/local_light.glsl: "the same calculation for
//     local light sources" as pass 2). Clamped ≥ 0 and divided by π: W/(m²·sr) per channel;
//  3. Eq. 10: L_S = Σ_j L_pj Y'_j with Y'_j the baked basis sums (already × 4π/N), summed over the
//     workgroup in shared memory;
//  4. Eq. 11: L^c = L_S ∗ c_S, the SH product with the SL's albedo SH per channel, through the
//     Gaunt tensor engine/math/sh_product.hpp computes (uploaded, not re-derived here).
// The C++ reference is engine/gi/sl/intensity.hpp (sampleReflection + intensityFromSamples);
// tests/unit/sl/intensity_gpu_test.cpp compares the two.
//
// Data (std430 unless noted, bytes): samples = Sample[], Sample = 96 (position.xyz local, normal.xyz
// local unit, basis[16] as 4 vec4); spheres = Sphere[], Sphere = 240 (rest: local centre, radius;
// posed: world centre, radius; rotation: 3 column vec4 (SL local → world); range: first sample,
// sample count; indirect: 9 vec4, rgb = radiance SH at the posed centre); albedo = vec4[sphere·16 + k]
// (rgb: c_S,k); gaunt = Gaunt[], Gaunt = 16 ((i, j, k) and C_ijk, sorted by (k, i, j)); lights and
// shadow matrices as the lighting pass has them (std140 UBOs of kMaxLights / kMaxShadowLayers);
// out = uint[sphere·24 + w], fp16 pairs (engine/gi/sl/intensity_words.hpp: word 8c + m =
// packHalf2x16(L^c_2m[c], L^c_2m+1[c]), channel c, the SL's local frame; unused k ≥ order² are 0;
// clamped to ±65504, half's range), pass 2's uniform block: half the per-lane reads of rgb floats;
// bindings 8–10: sl_data.glsl (the frame's SLs as blockers, engine/gi/sl/shade.hpp ShadeData; its
// intensity block is not read here).
// SSBOs are fine here: a compute pass (DESIGN's machine facts keep them out of fragment shaders).
#extension GL_GOOGLE_include_directive : require
#include "incident.glsl"

layout(local_size_x = 64) in;

// SH order of the basis sums, the albedo and the result: 3 or 4 (one pipeline per order); ids 1–3:
// sl.glsl's (ShadeData::specialization: blocking is unused here, array size, influence).
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
const uint kCoeffs = kOrder * kOrder;

struct Sample {
  vec4 position;
  vec4 normal;
  vec4 basis[4];
};
struct Sphere {
  vec4 rest;
  vec4 posed;
  vec4 rotation[3];
  uvec4 range;
  vec4 indirect[9];
};
struct Gaunt {
  uint i;
  uint j;
  uint k;
  float value;
};

layout(std430, binding = 0) readonly buffer Samples { Sample samples[]; };
layout(std430, binding = 1) readonly buffer Spheres { Sphere spheres[]; };
layout(std430, binding = 2) readonly buffer Albedo { vec4 albedo[]; };
layout(std430, binding = 3) readonly buffer GauntTensor { Gaunt gaunt[]; };
layout(std140, binding = 4) uniform Lights { Light lights[kMaxLights]; };
layout(std140, binding = 5) uniform ShadowMatrices { mat4 shadowMatrices[kMaxShadowLayers]; };
layout(binding = 6) uniform sampler2DArrayShadow shadowAtlas;
#include "shadow.glsl"
layout(std430, binding = 7) writeonly buffer Intensity { uint intensity[]; };
#define SL_SET 0
#define SL_BINDING 8
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/probe_shadow.glsl"
#include "sl/local_light.glsl"

layout(push_constant) uniform Push {
  uint lightCount;
  uint shadowsOn;   // 0: every light unoccluded (the level does not name `shadows`)
  uint gaunts;      // entries in gaunt[]
  uint blockers;    // bit 0: the SLs (bindings 8–10) block the indirect light at the samples (§5.1);
                    // bit 1: and the point and spot lights (§7.3 local lights, sl/local_light.glsl)
} pc;

shared vec3 partial[64 * 16];
shared vec3 result[16];  // L^c_k before packing (Eq. 11's output)

void main() {
  uint sl = gl_WorkGroupID.x;
  uint lid = gl_LocalInvocationID.x;
  Sphere s = spheres[sl];
  mat3 rot = mat3(s.rotation[0].xyz, s.rotation[1].xyz, s.rotation[2].xyz);
  float scale = s.rest.w > 0.0 ? s.posed.w / s.rest.w : 1.0;

  vec3 acc[16];
  for (uint k = 0u; k < 16u; ++k) acc[k] = vec3(0.0);
  // The sample, light and Gaunt loops are `do … while` with guarded bodies: llvmpipe runs a `for`
  // body once more with every lane masked (README "Loop bodies III").
  uint t = lid;
  do {
    if (t < s.range.y) {
      Sample smp = samples[s.range.x + t];
      vec3 p = s.posed.xyz + rot * ((smp.position.xyz - s.rest.xyz) * scale);
      vec3 n = normalize(rot * smp.normal.xyz);
      vec3 sh[9];
      for (int k = 0; k < 9; ++k) sh[k] = s.indirect[k].rgb;
      uint i = 0u;
      do {
        if (i < pc.lightCount) {
          float v = 1.0;
          if (pc.shadowsOn != 0u) {
            uint type = uint(lights[i].positionType.w + 0.5);
            float dist = type == kLightDirectional ? 0.0 : length(lights[i].positionType.xyz - p);
            v = shadowVisibility(lights[i], p, n, dist);
          }
          if ((pc.blockers & 2u) != 0u && uint(lights[i].positionType.w + 0.5) != kLightDirectional)
            v *= slLocalVisibility(p, n, lights[i].positionType.xyz, lights[i].radiance.w);
          if (v > 0.0) incidentAddLight(lights[i], p, 0.0, v, sh);
        }
        ++i;
      } while (i < pc.lightCount);
      vec3 blocked = vec3(0.0);  // ΔE ≤ 0 of the indirect light (Eq. 3 and 6)
      if ((pc.blockers & 1u) != 0u) {
        vec3 ind[9];
        for (int k = 0; k < 9; ++k) ind[k] = s.indirect[k].rgb;
        blocked = slProbeShadow(p, n, ind);
      }
      vec3 L = max(shIrradiance9(sh, n) + blocked, vec3(0.0)) * (1.0 / 3.14159265358979324);  // L_p, Eq. 3
      for (uint k = 0u; k < kCoeffs; ++k) acc[k] += L * smp.basis[k / 4u][k % 4u];   // Eq. 10
    }
    t += 64u;
  } while (t < s.range.y);
  for (uint k = 0u; k < 16u; ++k) partial[lid * 16u + k] = acc[k];
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1u) {
    if (lid < stride)
      for (uint k = 0u; k < 16u; ++k) partial[lid * 16u + k] += partial[(lid + stride) * 16u + k];
    barrier();
  }
  // Eq. 11: one output coefficient per invocation, c_k = Σ C_ijk L_S,i c_S,j (sh::product's order).
  if (lid < 16u) {
    vec3 c = vec3(0.0);
    if (lid < kCoeffs) {
      uint e = 0u;
      do {
        if (e < pc.gaunts) {
          Gaunt g = gaunt[e];
          if (g.k == lid && g.i < kCoeffs && g.j < kCoeffs) c += g.value * partial[g.i] * albedo[sl * 16u + g.j].rgb;
        }
        ++e;
      } while (e < pc.gaunts);
    }
    result[lid] = clamp(c, vec3(-65504.0), vec3(65504.0));  // intensity_words.hpp kIntensityHalfMax
  }
  barrier();
  // Pack: invocation w < 24 writes word w = 8c + m, channel c of coefficients 2m and 2m + 1.
  if (lid < 24u) {
    uint c = lid / 8u, m = lid % 8u;
    intensity[sl * 24u + lid] = packHalf2x16(vec2(result[2u * m][c], result[2u * m + 1u][c]));
  }
}
