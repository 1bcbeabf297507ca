#pragma once
// The objects' shared occlusion in the GPU's blocked light (issue 14, README RTF "Seventh pass",
// "Tenth pass").
//
// The GPU pass adds each object's blocked term on its own (additive blending); Algorithm 1 (§5)
// multiplies the objects' visibilities, and for two objects
//   1 − V_A V_B = (1 − V_A) + (1 − V_B) − (1 − V_A)(1 − V_B),
// so the sum counts the directions both objects hide twice. The shading record's light is the
// indirect light at o (its shape and level, update.hpp packObject); this per-sample factor takes
// half the shared part off each object's term (the other half off the other object's), with the
// light across the hidden directions taken as uniform:
//   s_A(p) = max(0, 1 − ½ Σ_{B≠A} ∫(1 − V_A)(1 − V_B) dω / ∫(1 − V_A) dω),
// V_A the OOF of A's field sample p, V_B B's OOF looked up at p (Eq. 10's weights, the field's end
// included). Where no other object's field reaches p, s = 1: the light at o, unscaled. The ξ pass
// multiplies the sample's blocked light by it (shaders/rtf/xi.comp, buffer BlockedScale), the same
// slot the former per-sample light level used (blockedScale in update.hpp, kept for rtf_parts).
//
// The shared integral ∫(1 − V_A)(1 − V_B) dω is taken with each object's hidden set as a spherical CAP
// (ours; README RTF "Tenth pass"): the cap's solid angle is the OOF's ∫(1 − V) dω = √(4π)·(1 − V)_0 (sr,
// exact), its axis the direction of (1 − V)'s l = 1 vector (the hidden set's mean direction), and the
// two caps' intersection is closed-form (capIntersection). Until session 12 it was the order-4 SH
// product Σ_j (1 − V_A)_j (1 − V_B)_j, which blurs a compact hidden set over ≈ 60°: for two objects
// that hide disjoint sets 30–50° apart it reports a shared part of 0.03–0.10 of A's (the exact one is
// 0), and for two aligned ones it reports 0.3 where the exact one is 1 (README "Tenth pass"'s table).
// On cornell-5 (five objects, fields 4.7 η wide, mostly far apart) those false shares summed to a
// 2–9 % loss of blocked light (README RTF "Ninth pass": the brute force's blocked light 0.71–0.92).
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/rtf/evaluate.hpp"

namespace bounce::gi::rtf {

// The solid angle (sr) two spherical caps share: half-angles α_a, α_b given by their cosines, axes
// γ apart (cos γ). Any α in [0, π] (a cap of α > π/2 is more than a hemisphere); 0 if disjoint, the
// smaller cap's 2π(1 − cos α) if it lies inside the other. Tovchigrechko & Vakser (2001), Eq. for two
// caps with α_a + α_b ≤ π; beyond that through the complements: |A ∩ B| = |A| + |B| − 4π + |Aᶜ ∩ Bᶜ|.
float capIntersection(float cosA, float cosB, float cosGamma);

// The cap (1 − V) stands for, from its order-4 SH coefficients (l = 0 and 1; coefficients 1, 2, 3 are
// the y, z, x lobes): .xyz the axis (unit; +z where the l = 1 vector vanishes), .w cos α with
// 2π(1 − cos α) = √(4π)·(1 − V)_0, clamped to [−1, 1].
glm::vec4 hiddenCap(const float* notV);

// One vec4 (s, s, s, 1) per sample of objects[a]'s field, in field.hpp's sample order.
std::vector<glm::vec4> sharedOcclusionScale(std::span<const Object> objects, std::size_t a);

}  // namespace bounce::gi::rtf
