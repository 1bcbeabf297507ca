// The baked volume's radiance SH at a receiver, read as the probes pass reads it (texelFetch from
// the probe images, DESIGN.md: no SSBOs); shared by probes/probes.frag and the SL shadow on the
// probes' light (sl/probe_shadow.frag), so both see the same L at a pixel (up to the packing
// where probes.frag reads its uniform block, below, and, where probes.frag taps the irradiance
// tiles instead (kTiles), up to their interpolation error E_t: the SL shadow's E_u + ΔE is then
// E_shadowed within E_t, sl/probe_shadow_frag.glsl).
//
// The includer declares, before including this file:
//   const int kCoeffs (order²: 4 or 9, a specialization constant);
//   sampler2D probeSh (RGBA32F) and probeMoments (RG32F), laid out by engine/gi/probes/node.cpp:
//     probe p = x + count.x·row sits in texel row `row`, its data in `slots` texels from slots·x on:
//     SH, kTexels texels packing L_0.rgb, L_1.rgb, … then the valid flag, 4 floats a texel (order 3:
//     7 texels, not 9: the gathers are most of the pass); moments, texel (bin + PROBE_VIS_BINS·x, row)
//     = (mean, mean square) (m, m²);
//   a push-constant block `pc` with probes::ProbePush's layout (engine/gi/probes/node.hpp):
//     vec4 originSpacing (xyz: probe (0,0,0) position, w: spacing, m), ivec4 countOrder (xyz: probes
//     per axis, w: SH order), vec4 bias (x: normal bias (m), y: view bias (m), z: Chebyshev variance
//     floor (m²), w: includer's flag).
#ifndef BOUNCE_PROBE_SH_GLSL
#define BOUNCE_PROBE_SH_GLSL

const int kTexels = (3 * kCoeffs + 4) / 4;  // SH texels per probe: 3 floats a coefficient + valid

ivec2 probeTexel(int probe, int slot, int slotsPerProbe) {
  return ivec2(slot + slotsPerProbe * (probe % pc.countOrder.x), probe / pc.countOrder.x);
}

// Probe p's SH texel t in the image.
vec4 probeShTexel(int probe, int t) { return texelFetch(probeSh, probeTexel(probe, t, kTexels), 0); }

#ifdef PROBE_SH_UBO
// An includer that defines PROBE_SH_UBO also declares `const bool kShInUbo` and
// `uniform ProbeShBlock { uvec4 probeShUbo[]; }`: the image's values packed when the volume fits
// the block (engine/gi/probes/node.cpp shPackedWords): probe p's word j at texel kPackedTexels·p +
// j / 4, component j % 4: word 0 = halves (L_0.r, L_0.g), word 1 = halves (L_0.b, s), words 2… =
// the 3·(kCoeffs − 1) values L_i.c / (s·L_0.c) (i ≥ 1) as snorm bytes, 4 a word, low byte first.
// 8 words a probe at order 3 (5 at order 2) instead of 16 halves: on llvmpipe an indexed uniform
// array is a per-lane load per scalar, the dominant cost of the pass (README "DNRT and probes cost,
// session 8"). Each L_i.c moves by at most ½·s·|L_0.c|/127 (E by node.cpp
// packedShIrradianceError; test ProbeGpu.ShFromTheUniformBlockIsTheImagePathWithinItsRounding).
const int kPackedTexels = 2;
const int kPackedWords = 2 + (3 * (kCoeffs - 1) + 3) / 4;
#endif

bool probeValid(int probe) {
#ifdef PROBE_SH_UBO
  if (kShInUbo) {
    // The block's valid bits after the last probe's texels (engine/gi/probes/node.cpp
    // shPackedWords): one word a lane. Reading the texel holding the valid half cost ~0.25 of
    // the lighting pass, this ~0.1 (probeWeights runs before probeRadianceSh's loads of that texel,
    // so they were never shared; README "DNRT and probes cost, session 8").
    int bits = kPackedTexels * pc.countOrder.x * pc.countOrder.y * pc.countOrder.z + probe / 32;
    return ((probeShUbo[bits].x >> uint(probe % 32)) & 1u) != 0u;
  }
#endif
  return probeShTexel(probe, kTexels - 1)[(3 * kCoeffs) % 4] != 0.0;
}

// Probe i's visibility moments in bin b: (mean, mean square) of the hit distance (m, m²). An
// includer that defines PROBE_SH_UBO also declares `const bool kMomentsInUbo` and
// `uniform ProbeMomentsBlock { uvec4 probeMomentsUbo[]; }`: when the volume fits it
// (engine/gi/probes/node.cpp momentHalfWords), bin b of probe i is word 64·i + b, packHalf2x16 of
// (mean, standard deviation) — σ, not the mean square, so a half keeps 2⁻¹¹ of it where the mean
// square minus the squared mean would cancel. One uniform word per lane instead of an RG32F
// texelFetch: about a fifth of the pass on llvmpipe (README "What costs what on lavapipe").
vec2 probeMomentsAt(int probe, int bin, int bins) {  // bins: PROBE_VIS_BINS, declared below
#ifdef PROBE_SH_UBO
  if (kMomentsInUbo) {
    int w = bins * probe + bin;
    vec2 h = unpackHalf2x16(probeMomentsUbo[w / 4][w % 4]);
    return vec2(h.x, h.y * h.y + h.x * h.x);
  }
#endif
  return texelFetch(probeMoments, probeTexel(probe, bin, bins), 0).rg;
}

#ifdef PROBE_TILES
// An includer that defines PROBE_TILES also declares `const bool kTiles` and `sampler2D probeTiles`
// (bilinear): the probes' irradiance tiles (probes/probe_tiles.glsl, written by probes/tiles.comp).
#include "probes/probe_tiles.glsl"
#endif

#define PROBE_DATA_PARAM
#define PROBE_DATA_ARG
#define PROBE_VALID(i) probeValid(i)
#define PROBE_MOMENTS(i, b) probeMomentsAt(i, b, PROBE_VIS_BINS)
#include "probes/probe_weights.glsl"

// L += w · probe pk's SH (coefficients ≥ kCoeffs untouched).
void probeAddSh(int pk, float w, inout vec3 L[9]) {
#ifdef PROBE_SH_UBO
  if (kShInUbo) {  // a specialization constant: the other path is compiled out
    uint word[8];  // only the kPackedWords used words are loaded (constant components once unrolled)
    for (int j = 0; j < kPackedWords; ++j) word[j] = probeShUbo[kPackedTexels * pk + j / 4][j % 4];
    vec2 rg = unpackHalf2x16(word[0]), bs = unpackHalf2x16(word[1]);
    vec3 l0 = vec3(rg, bs.x);
    L[0] += w * l0;
    vec3 scale = (w * bs.y) * l0;  // L_i = scale ⊙ fraction_i, weighted
    float f[24];                   // 3 · (kCoeffs − 1) ≤ 24
    for (int j = 2; j < kPackedWords; ++j) {
      vec4 q = unpackSnorm4x8(word[j]);
      f[4 * j - 8] = q.x, f[4 * j - 7] = q.y, f[4 * j - 6] = q.z, f[4 * j - 5] = q.w;
    }
    for (int i = 1; i < kCoeffs; ++i) L[i] += scale * vec3(f[3 * i - 3], f[3 * i - 2], f[3 * i - 1]);
    return;
  }
#endif
  float f[28];  // kTexels · 4 ≤ 28
  for (int t = 0; t < kTexels; ++t) {
    vec4 v = probeShTexel(pk, t);
    f[4 * t] = v.x, f[4 * t + 1] = v.y, f[4 * t + 2] = v.z, f[4 * t + 3] = v.w;
  }
  for (int i = 0; i < kCoeffs; ++i) L[i] += w * vec3(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
}

// L = Σ_k w_k L^k at surface point x with unit normal n, v the unit vector to the eye (the lookup
// point is biased along both, probe_weights.glsl); coefficients ≥ kCoeffs are 0.
// One loop over the cell corners of non-zero trilinear weight (a receiver on a face of the volume
// has 4, on an edge 2): each computes its probe's weight (probe_weights.glsl probeCornerWeight, the
// CPU API's code) and adds its weighted SH; the sum is divided by Σ w_k once at the end, as E is
// linear in L (probeWeights normalises first: the same value up to float rounding, ≤ 1 fp16 step
// in the image). llvmpipe skips no branch but leaves a loop when none of its 8 lanes is still in
// it, so a group of wall pixels runs 4 corners, not 8, of the weights too (session 9 looped the SH
// only, and picking probe[k], weight[k] out of arrays by selects cost what the skipped weights
// saved; here the corner is arithmetic on k). do-while with the test at the end (README "What costs
// what on lavapipe"); a lane may pass through the body after its own last corner (`live` false:
// it adds 0). Session 11: probes / lighting, README "Probes cost, session 11".
// With PROBE_TILES and kTiles, L[0] returns Σ_k w_k E_k(n) / Σ w_k instead (one bilinear tap of
// probe k's irradiance tile per corner, probe_tiles.glsl) and L[1…] stay 0.
void probeRadianceSh(vec3 x, vec3 n, vec3 v, out vec3 L[9]) {
  vec3 q = x + pc.bias.x * n + pc.bias.y * v;
  const ivec3 count = pc.countOrder.xyz;
  vec3 g = probeGridCoord(count, pc.originSpacing.xyz, pc.originSpacing.w, q);
  ivec3 base = probeCellBase(count, g);
  vec3 f = g - vec3(base);
  for (int i = 0; i < 9; ++i) L[i] = vec3(0.0);
#ifdef PROBE_TILES
  const vec2 tile = probeTileCoord(n);  // the same place in every probe's square
  const vec2 invSize = 1.0 / vec2(PROBE_TILE * count.x, PROBE_TILE * count.y * count.z);
#endif
  uint nz = 0u;
  for (int k = 0; k < 8; ++k) nz |= probeTrilinear(f, k) > 0.0 ? (1u << uint(k)) : 0u;
  float sum = 0.0;
  do {
    const bool live = nz != 0u;
    int k = max(findLSB(nz), 0);
    nz &= nz - 1u;
    ivec3 c = probeCorner(count, base, k);
    int idx = probeIndex(count, c);
    float w = probeCornerWeight(pc.originSpacing.xyz, pc.originSpacing.w, pc.bias.z, q, n, c, idx, probeTrilinear(f, k));
    w = live ? w : 0.0;
    sum += w;
#ifdef PROBE_TILES
    if (kTiles) {  // a specialization constant
      // w = 0 (a dead lane, a culled corner) adds exactly 0 even under a non-finite texel (0·Inf =
      // NaN): a select (mix with a bvec is OpSelect), not a branch. tiles.comp clamps to the
      // largest half, so this guards what that clamp cannot (an Inf/NaN SH).
      const vec3 tap = textureLod(probeTiles, (vec2(probeTileOrigin(c, count)) + tile) * invSize, 0.0).rgb;
      L[0] += mix(vec3(0.0), w * tap, bvec3(w > 0.0));
    } else
#endif
      probeAddSh(idx, w, L);
  } while (nz != 0u);
  float inv = sum > 0.0 ? 1.0 / sum : 0.0;
  for (int i = 0; i < kCoeffs; ++i) L[i] *= inv;
}

#endif  // BOUNCE_PROBE_SH_GLSL
