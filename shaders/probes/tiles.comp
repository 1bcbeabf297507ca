#version 450
#extension GL_GOOGLE_include_directive : require
// Pass `probes.tiles` (engine/gi/probes/node.cpp): each probe's irradiance E(n) (sh.glsl
// shIrradiance9 of its SH, read exactly as probes.frag's SH path reads it: probe_sh.glsl
// probeAddSh from the packed uniform block) at the normals of its octahedral tile's texels
// (probes/probe_tiles.glsl), into an RGBA16F image the probes pass taps once per probe. One
// workgroup per probe (workgroup (x, row) is probe x + count.x·row, probe_tiles.glsl
// probeTileOrigin), PROBE_TILE × PROBE_TILE/2 invocations (128: the Vulkan minimum of
// maxComputeWorkGroupInvocations, so no device limit is assumed), each writing two texels of the
// square, rows y and y + PROBE_TILE/2, from one read of the SH (border texels repeat their source
// texel's direction). Every frame after `probes.relight` rewrote the block; once for a baked volume
// (216 probes: 55 296 texels).
#include "sh.glsl"
#include "probes/probe_tiles.glsl"

layout(local_size_x = PROBE_TILE, local_size_y = PROBE_TILE / 2) in;  // one probe's square, two texels each

layout(constant_id = 0) const int kCoeffs = 9;  // order²: 4 or 9
const bool kShInUbo = true;                     // this pass runs only when the SH fit the block
const bool kMomentsInUbo = false;

// probe_sh.glsl's declarations; only the block is read (kShInUbo), the samplers are its image path.
layout(binding = 0) uniform sampler2D probeSh;
layout(binding = 1) uniform sampler2D probeMoments;
layout(std140, binding = 2) uniform ProbeShBlock { uvec4 probeShUbo[4096]; };
layout(std140, binding = 3) uniform ProbeMomentsBlock { uvec4 probeMomentsUbo[4096]; };
layout(binding = 4, rgba16f) uniform writeonly image2D tiles;

layout(push_constant) uniform Push {  // probes::ProbePush
  vec4 originSpacing;
  ivec4 countOrder;
  vec4 bias;
} pc;

#define PROBE_SH_UBO
#include "probes/probe_sh.glsl"

// The largest finite half: E past it would store +-Inf in the RGBA16F texel, and probes.frag's
// w·tap with w = 0 would make 0·Inf = NaN of it; clamped, a too-bright probe saturates instead.
const float kHalfMax = 65504.0;

void main() {
  const int probe = int(gl_WorkGroupID.x + gl_WorkGroupID.y * uint(pc.countOrder.x));
  vec3 L[9];
  for (int i = 0; i < 9; ++i) L[i] = vec3(0.0);
  probeAddSh(probe, 1.0, L);
  const ivec2 origin = ivec2(gl_WorkGroupID.xy) * PROBE_TILE;
  for (int half_ = 0; half_ < 2; ++half_) {
    const ivec2 t = ivec2(gl_LocalInvocationID.x, int(gl_LocalInvocationID.y) + half_ * (PROBE_TILE / 2));
    const vec3 e = clamp(shIrradiance9(L, probeTileDirection(t)), vec3(-kHalfMax), vec3(kHalfMax));
    imageStore(tiles, origin + t, vec4(e, 0.0));
  }
}
