#version 450
// The GPU face of engine/anim/skinning.cpp (MorphJob then SkinningJob; tests/unit/skinning holds
// the two equal): morph targets, then linear blend skinning with up to 8 influences, once per
// frame per deformed instance, into the frame's posed-vertex buffer that the G-buffer, shadow,
// debug-view and entity-id passes all read.
//   Morph (glTF 2.0 §3.7.2.2): p = p₀ + Σ_t w_t·Δp_t,  n = n₀ + Σ_t w_t·Δn_t  (targets in order,
//     zero weights skipped, as on the CPU; n left unnormalised, as MorphJob leaves it).
//   Skin: S = Σ w_i·J_i (JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1, summed in the CPU's order),
//     p' = S·p,  n' = normalize(inverse(transpose(S₃ₓ₃))·n).
// A morph-only instance (pc.skinned == 0) writes the morphed p and n in its node's frame.
layout(local_size_x = 64) in;

// One cooked vertex (GpuScene packs it at load): position + u, normal + v, joints as u16 pairs
// (x = j0 | j1 << 16, y = j2 | j3 << 16, z = j4 | j5 << 16, w = j6 | j7 << 16), weights 0-3, 4-7.
struct SkinVertex {
  vec4 positionU;
  vec4 normalV;
  uvec4 joints;
  vec4 weights0;
  vec4 weights1;
};

layout(std430, set = 0, binding = 0) readonly buffer Source { SkinVertex src[]; };
layout(std430, set = 0, binding = 1) readonly buffer Joints { mat4 joints[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Posed { float dst[]; };  // MeshVertex: 8 floats
// The mesh's morph targets, target-major: Δp of target t, vertex i at 2·(t·vertexCount + i), Δn
// right after (xyz; w unused). Not read when targetCount is 0 (another buffer is bound then).
layout(std430, set = 0, binding = 3) readonly buffer Morph { vec4 deltas[]; };
// Every instance's morph weights this frame, back to back (RenderWorld::morphWeights).
layout(std430, set = 0, binding = 4) readonly buffer MorphWeights { float morphWeights[]; };

layout(push_constant) uniform Push {
  uint vertexCount;
  uint jointBase;    // this instance's first joint matrix in `joints`
  uint dstBase;      // this instance's first vertex in `dst`
  uint weightBase;   // this instance's first weight in `morphWeights`
  uint targetCount;  // the mesh's morph targets (0: none)
  uint skinned;      // 0: morph only
} pc;

uint jointIndex(uvec4 packed, int k) { return (packed[k >> 1] >> (16 * (k & 1))) & 0xffffu; }

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.vertexCount) return;
  const SkinVertex v = src[i];
  vec3 p = v.positionU.xyz, n = v.normalV.xyz;
  // do…while with a guarded body: llvmpipe runs a `for` body once more with every lane masked
  // (README "Loop bodies III"), so n targets cost n bodies, not n + 1.
  uint t = 0u;
  do {
    if (t < pc.targetCount) {
      const float w = morphWeights[pc.weightBase + t];
      if (w != 0.0) {
        const uint d = 2u * (t * pc.vertexCount + i);
        p += w * deltas[d].xyz;
        n += w * deltas[d + 1u].xyz;
      }
    }
    ++t;
  } while (t < pc.targetCount);
  if (pc.skinned != 0u) {
    mat4 s = mat4(0.0);
    for (int k = 0; k < 4; ++k) {
      // Zero weights are skipped, as on the CPU: their joint index need not be valid.
      if (v.weights0[k] != 0.0) s += v.weights0[k] * joints[pc.jointBase + jointIndex(v.joints, k)];
      if (v.weights1[k] != 0.0) s += v.weights1[k] * joints[pc.jointBase + jointIndex(v.joints, k + 4)];
    }
    p = (s * vec4(p, 1.0)).xyz;
    const vec3 sn = transpose(inverse(mat3(s))) * n;
    const float len = length(sn);
    n = len > 0.0 ? sn / len : n;
  }
  const uint o = (pc.dstBase + i) * 8u;
  dst[o + 0] = p.x;
  dst[o + 1] = p.y;
  dst[o + 2] = p.z;
  dst[o + 3] = n.x;
  dst[o + 4] = n.y;
  dst[o + 5] = n.z;
  dst[o + 6] = v.positionU.w;
  dst[o + 7] = v.normalV.w;
}
