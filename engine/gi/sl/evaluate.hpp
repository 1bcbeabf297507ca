#pragma once
// Spherical lights (Guerrero, Jeschke, Wimmer 2008, ../shared/papers/sl-spherical-lights.md):
// the per-receiver evaluation in C++, double precision — the reference the GLSL pass 2 is tested
// against. Everything here is for ONE receiver point p with unit normal n.
//
//   E(p) = Σ_i L̃_i Ṽ_i                                                        (Eq. 14)
//   L̃_i = w'_θ · L^c_i      (average radiance: Eq. 16–18, w_θ the normalised cos γ ZH of Eq. 17,
//                            rotated to the SL-local direction towards p: §7.1 rotates the weight
//                            vector, not the sphere's samples)
//   Ṽ_i = V_i · ρ_n         (Eq. 24, ρ_n the clamped cosine n·ω, so Ṽ_i is cosine-weighted visibility)
//   V_i = exp(Σ_{j<i} G_j) − exp(G_i + Σ_{j<i} G_j)      (Eq. 23; rescaled by the Ratio form, below)
//
// E is irradiance (W/m² for L in W/(m²·sr)): a diffuse receiver of albedo ρ reflects ρ E / π. The
// sum over j < i runs over the spheres closer to p than i (distance between p and the centre),
// skipping spheres of i's own object that intersect i (their occlusion is baked into i's samples,
// §6.2). Per-object blocking (§7.2) sorts objects by the distance to their sphere centres' mean and
// reuses the closer objects' summed logs — see "Per-object blocking" below for how far.
//
// Per-object blocking, one exp per object (§7.2: "re-use the accumulated blocking effect of one
// object for all following objects"; ours where it departs). For the lights of object o:
//   E_o = exp(C_o), C_o = Σ G_j over the live lights of the closer objects  (ONE hybrid exp per object)
//   Ṽ_i = X_i · clamp(⟨E_o⟩_i, 0, 1)
// with X_i the cap's exact unoccluded Ṽ (the Ratio form's amount) and ⟨f⟩_i = ∫_cap f dω / |cap| the
// average of f over light i's cap (a dot product with the cap's projected indicator K_i).
// Departures, and why:
//  - Eq. 23's two exps per light, exp(B) − exp(B + G_i), become the cap average of exp(C_o): ρ_n is
//    taken as constant over the cap — the approximation the paper itself makes for L̃ in Eq. 15 —
//    so the visible fraction of the cap is ⟨V⟩ over it. On llvmpipe a hybrid exp is a Gaunt square
//    or more (branches are not skipped), 2–3 per light and pixel; this is one per object and pixel.
//  - An object's own non-intersecting spheres do not block each other (the paper adds them to the
//    closer objects' sum per light). They are few — an object's neighbouring spheres mostly
//    intersect and are skipped anyway (§6.2) — and leaving them out lets the GPU visit an object's
//    lights in any order: no per-pixel sort, no per-lane gathers of their logs. Measured (process
//    CPU per frame, characters, 640×360): they cost 0.25 s of 0.77 s and the sort 0.16 s; their
//    effect on the image: README "SL cost" (accuracy rows per-object vs per-sphere).
// So per-object equals per-sphere only approximately on separated objects (SlEvaluate.PerObject…
// bounds the difference), and differs from the paper's per-object in images by the amounts in
// README "SL cost".

//
// Receiver rules (§6.2 "Avoiding problems with receiver points inside SLs", after Ren et al. 2006;
// the paper gives no formulas, these are ours and continuous in p, n, centre and radius):
//  1. containment: with t = |c − p| / r < 1 the sphere contains p; its radius becomes
//     r₁ = |c − p| · clamp((t − kCullFraction) / (1 − kCullFraction), 0, 1): it passes through p at
//     t = 1, shrinks as p goes deeper and vanishes (culled) at t ≤ kCullFraction;
//  2. tangent plane: with h = n·(c − p) the centre's height above the plane, a sphere with h < r₁
//     crosses the plane: it is replaced by the sphere spanning its part above the plane, radius
//     r₂ = (h + r₁)/2 and centre moved along n to height r₂ (r₂ = r₁ at h = r₁: continuous);
//     h + r₁ ≤ 0 (entirely below) culls it.
// After both, no sphere contains p or reaches below its tangent plane, so every angular radius is
// ≤ π/2, the range of the log table.
//  0. influence (optional, EvalSettings::influence = F > 0; ours, for cost): with t = |c − p| / r, a
//     sphere far from p fades out — r₀ = r · clamp((F − t) / (F/2), 0, 1): unchanged up to t = F/2
//     (angular radius asin(2/F)), shrinking continuously to nothing at t = F — so a receiver only
//     pays for the spheres near it (the "influence bounds", as Unreal's capsule shadows
//     cull capsules by theirs). Applied before rules 1–2 (which act at t ≤ 1 < F/2).
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/math/sh_exp.hpp"

namespace bounce::gi::sl {

// Rule 1's culling depth: spheres whose centre is within this fraction of their radius of p vanish.
inline constexpr double kCullFraction = 0.5;

struct Sphere {
  glm::dvec3 centre{0.0};
  double radius = 0.0;
};

struct Adjusted {
  Sphere sphere;
  bool culled = false;
};
// Rules 0 (when influence > 0), 1 and 2 above for one sphere at receiver (p, n).
Adjusted adjustForReceiver(const Sphere& s, const glm::dvec3& p, const glm::dvec3& n, double influence = 0.0);

// Eq. 17: cos γ at angular distance α from the direction centre → p, for a sphere of angular radius θ
// seen from p; max(0, ·). Equal to (cos α − sin θ) / √(1 − 2 sin θ cos α + sin² θ).
double cosGamma(double alpha, double theta);

// w_θ: Eq. 16's normalised weight max(0, cos γ)/∫max(0, cos γ) as ZH about the direction to p
// (order coefficients), linear interpolation in a table of 256 θ in [0, π/2] built once per order
// (3 or 4) by 1D Gauss–Legendre quadrature over the lit cap cos α ∈ [sin θ, 1]; at θ = π/2 (p on the
// sphere) the weight is a delta towards p.
std::vector<double> averageRadianceZonal(double theta, int order);
// The table itself for upload (pass 2 reads it as a texture): row i (θ_i = i/255 · π/2) at
// [i·order, i·order + order).
std::span<const double> averageRadianceTable(int order);
inline constexpr int kAverageRadianceEntries = 256;

// One spherical light as pass 2 sees it.
struct Light {
  Sphere sphere;                      // world space
  glm::dmat3 rotation{1.0};           // SL local → world (the object's or the vertices' average, §7.1)
  std::vector<glm::dvec3> intensity;  // L^c (Eq. 11), RGB SH in the SL's LOCAL frame, order² entries
  int object = 0;                     // lights with equal `object` may intersect (baked occlusion)
};

enum class Blocking { PerSphere, PerObject };

// How Ṽ_i is formed:
//  - Eq23 (the paper): Ṽ_i = ρ_n · [exp(Σ_{j<i} G_j) − exp(G_i + Σ_{j<i} G_j)];
//  - Ratio (ours, the default): Eq23's Ṽ_i times Ṽ_i^exact / Ṽ_i^23, where the two are light i's
//    UNOCCLUDED Ṽ from its cap's exact ZH projection (sh::capVisibilityZonal) and from Eq. 23 with no
//    blockers (1 − exp(G_i)). Eq. 23 decides the visible fraction, the exact cap the amount: no
//    blockers gives the cap's exact order-n Ṽ, full blocking gives 0. Why: the clamped, windowed log
//    that keeps sums of many blockers stable (sh_exp.hpp) is a poor model of ONE cap — Eq23 alone
//    misses an unoccluded sphere's form factor by up to 37 % — while Eq. 23's difference of two
//    exps is accurate for the shadowed fraction (1 % in the blocker test). An SH product of exp(blockers)
//    with the exact cap was tried and loses the shadow (truncated product: Ṽ above the unoccluded).
//    Cost: one more OL exp per light (a single blocker never needs squarings) and two dot products.
enum class VisibilityForm { Ratio, Eq23 };

struct EvalSettings {
  int order = 4;  // 3 or 4; every Light::intensity must have order² coefficients
  Blocking blocking = Blocking::PerSphere;
  VisibilityForm visibility = VisibilityForm::Ratio;
  sh::LogKind log = sh::LogKind::Windowed;  // which blocker log table (sh_exp.hpp)
  double influence = 0.0;  // rule 0's F (> 2), or 0: every sphere counts at every receiver
};

// Per light, for tests and the GLSL comparison: the adjusted geometry and the two factors.
struct LightTerm {
  bool culled = false;
  double theta = 0.0;         // angular radius after the receiver rules (rad)
  glm::dvec3 average{0.0};    // L̃ (Eq. 18)
  double visibility = 0.0;    // Ṽ (Eq. 24), sr
};

struct Evaluation {
  glm::dvec3 irradiance{0.0};   // Σ L̃ Ṽ
  std::vector<LightTerm> terms;  // in the order of `lights`
};

Evaluation evaluate(std::span<const Light> lights, const glm::dvec3& p, const glm::dvec3& n,
                    const EvalSettings& settings);

// Pass 1's last step on the CPU (the reference for the GPU's): the SL's intensity from the diffuse
// reflection L_pj at its surface samples, Eq. 10 L_S = Σ_j L_pj Y'_j (Y'_j = `basis[j]`, Eq. 10's
// sums pre-multiplied by 4π/N, order² each), then Eq. 11 L^c = L_S ∗ c_S with c_S the albedo SH
// (`albedo`, RGB, coefficient-major order² × 3), one SH product per channel (sh_product.hpp).
// Returns order² RGB coefficients in the SL's local frame (Light::intensity).
std::vector<glm::dvec3> intensityFromSamples(std::span<const glm::dvec3> sampleRadiance,
                                             std::span<const std::vector<float>> basis, std::span<const float> albedo,
                                             int order);

// Eq. 6: the visibility SH vector of the environment at p with every light as a blocker (the soft
// shadow the dynamic objects cast on distant/probe light). Dot with a cosine-convolved radiance to
// shade.
std::vector<double> environmentVisibility(std::span<const Light> lights, const glm::dvec3& p, const glm::dvec3& n,
                                          int order, sh::LogKind kind = sh::LogKind::Windowed, double influence = 0.0);

}  // namespace bounce::gi::sl
