// SL pass 2's tile lists cut by the tile's receivers (issue 13; the analogue of DNRT's
// tile_cull.comp, against the receivers' world box rather than a depth range). binTiles
// (engine/gi/sl/tiles.hpp) lists an SL where its influence ball, radius F·r (receiver rule 0 of
// evaluate.hpp), meets the tile's frustum; many listed balls still miss every G-buffer point the
// tile's pixels shade, and each listed SL costs every 8-pixel block of the tile a walk body (sl.glsl
// slWalk: a per-lane sphere read and the receiver rules). An SL whose ball misses the box B that
// holds every receiver of the tile is culled by rule 0 at each of them (r → 0 at |c − p| ≥ F·r): it
// neither lights nor blocks there, so E(p) is the same, term for term (sl.glsl slIrradianceAt).
// The includer declares kInfluence (F; 0: no bound) and sl_data.glsl (slSphere).
#ifndef BOUNCE_SL_TILE_CUT_GLSL
#define BOUNCE_SL_TILE_CUT_GLSL

#include "mask.glsl"

// `mask` (SL i at bit i % 32 of word i / 32) less the SLs whose influence ball misses the box
// [lo, hi] (world, metres); nothing when the box is empty (lo > hi in any axis: a tile with no
// receiver, all background); unchanged with F = 0. Ball radius 1.001·F·r (binTiles' slack) plus
// 1e-5 of the box's largest coordinate: the stage that formed the box may round p differently from
// the fragment shader (same formula, another compiled shader), so the cut keeps an SL whose ball
// reaches within that of B.
uvec4 slBoxCut(vec3 lo, vec3 hi, uvec4 mask) {
  if (any(greaterThan(lo, hi))) return uvec4(0u);
  if (!(kInfluence > 0.0)) return mask;
  vec3 big = max(abs(lo), abs(hi));
  float slack = 1e-5 * max(big.x, max(big.y, big.z));
  uvec4 kept = mask;
  uvec4 rest = mask;
  do {
    uint i = maskPop(rest);
    if (i < kMaskEmpty) {
      vec4 sp = slSphere(i);
      float ball = 1.001 * kInfluence * max(0.0, sp.w) + slack;
      vec3 q = clamp(sp.xyz, lo, hi);  // B's point nearest the centre
      if (dot(sp.xyz - q, sp.xyz - q) > ball * ball) kept[i >> 5u] &= ~(1u << (i & 31u));
    }
  } while (rest != uvec4(0u));
  return kept;
}

#endif  // BOUNCE_SL_TILE_CUT_GLSL
