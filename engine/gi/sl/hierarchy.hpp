#pragma once
// SL hierarchy, two levels (§7.3 of ../shared/papers/sl-spherical-lights.md, Eq. 25–26; issue 13):
// the C++ reference, double precision, built on sl::evaluate (evaluate.hpp). Not on the GPU yet.
//
// Why: rule 0 (influence F, evaluate.hpp) fades each SL out between F/2 and F of ITS OWN radii, so a
// receiver beyond that band gets nothing from the object at all — on cornell-1 that cut hides most
// of SL's effect (README "SL accuracy with the reference's noise taken out"). The paper's far-field
// economy is not a cut but a coarser level of the hierarchy: far receivers see a parent SL.
//
// Two levels, ours where the paper is silent:
//  - one parent per object (`parentOf`): the bounding sphere of its children (centre = the mean of
//    the children's centres, radius = the largest |c_j − c_P| + r_j — not the minimal ball, but
//    every child is inside), rotation = identity (world frame), intensity
//        L^c_P = Σ_j (r_j / r_P)² R_j L^c_j                                            (ours)
//    i.e. the children's combined radiance: far away a sphere's irradiance is L·π r²/d² · cos, so
//    this keeps the far field's total (overlapping children are counted twice; t below corrects the
//    scale). R_j rotates child j's local SH into the world (sh::Rotation).
//    Made from the children's intensities, i.e. after pass 1: on the GPU it belongs at the end of
//    pass 1 (a reduction over the object's SLs), since the intensities never come back to the CPU.
//  - the reflection ratio (Eq. 25) once per receiver cluster (a screen tile) at its centre x_C,
//    per RGB channel:
//        t_P = Σ_j L̃_{x_C,S_j} Ṽ_{x_C,S_j} / (L̃_{x_C,S_P} Ṽ_{x_C,S_P})                 (Eq. 25)
//    the children's terms from the FLAT evaluation of every light without the cut (so their
//    blockers are in t), the parent's alone and unblocked. t = 1 where a channel's denominator is
//    below kMinParentTerm (both ~0 then).
//  - Eq. 26 at a receiver p of that cluster, with the same fade band as rule 0 (continuous):
//        E(p) = Σ_i L̃_i Ṽ_i |cut(p)  +  Σ_o m_o(p) · t_o ⊙ L̃_{p,P_o} Ṽ_{p,P_o}           (Eq. 26 + ours)
//        m_o(p) = Σ_{j∈o} (1 − s_j(p)²) e_j / Σ_{j∈o} e_j
//    s_j(p) = clamp((F − |c_j − p|/r_j) / (F/2), 0, 1) is rule 0's radius scale (the cut child keeps
//    ~s² of its solid angle), e_j the luminance of child j's uncut term at x_C: the parent stands in
//    for exactly the share of the children the cut has taken away. Inside every child's band
//    (s = 1) nothing changes; beyond all of them (s = 0) E = t ⊙ parent, and at p = x_C that is the
//    flat, uncut sum exactly.
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/probe_shadow.hpp"

namespace bounce::gi::sl {

// Below this parent term (W/m², per channel) Eq. 25 is not formed and t = 1.
inline constexpr double kMinParentTerm = 1e-12;
// t and τ are clamped to [0, kMaxParentRatio] (ours, as probe_shadow.hpp clamps its ratio): at a
// cluster centre where the receiver rules shrink the parent (a receiver inside or below the bounding
// sphere) but not its smaller children, the ratio is a small denominator's, and it would scale the
// parent over the whole tile — measured on cornell-1 (README "SL hierarchy on the GPU"): a bright
// seam of tiles and a corrected error of 2.6 without the clamp.
inline constexpr double kMaxParentRatio = 4.0;

// The parent's sphere (the header's bounding sphere: centre the children's mean centre, radius the
// largest |c_j − c_P| + r_j). Non-empty; else InternalError. Shared by parentOf and the per-frame
// parents of pass 2 (update.hpp parentSpheres).
Sphere parentSphere(std::span<const Sphere> children);

// The parent SL of one object's children (all with the same `object`, non-empty; else InternalError).
Light parentOf(std::span<const Light> children);

struct Parent {
  Light light;                  // parentOf(the object's children)
  glm::dvec3 ratio{1.0};        // t (Eq. 25) at the cluster centre, per channel
  std::vector<double> share;    // e_j / Σ e (per child of this object, in `lights` order)
};

// Per receiver cluster: one parent per object of `lights` (in increasing `object` id) with its t and
// the children's shares, all at the cluster centre (xC, nC). settings.influence is ignored here
// (Eq. 25 is against the uncut children).
std::vector<Parent> clusterParents(std::span<const Light> lights, const glm::dvec3& xC, const glm::dvec3& nC,
                                   const EvalSettings& settings);

// Eq. 26 at receiver (p, n) of that cluster: the flat evaluation with settings.influence (> 0, the cut)
// plus each object's parent weighted by m_o(p). With settings.influence = 0 nothing is cut and this
// equals evaluate(lights, p, n, settings).irradiance.
glm::dvec3 evaluateHierarchy(std::span<const Light> lights, std::span<const Parent> parents, const glm::dvec3& p,
                             const glm::dvec3& n, const EvalSettings& settings);

// The same two levels for `sl.shadow` (probe_shadow.hpp, Eq. 6 on the probes' light; ours — the
// paper's Eq. 25–26 are for the diffuse reflection only). Why: on cornell-1 the cut's loss is mostly
// the SHADOW (README "SL accuracy with the reference's noise taken out": shadow alone 1.006 → 0.943
// without the cut, bounce alone 1.016 → 1.108, i.e. worse), so a hierarchy of the reflection alone
// would not bring the uncut gain. Per object o and cluster:
//   τ_o = ΔE(o's children, uncut, x_C) / ΔE(P_o alone, x_C)          (per channel; 1 below kMinParentTerm)
//   ΔE(p) = ΔE(every light, cut by rule 0, p) + Σ_o m_o(p) τ_o ⊙ ΔE(P_o alone, p)
// with m_o as above but the children weighted by their caps' exact amounts X_j = π sin²θ_j (n·d_j)₊
// at x_C (probe_shadow.hpp's X). The objects' far shadows are summed, not multiplied: far away they
// are small and exp is additive there (probe_shadow.hpp "Overlapping spheres"). The sum is clamped
// to [−E_u, 0] per channel like ΔE itself.
struct ShadowParent {
  Light light;
  glm::dvec3 ratio{1.0};      // τ at the cluster centre
  std::vector<double> share;  // X_j / Σ X (per child of this object, in `lights` order)
};

// `radianceC`: the probes' radiance SH at x_C (4 or 9 RGB). settings.influence is ignored (uncut).
std::vector<ShadowParent> clusterShadowParents(std::span<const Light> lights, const glm::dvec3& xC,
                                               const glm::dvec3& nC, std::span<const glm::dvec3> radianceC,
                                               const ShadowSettings& settings);

// ΔE at (p, n) of that cluster, `radiance` the probes' SH at p; settings.influence > 0 is the cut.
glm::dvec3 probeShadowHierarchy(std::span<const Light> lights, std::span<const ShadowParent> parents,
                                const glm::dvec3& p, const glm::dvec3& n, std::span<const glm::dvec3> radiance,
                                const ShadowSettings& settings);

}  // namespace bounce::gi::sl
