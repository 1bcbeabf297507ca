#pragma once
// The dynamic objects' soft shadow on the probes' indirect light (issue 13, pass 2: "plus the
// dynamic objects' soft shadows on the probes' indirect light"; the SL paper §5.1, Eq. 3 and 6, with
// the probes' radiance in place of the paper's distant environment). The C++ reference of
// shaders/sl/probe_shadow.glsl, in double precision, for ONE receiver point p with unit normal n.
//
// The probes pass adds ρ/π · E_u with E_u = Σ Â_l L_lm Y_lm(n) (the probes' radiance SH L at p,
// unshadowed: the probes were baked without the dynamic objects). With every SL as a blocker the
// visibility is V = exp(Σ_j G_j) (Eq. 6: the SLs' rotated log ZH after the receiver rules of
// evaluate.hpp, the hybrid exp), and the shadowed irradiance is the triple product (Eq. 3)
//   E_s = ∫ L V max(0, n·ω) dω ≈ Σ_j L_j P_j,   P = V ∗ ĉ_n   (sh::product, truncated to L's order)
// with ĉ_n the clamped cosine about n (ĉ_lm = Â_l Y_lm(n), l ≤ 2). The pass adds ρ/π · ΔE, with
//   ΔE = clamp(−k (E_u − E_s), −max(E_u, 0), 0)                                     (per channel)
// negative: it takes light away. The clamps keep the probes' light plus ΔE in [0, E_u] — a blocker
// only removes light, never more than there is — and are continuous.
//
// k (ShadowForm::Ratio, ours, the analogue of evaluate.hpp's Ratio form for Ṽ) rescales the exp's
// blocked amount to the exact one of the caps: k = (Σ_j X_j + ε)/(Σ_j A_j + ε) with, per blocker j
// after the receiver rules (angular radius θ_j, unit direction d_j, so n·d_j ≥ sin θ_j: rule 2 keeps
// the cap above the tangent plane),
//   X_j = π sin²θ_j (n·d_j)         the cap's exact cosine-weighted solid angle (sphere form factor × π), sr
//   A_j = ρ_n · (1 − exp(G_j))       the same as one blocker's exp sees it
// Why: the windowed log (sh_exp.hpp) blurs one small cap, and plain Eq. 6 misses one sphere's
// darkening by up to 37 % (tests/unit/sl/probe_shadow_test.cpp, printed); Eq. 6 keeps the shape of the shadow (where the blockers overlap, how the light's
// direction meets them), the caps' closed form its amount. One sphere under uniform light gives
// exactly the closed form, E_s/E_u = 1 − sin²θ cos β; a directional light behind 1–3 spheres is
// within 0.082 of E_u of brute force (plain Eq. 6: 0.18). ShadowForm::Eq6 is the paper's plain k = 1.
// ε = kShadowEpsilon keeps k continuous (→ 1) where every cap vanishes at the horizon.
//
// Overlapping spheres of one object (ours): an object's spheres overlap heavily (they bound one
// surface), but small caps are in exp's linear regime (a shallow, wide log; order ≤ 4 cannot hold
// a deep narrow one), where summed logs ADD their blocked solid angles instead of taking the union's:
// on cornell-1 the 8 spheres of a 7 cm box darkened the walls ~6× more than the reference's net
// effect. So each X_j is weighted by its object's union share u_o = E_ω[area(∪ silhouettes)] /
// E_ω[Σ area(silhouettes)] (unionShare: the spheres' silhouettes averaged over view directions; 1
// for disjoint spheres, 1/n for n coincident ones): the far field's exact amount is then the union's.
// Near an object (large caps) exp saturates and already discounts the overlaps, and the share must
// not discount them twice, so it applies in proportion to how additive exp is at the receiver:
//   k = (σ Σ u_o X_j + (1 − σ) Σ X_j + ε) / (Σ A_j + ε),   σ = √clamp((π − ρ_n·V + ε)/(Σ A_j + ε), 0, 1)
// (π − ρ_n·V: exp's own blocked amount under uniform light; σ = 1 where summed logs act additively,
// → 0 where they saturate). Ours; the square root is fitted on four coincident spheres, which must
// darken like one (tests/unit/sl/probe_shadow_test.cpp: within 17 % from touching to far, against
// 34 % with σ² and a near shadow quartered without σ). Measured in README Results "SL".
// Every X_j is also multiplied by its set's shadow scale (bounce_scale.hpp: the mesh's silhouette
// over the spheres' union, baked), settings.objectSilhouette / sl_data.glsl slSilhouette.
//
// Where the blocked light is read (BlockedLight, level key "sl": {"blocked_light": …}; issue 13's
// cornell-1 goal, README "SL: the blocked light read at the spheres, session 14"). Receiver (the
// default, above): E_u − E_s from the receiver's SH L. A receiver's order-3 SH spreads a small, bright
// source (cornell-1's ceiling hot spot above the lamp) over a wide lobe, so it misplaces the light an
// SL actually stands in front of. Sphere (ours, after DNRT's anti-radiance, which reads the radiance at
// the object): the amount stays the Ratio form's, and the radiance is read at each SL's centre
// in the direction it blocks:
//   E_u − E_s  →  B = (π − ρ_n·V) · Σ_j w_j max(0, L_j(d_j)) / Σ_j w_j,   w_j = (σ u_o + 1 − σ) X_j
// with L_j the probes' radiance SH at SL j's posed centre (settings.sphereRadiance, pass 1's
// `indirect`), evaluated in the receiver → SL direction d_j (the light arriving at the SL from behind
// it, which it keeps from the receiver), clamped ≥ 0 (a blocker adds no light). π − ρ_n·V is exp's
// blocked amount under uniform unit radiance, so k·B is the Ratio form's ΔE under uniform light
// exactly: a probe field uniform in direction and constant in space gives both modes the same ΔE.
// One small sphere: σ = 1, k(π − ρ_n·V) = X, so ΔE = −X L(d) (the cap's exact amount × the radiance
// behind it). The clamps to [−max(E_u, 0), 0] are kept (E_u the receiver's).
//
// How L_j(d_j) is read (BlockedRead, level key "sl": {"blocked_read": …}; README "SL's blocked light
// read from the probes' direction maps, session 19"). Sh (the default): the order-3 SH above. On the
// characters' floor it is 1.3–1.6× the radiance the mesh hides (session 18): the floor is the
// bright half of the SL's sphere of directions, and order 3 spreads it over the horizon, where the
// directions an SL blocks from a nearby floor receiver lie. Map (ours): the probes' 16² octahedral
// maps of the static radiance (probe_volume.hpp dirMap), blended at SL j's centre with the SH's own
// lookup weights (settings.sphereMap), read at the texel holding d_j (math::octTexel, nearest; the
// same function the shader compiles). Everything else — the amount, w_j, the clamps — is unchanged.
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/sl/evaluate.hpp"

namespace bounce::gi::sl {

enum class ShadowForm { Ratio, Eq6 };
// Where the light the SLs block is read (header): the receiver's SH or each SL's own.
enum class BlockedLight { Receiver, Sphere };
// How the light an SL blocks is read at the sphere (header): its SH, or its direction map.
enum class BlockedRead { Sh, Map };

inline constexpr double kShadowEpsilon = 1e-9;  // sr; ε of k above
inline constexpr double kShadowMaxRatio = 4.0;  // k is clamped to [1/4, 4]: a bound, not reached by one cap

struct ShadowSettings {
  int order = 4;  // the SLs' SH order (3 or 4): V's
  ShadowForm form = ShadowForm::Ratio;
  sh::LogKind log = sh::LogKind::Windowed;
  double influence = 0.0;  // evaluate.hpp rule 0's F (0: off)
  // u_o per Light::object (missing ids: 1), Ratio form only.
  std::vector<double> objectShare;
  // s_shadow per Light::object (SlSphere::shadowScale, bounce_scale.hpp; missing ids: 1): every
  // cap's exact amount X_j is multiplied by it (Ratio form only).
  std::vector<double> objectSilhouette;
  BlockedLight blocked = BlockedLight::Receiver;
  // BlockedLight::Sphere: the probes' radiance SH (9 RGB coefficients, W/(m²·sr)) at the posed centre
  // of lights[i], one per light.
  std::vector<std::vector<glm::dvec3>> sphereRadiance;
  // BlockedRead::Map (with BlockedLight::Sphere): the blended direction map at the posed centre of
  // lights[i] (math::kOctMapTexels RGB, W/(m²·sr)), one per light; sphereRadiance is then unused.
  BlockedRead read = BlockedRead::Sh;
  std::vector<std::vector<glm::dvec3>> sphereMap;
};

// u_o of one object's spheres (any frame: a rigid motion or uniform scale leaves it unchanged):
// silhouettes of kShareDirections Fibonacci directions rasterised on kShareGrid² cells over their
// bounding square. Deterministic; 1 for no or one sphere.
inline constexpr int kShareDirections = 64;
inline constexpr int kShareGrid = 64;
double unionShare(std::span<const Sphere> spheres);

struct ProbeShadow {
  glm::dvec3 delta{0.0};      // ΔE, W/m² (≤ 0)
  glm::dvec3 unshadowed{0.0};  // E_u
  double ratio = 1.0;          // k
  double additive = 1.0;       // σ (Ratio form)
};

// `radiance`: the probes' radiance SH at p, 4 or 9 RGB coefficients (W/(m²·sr)).
ProbeShadow probeShadow(std::span<const Light> lights, const glm::dvec3& p, const glm::dvec3& n,
                        std::span<const glm::dvec3> radiance, const ShadowSettings& settings);

}  // namespace bounce::gi::sl
