#pragma once
// SL local lights (Guerrero, Jeschke, Wimmer 2008, §7.3: "Local lights can be treated like SLs";
// issue 13 item 4): a point or spot light of radius R (scene::Light::radius) is a sphere like an SL,
// and the SLs closer to the receiver than it block it with the SH-exponentiated visibility of §6.2.
// This is the double-precision reference of shaders/sl/local_light.glsl (tests compare the two).
//
// For ONE receiver p with unit normal n and a light sphere (x, R) of angular radius a = asin(R/|x − p|),
// the SLs after the receiver rules (evaluate.hpp rules 0–2: the spheres pass 2 uses), each with a
// blocker weight w_j ∈ [0, 1] (below), give the visible fraction v ∈ [0, 1] of the light's cap in
// one of two forms (LocalForm):
//  - Sh (the paper's machinery): B = Σ_j w_j G_j (the rotated log ZH, Eq. 22), v = clamp(⟨exp(B)⟩_cap,
//    0, 1), exp the hybrid one (Eq. 6/21) and ⟨f⟩ the cap average (f · K)/(√(4π) K_00) of per-object
//    blocking (evaluate.hpp); at R = 0 the cap is a direction and ⟨f⟩ = f(dir).
//    It is kept as the reference for why the default departs: order 3–4 SH cannot hold a blocker of
//    ~20°, so under it exp(B) is ~0.9, not 0 (SlLocalLight.TheShFormMissesMostOfTheShadow: the
//    floor under one sphere gets 16 % of its shadow).
//  - Cap (ours, the default; the one shaders/sl/local_light.glsl runs): the same accumulation in log
//    space (Ren et al.'s idea, Eq. 6) but with the light's cap as the single basis function, where it
//    is exact: log v = Σ_j w_j log(1 − o_j), o_j the fraction of the light's cap that blocker j's cap
//    covers (the closed-form area of two intersecting spherical caps over the light's). Exact for one
//    blocker (and for R = 0: then o_j is 0 or 1, a hard shadow), the product of the blockers'
//    fractions for several (their overlaps on the light's cap counted as independent, as Eq. 6's
//    product of visibilities is when the caps are averaged separately).
// Fat and overlapping spheres (ours, as sl.shadow does, probe_shadow.hpp / bounce_scale.hpp): the
// sphere set bounds the mesh (its union's solid angle is ~2× the mesh's), so in the Cap form each
// blocker's cap is shrunk to s_j times its solid angle (s_j its set's shadow scale,
// SlSphere::shadowScale: Ω_mesh / Ω_union measured at bake), 1 − cos b' = s_j (1 − cos b), and its
// log is weighted by its object's union share u_j (unionShare: an object's overlapping caps on the
// light count once, not multiplied). Both 1 when not given.
// Which SLs block (w_j; ours where the paper is silent, continuous in every position):
//   - closer than the light (Eq. 20's order by centre distance, d_j < d_x): w fades from 1 at
//     d_j ≤ d_x − r_j to 0 at d_j ≥ d_x, so a sphere passing the light's distance does not pop;
//   - not intersecting the light (§6.2: intersecting SLs ignore each other): w fades from 1 at a
//     gap |c_j − x| − r_j − R ≥ r_j to 0 at touching — a light inside an object's sphere is not
//     blocked by that sphere (its light would otherwise vanish).
// The shading ("sl.local", engine/gi/sl/local_light_pass.hpp) uses v as a product: the light's
// direct term E·V_map (lighting pass; its shadow map no longer holds this object, DrawItem::slLocal)
// becomes E·V_map·v by adding −E·V_map·(1 − v) — so the object's shadow counts once, soft.
#include <span>

#include <glm/glm.hpp>

#include "engine/gi/sl/evaluate.hpp"
#include "engine/math/sh_exp.hpp"

namespace bounce::gi::sl {

enum class LocalForm { Cap, Sh };

struct LocalLight {
  glm::dvec3 position{0.0};
  double radius = 0.0;  // metres, ≥ 0
};

// The visible fraction v ∈ [0, 1] of `light` at (p, n) through `spheres` (world space), order 3 or 4.
// 1 when no sphere blocks or p is at the light's centre.
double localLightVisibility(std::span<const Sphere> spheres, const LocalLight& light, const glm::dvec3& p,
                            const glm::dvec3& n, int order, double influence = 0.0,
                            LocalForm form = LocalForm::Cap, sh::LogKind kind = sh::LogKind::Windowed,
                            std::span<const double> share = {}, std::span<const double> shadowScale = {});

// The fraction of a cap of angular radius a that a cap of angular radius b covers, their centres c
// apart (radians): the intersection area of two spherical caps over 2π(1 − cos a); for a → 0 the
// limit, 1 for c < b and 0 beyond.
double capOverlapFraction(double a, double b, double c);

// The blocker weight w_j above for an (adjusted) sphere at distance d from p, light at distance dx.
double localBlockerWeight(const Sphere& adjusted, double d, const LocalLight& light, double dx);

}  // namespace bounce::gi::sl
