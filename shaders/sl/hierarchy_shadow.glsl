// SL hierarchy for "sl.shadow" (engine/gi/sl/hierarchy.hpp clusterShadowParents /
// probeShadowHierarchy; ours — the paper's Eq. 25–26 are for the reflection only): per object o and
// tile, τ_o = ΔE(o's children, uncut, x_C) / ΔE(P_o alone, x_C) per channel (1 below
// kSlMinParentTerm), and at a receiver ΔE(p) = clamp(ΔE(every SL, cut by rule 0) + Σ_o m_o(p) τ_o ⊙
// ΔE(P_o alone, p), −E_u, 0). Why the shadow needs it: on cornell-1 the uncut gain is the shadow's
// (README "SL accuracy with the reference's noise taken out"). Same departures as sl/hierarchy.glsl
// (m_o by r_j² instead of the caps' X_j at x_C; the parent cut by rule 0 at F·r_P).
// Needs sl.glsl, sl/hierarchy.glsl and sl/probe_shadow.glsl included first.
#ifndef BOUNCE_SL_HIERARCHY_SHADOW_GLSL
#define BOUNCE_SL_HIERARCHY_SHADOW_GLSL

uvec4 slBit(uint i) {
  uvec4 b = uvec4(0u);
  b[i >> 5u] = 1u << (i & 31u);
  return b;
}

// ΔE of object o's parent alone at (p, n).
vec3 slParentShadow(uint o, vec3 p, vec3 n, in vec3 L[9]) {
  uint i = slParentIndex(o);
  return slProbeShadow(p, n, L, slBit(i), i + 1u);
}

// τ_o at the cluster centre (x_C, n_C) with the probes' radiance L there (the tile pass, kInfluence = 0).
vec3 slShadowParentRatio(uint o, vec3 xC, vec3 nC, in vec3 L[9]) {
  uvec4 mine = uvec4(0u);
  uint count = min(slCount(), kSpheres);
  for (uint j = 0u; j < count; ++j)
    if (slObject(j) == o) mine |= slBit(j);
  vec3 num = slProbeShadow(xC, nC, L, mine, count);
  vec3 den = slParentShadow(o, xC, nC, L);
  vec3 t = vec3(abs(den.r) > kSlMinParentTerm ? num.r / den.r : 1.0, abs(den.g) > kSlMinParentTerm ? num.g / den.g : 1.0,
                abs(den.b) > kSlMinParentTerm ? num.b / den.b : 1.0);
  return clamp(t, vec3(0.0), vec3(kSlMaxParentRatio));
}

// E_u = ρ_n ∗ L at n (probe_shadow.glsl's `unshadowed`): the clamp's floor.
vec3 slUnshadowed(vec3 n, in vec3 L[9]) {
  float y[9];
  shEval9(n, y);
  vec3 e = SH_A0 * y[0] * L[0];
  for (int k = 1; k < 4; ++k) e += SH_A1 * y[k] * L[k];
  for (int k = 4; k < 9; ++k) e += SH_A2 * y[k] * L[k];
  return e;
}

// ΔE at receiver (p, n): `cut` = slProbeShadow over the tile's candidates (rule 0 at kInfluence), plus
// each listed parent's share; tau[o] the tile's τ.
vec3 slShadowHierarchyAt(vec3 p, vec3 n, in vec3 L[9], uvec4 candidates, in vec4 tau[kSlHierObjects], vec3 cut) {
  float m[kSlHierObjects];
  slCutShares(p, m);
  vec3 delta = cut;
  uint parents = min(slParentCount(), kSlHierObjects);
  for (uint o = 0u; o < parents; ++o) {
    uint i = slParentIndex(o);
    bool listed = (candidates[i >> 5u] >> (i & 31u) & 1u) != 0u;
    if (listed && m[o] > 0.0) delta += m[o] * tau[o].rgb * slParentShadow(o, p, n, L);
  }
  return clamp(delta, -max(slUnshadowed(n, L), vec3(0.0)), vec3(0.0));
}

#endif  // BOUNCE_SL_HIERARCHY_SHADOW_GLSL
