// SL hierarchy, two levels (Guerrero, Jeschke, Wimmer 2008, §7.3 Eq. 25–26): the GLSL of
// engine/gi/sl/hierarchy.hpp (the double-precision reference, whose header derives it). One parent
// SL per object o sits after the frame's SLs in sl_data.glsl's blocks, at index slCount() + o (its
// sphere from the CPU, update.hpp parentSpheres; its intensity from pass 1's reduction,
// shaders/sl/parent_intensity.comp; rotation the identity). No candidate walk visits it (the walks
// stop at slCount()).
//  - the tile pass (sl/hierarchy_ratio.comp, kInfluence = 0: uncut) forms Eq. 25's t_o at a tile's
//    centre x_C: the object's children's L̃Ṽ from the flat evaluation (slObjectTerms, every SL's
//    blockers in it) over the parent's own L̃Ṽ (slParentTerm);
//  - pass 2 (sl.frag with SL_HIERARCHY) adds Σ_o m_o(p) t_o ⊙ L̃_{p,P_o} Ṽ_{p,P_o} (Eq. 26 + ours).
// DEPARTURES from the reference: (1) m_o(p) = Σ_j (1 − s_j(p)²) r_j² / Σ_j r_j² — each child's
// share of the cut weighted by its area r_j² (the far-field weight parentOf gives it), the same for
// every tile, instead of hierarchy.hpp's e_j (child j's uncut term at x_C), which would need per-tile
// per-child storage; tests/unit/sl/hierarchy_gpu_test.cpp measures the difference. (2) The parent
// goes through rule 0 at its own influence ball F·r_P like every SL (pass 2's tiles list it only
// there, so far tiles still end); the reference leaves it uncut. Within F/2 · r_P of its centre the
// two agree.
// The tile pass's includer defines SL_OBJECT_TERMS (= kSlHierObjects) before including sl.glsl (for
// slParentRatio); pass 2 does not (its walk keeps no per-object sums).
#ifndef BOUNCE_SL_HIERARCHY_GLSL
#define BOUNCE_SL_HIERARCHY_GLSL

const uint kSlHierObjects = 4u;  // objects a hierarchy serves (engine/gi/sl/node.hpp kMaxHierarchyObjects)
const float kSlMinParentTerm = 1e-12;  // hierarchy.hpp kMinParentTerm: below it t = 1
const float kSlMaxParentRatio = 4.0;   // hierarchy.hpp kMaxParentRatio: t and τ clamped to [0, 4]

uint slParentCount() { return slHeader.z; }
uint slParentIndex(uint o) { return slCount() + o; }

// L̃_P Ṽ_P of object o's parent alone (no blockers) at receiver (p, n), after the receiver rules
// (rule 0 with kInfluence): the exact open cap times its average radiance — what slIrradianceAt
// gives for a lone SL (its ratio makes Eq. 23's Ṽ the exact one).
vec3 slParentTerm(uint o, vec3 p, vec3 n) {
  uint i = slParentIndex(o);
  vec4 cr;
  float d;
  if (!slSeenFrom(i, p, n, cr, d)) return vec3(0.0);
  vec3 dir = (cr.xyz - p) / d;
  float sn = min(1.0, cr.w / d);
  float open = slOpenCapExact(sn, dot(dir, n));
  return slAverageRadiance(i, asin(sn), dir) * open;
}

#ifdef SL_OBJECT_TERMS
// Eq. 25 at (x_C, n_C), per object and channel, after slIrradianceAt(x_C, n_C, …) over every SL
// (uncut) filled slObjectTerms: t_o = Σ_{j∈o} L̃_j Ṽ_j / (L̃_P Ṽ_P); 1 where the parent's term is
// below kSlMinParentTerm.
vec3 slParentRatio(uint o, vec3 xC, vec3 nC) {
  vec3 den = slParentTerm(o, xC, nC);
  vec3 num = slObjectTerms[min(o, kSlHierObjects - 1u)];
  vec3 t = vec3(den.r > kSlMinParentTerm ? num.r / den.r : 1.0, den.g > kSlMinParentTerm ? num.g / den.g : 1.0,
                den.b > kSlMinParentTerm ? num.b / den.b : 1.0);
  return clamp(t, vec3(0.0), vec3(kSlMaxParentRatio));
}
#endif

// m_o(p) for every object (departure 1 above): the area-weighted share of o's children that rule 0
// has cut at p. One loop over every SL at the loop counter's index (the same read in all lanes).
void slCutShares(vec3 p, out float m[kSlHierObjects]) {
  float total[kSlHierObjects];
  for (uint o = 0u; o < kSlHierObjects; ++o) {
    m[o] = 0.0;
    total[o] = 0.0;
  }
  uint count = slCount();
  uint j = 0u;
  do {
    if (j < count) {
      vec4 sp = slSphere(j);
      uint o = min(slObject(j), kSlHierObjects - 1u);
      float r = max(sp.w, 0.0);
      // Rule 0's radius scale s (sl.glsl slAdjust): 1 up to F/2 radii, 0 from F on.
      float sc = r > 0.0 && kInfluence > 0.0 ? clamp((kInfluence - length(sp.xyz - p) / r) / (0.5 * kInfluence), 0.0, 1.0) : 1.0;
      m[o] += (1.0 - sc * sc) * r * r;
      total[o] += r * r;
    }
    ++j;
  } while (j < count);
  for (uint o = 0u; o < kSlHierObjects; ++o) m[o] = total[o] > 0.0 ? m[o] / total[o] : 0.0;
}

// Eq. 26's parent part at receiver (p, n): Σ_o m_o(p) t_o ⊙ L̃_P Ṽ_P, for the objects whose parent
// bit (slParentIndex(o)) is set in the tile's candidates; t[o] the tile's Eq. 25 ratios.
vec3 slHierarchyAt(vec3 p, vec3 n, uvec4 candidates, in vec4 t[kSlHierObjects]) {
  float m[kSlHierObjects];
  slCutShares(p, m);
  vec3 e = vec3(0.0);
  uint parents = min(slParentCount(), kSlHierObjects);
  for (uint o = 0u; o < parents; ++o) {
    uint i = slParentIndex(o);
    bool listed = (candidates[i >> 5u] >> (i & 31u) & 1u) != 0u;
    if (listed && m[o] > 0.0) e += m[o] * t[o].rgb * slParentTerm(o, p, n);
  }
  return e;
}

#endif  // BOUNCE_SL_HIERARCHY_GLSL
