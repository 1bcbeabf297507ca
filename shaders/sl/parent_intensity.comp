#version 450
// SL hierarchy, two levels (Guerrero, Jeschke, Wimmer 2008, §7.3; engine/gi/sl/hierarchy.hpp, which
// derives it): each object's parent SL intensity, a reduction at the end of pass 1 (after
// intensity.comp, same "sl.intensity" pass), since the children's L^c never come back to the CPU:
//   L^c_P = Σ_j (r_j / r_P)² R_j L^c_j                       (hierarchy.hpp parentOf, ours)
// the children's combined far-field radiance, in the world frame (the parent's rotation is the
// identity). R_j is child j's SL-local → world rotation applied to its SH (band-diagonal; band l's
// (2l+1)² matrix, row-major, from the CPU: engine/math/sh_rotate.hpp sh::Rotation, the same
// matrices parentOf uses, so no rotation recurrence is re-derived here).
// One workgroup per object, invocation k < order² forms coefficient k, invocations < 24 pack.
// Data (std430): intensity = uint[SL·24 + w], pass 1's fp16 pairs (engine/gi/sl/intensity_words.hpp),
// children read, parents written at their own indices (disjoint); objects[o] = (first child, child
// count, parent's SL index, 0); children = float[SL·84]: [0] = (r_j / r_P)², [1 … 9] band 1,
// [10 … 34] band 2, [35 … 83] band 3 of R_j's SH rotation.
layout(local_size_x = 32) in;

layout(constant_id = 0) const uint kOrder = 4u;

layout(std430, binding = 0) buffer Intensity { uint intensity[]; };
layout(std430, binding = 1) readonly buffer Objects { uvec4 parentObjects[]; };
layout(std430, binding = 2) readonly buffer Children { float children[]; };

const uint kChildFloats = 84u;
shared vec3 result[16];

// L^c_k of SL `sl` (fp16 pair word 8c + k/2, low half for even k).
vec3 coefficient(uint sl, uint k) {
  vec3 v;
  for (uint c = 0u; c < 3u; ++c) {
    vec2 pair = unpackHalf2x16(intensity[sl * 24u + 8u * c + k / 2u]);
    v[c] = (k % 2u) == 0u ? pair.x : pair.y;
  }
  return v;
}

void main() {
  uvec4 object = parentObjects[gl_WorkGroupID.x];
  uint k = gl_LocalInvocationID.x;
  if (k < 16u) {
    vec3 acc = vec3(0.0);
    if (k < kOrder * kOrder) {
      uint l = k < 1u ? 0u : (k < 4u ? 1u : (k < 9u ? 2u : 3u));
      uint base = l * l, n2 = 2u * l + 1u, row = k - base;
      uint offset = l == 1u ? 1u : (l == 2u ? 10u : 35u);
      for (uint j = object.x; j < object.x + object.y; ++j) {
        float w = children[j * kChildFloats];
        if (l == 0u) {
          acc += w * coefficient(j, 0u);  // band 0 is rotation-invariant
          continue;
        }
        vec3 rotated = vec3(0.0);
        for (uint c = 0u; c < n2; ++c) rotated += children[j * kChildFloats + offset + row * n2 + c] * coefficient(j, base + c);
        acc += w * rotated;
      }
    }
    result[k] = clamp(acc, vec3(-65504.0), vec3(65504.0));  // intensity_words.hpp kIntensityHalfMax
  }
  barrier();
  if (k < 24u) {
    uint c = k / 8u, m = k % 8u;
    intensity[object.z * 24u + k] = packHalf2x16(vec2(result[2u * m][c], result[2u * m + 1u][c]));
  }
}
