#pragma once
// RTF at run time on the CPU (Pan et al. 2007, §5): the bouncing step (Algorithm 1 run at every
// proxy, bounce after bounce) and the shading step (Eq. 10 with the caches of Eq. 11–12). This is
// the reference the GPU passes are to be checked against, and the math the tests check.
//
// Frames: a field's M, OOF and proxies are in its object's LOCAL frame; lights (SH of incident
// radiance, 16 RGB coefficients, ω pointing towards the source, convention of sh_eval.hpp) are
// rotated between world and local frames with sh::Rotation. Positions in the field are offsets
// from the bounding-sphere centre o in units of η, so a uniform scale needs nothing else (radiance
// transfer between similar geometries is scale-free).
//
// Field lookup (Eq. 10): the 8 samples around q — 4 on each of the two spheres bracketing |q| —
// with trilinear weights: bilinear between the texel centres of the cube-map face that q's
// direction falls on (clamped to that face's outer texel centres, no filtering across faces:
// what a 2D-array texture with clamp-to-edge does), and between the spheres linear in 1/|q|²
// (radialWeight; departure from Eq. 10's linear-in-|q| weight: what a field carries — the light
// an object sends to q and the light it blocks there — goes with the solid angle it covers, ~1/|q|²
// away from it, which a chord in |q| over-estimates between two spheres (a sphere of radius 0.9
// seen from 1.25 between spheres at 1 and 1.5: +24 % linear in |q|, +7 % linear in 1/|q|²; on
// cornell-rtf README Results "RTF"). Exact at the spheres, so continuous.
// Inside the innermost sphere the innermost sphere's value is used. Beyond the outermost sphere
// r_N the field goes on as (r_N/|q|)² — what it carries falls with the object's solid angle
// (radialWeight's comment) — and ends at r_N + Δr (Δr the sphere spacing; the shading pass draws no
// further) by a linear ramp over the last kFadeRamp·Δr: continuous at r_N, zero from r_N + Δr on.
// The OOF fades to "unoccluded" (V = 1) the same way, so the occluded part (1 − V) fades to zero.
// (Before session 10 the ramp was the whole spacing from r_N: it kept on average half of the field
// there where the solid angle keeps 0.85, and on cornell-5 that band blocked 0.0042 where the OOF at
// the receiver blocks 0.0179 and the path tracer 0.0158 — README "Sixth pass".)
#include <array>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/dnrt/irradiance_source.hpp"
#include "engine/gi/placement.hpp"
#include "engine/gi/rtf/field.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_eval.hpp"

namespace bounce::gi::rtf {

using ShRgb = std::array<glm::vec3, kShCount>;  // 16 RGB SH coefficients
using ShScalar = std::array<float, kShCount>;

// V ≡ 1 has the single coefficient ∫ Y_00 dω = 4π·Y_00 = 2√π (= √(4π)); so ∫f dω = kUnitVisibility·f_0
// and (1 − V)'s l = 0 coefficient is kUnitVisibility − V_0. rtf.glsl kRtfUnitVisibility, xi.comp's u_0.
inline constexpr float kUnitVisibility = float(4.0 * math::kPi * sh::constants::kY00);

// The object's placement (engine/gi/placement.hpp, shared with DNRT; a mirror included).
using gi::Placement;
// Throws InternalError when `world` is singular or not finite.
inline Placement place(const Field& field, const glm::mat4& world) {
  return gi::place(field.centre, field.radius, world, "rtf::place");
}
// nullopt where place() throws (gi::tryPlace): a frame skips such an object's GI.
inline std::optional<Placement> tryPlace(const Field& field, const glm::mat4& world) {
  return gi::tryPlace(field.centre, field.radius, world);
}

// SH of a local-frame function in the world, g(M n) = f(n), and back (gi::shToWorld / shToLocal;
// M the placement's local → world directions, a reflection for a mirrored object).
ShRgb toWorld(const ShRgb& local, const Placement& placement);
ShScalar toWorld(const ShScalar& local, const Placement& placement);
ShRgb toLocal(const ShRgb& world, const Placement& placement);

// The 8 samples and weights of Eq. 10 for a local offset q in units of η. Weights sum to 1 up to
// the outermost sphere and fade to 0 beyond it (header comment).
struct Lookup {
  std::array<std::uint32_t, 8> sample{};
  std::array<float, 8> weight{};
};
// `reach` (units of η, run time: scene::Rtf::reach × the outermost radius): 0 keeps the end above;
// beyond r_N + Δr the field instead goes on as (r_N/|q|)² — what a field carries falls off as the solid
// angle of the object (radialWeight's comment) — and ramps to zero over the last kFadeRamp·Δr before
// `reach` (continuous at r_N and at `reach`).
Lookup lookup(const FieldSettings& settings, glm::vec3 q, float reach = 0.0f);
// The share of Δr over which the field ramps to zero at its end (header comment): a quarter spacing,
// so the ramp's slope is 4/Δr of the value there (the field's own change between two spheres is ~1/Δr
// of it near the object): steeper than the field, still continuous.
inline constexpr float kFadeRamp = 0.25f;
// The radial factor beyond the outermost sphere r_N (1 inside it): lookup()'s fade, rtf.frag's:
// (r_N/r)² · clamp((end − r)/(kFadeRamp·Δr), 0, 1), end = reach when reach > r_N + Δr, else r_N + Δr.
float tailFade(const FieldSettings& settings, float r, float reach);
// The reach (η) of scene::Rtf::tail τ: the object's solid angle seen from the outermost sphere,
// Ω_N = the mean over its samples of ∫(1 − V) = 4π − V_00/Y_00 (the OOF), falls as (r_N/r)², so it
// drops below τ·π at r = r_N·√(Ω_N/(τπ)); the tail's linear fade ends there. 0 (no tail: the
// end at r_N + Δr) when τ ≤ 0 or that radius is within r_N + Δr.
float tailReach(const Field& field, float tail);
// The weight of the outer sphere (radius rb) against the inner (ra) for a point at |q| = r in
// [ra, rb]: linear in 1/r², (1/ra² − 1/r²)/(1/ra² − 1/rb²), clamped to [0, 1]. rtf.frag and
// rtf.glsl rtfTaps compute the same.
float radialWeight(float ra, float rb, float r);

// Eq. 12 eigen cache: u_{h,e} = Σ_k E_{he,k} L_k for every cluster h and e = 0 (mean) … n_e,
// [(h·(n_e+1) + e)·16 + i]. proxyLight: m·16 RGB, the proxies' incident radiance in the LOCAL frame.
std::vector<glm::vec3> eigenCache(const Field& field, std::span<const glm::vec3> proxyLight);
// Eq. 11 ξ cache: ξ_r = u_{h(r),0} + Σ_e α_e(r) u_{h(r),e}, [sample·16 + i], local frame.
std::vector<glm::vec3> xiCache(const Field& field, std::span<const glm::vec3> proxyLight);
// ξ at q (local, units of η) by Eq. 10: the object's interreflected radiance arriving at q.
ShRgb interreflection(const Field& field, std::span<const glm::vec3> xi, glm::vec3 q, float reach = 0.0f);
// The OOF at q (local, units of η), faded to V = 1 beyond the field.
ShScalar occlusion(const Field& field, glm::vec3 q, float reach = 0.0f);

// One object of the scene: its field placed by `world` (rotation, uniform scale, translation, a reflection allowed).
struct Object {
  const Field* field = nullptr;
  glm::mat4 world{1.0f};
  float reach = 0.0f;  // lookup()'s: 0 the end at r_N + Δr, else where the (r_N/|q|)² tail ends (η)
};

struct BounceResult {
  // proxyLight[object][k·16 + i]: Σ over bounces 0..B−1 of the proxies' incident radiance, LOCAL frame.
  std::vector<std::vector<glm::vec3>> proxyLight;
  // ξ caches from proxyLight (what the shading step looks up), one per object.
  std::vector<std::vector<glm::vec3>> xi;
  // Per bounce b: Σ over objects and proxies of the mean over RGB of the l = 0 coefficient of
  // bounce b's light (proportional to the incident power at the proxies).
  std::vector<double> bounceEnergy;
};

// §5 bouncing step. Bounce 0: source light at each proxy (world position), occluded by the OTHER
// objects' OOFs (Algorithm 1: the distant light is the farthest entity). Bounce b ≥ 1: the other
// objects' RTFs lit by their bounce b−1 light, each occluded by the OOFs of the objects nearer to
// the proxy (Algorithm 1's order). `bounces` in 1..4 = B: light reaching the proxies after 0..B−1
// inter-object reflections; the shading step adds one more. The proxies run in parallel (TBB), so a
// source's radianceSH is called from several threads at once: it must be safe to (every source in the
// engine is: const reads and Embree queries). The result does not depend on the thread count.
BounceResult bounce(std::span<const Object> objects, const dnrt::IrradianceSource& source, int bounces);
// The same with object J's bounce-0 source light read from sources[J] (one per object, not null): the
// session's lamp visibility at J's proxies leaves J's own mesh out (occluders.hpp, update.cpp).
BounceResult bounce(std::span<const Object> objects, std::span<const dnrt::IrradianceSource* const> sources, int bounces);

// Algorithm 1 (ComputeIncidentRadiance) at world point q for every object but `skip` (−1: none):
// Σ_i V_{<i} ⊙ RTF_i(q) (xi[i] null: object i adds no light, only occlusion), then, when
// `source` is set, V_all ⊙ source(q). World frame. Also returns the total visibility V_all.
struct Incident {
  ShRgb radiance{};
  ShScalar visibility{};
};
Incident incidentRadiance(std::span<const Object> objects, std::span<const std::vector<glm::vec3>* const> xi,
                          const dnrt::IrradianceSource* source, glm::vec3 q, int skip);

// Shading step for a diffuse receiver at world point r, unit normal n, albedo ρ (objects' own
// surfaces pass their index as `skip`): the outgoing radiance the RTF objects add
// (ρ/π · E_n of their interreflected light) and take away (ρ/π · E_n of the source light their
// OOFs block: (1 − V_all) ⊙ source(r)). E_n(L) = Σ Â_l L_lm Y_lm(n) (sh_convolve.hpp).
struct Shading {
  glm::vec3 interreflected{0.0f};
  glm::vec3 blocked{0.0f};
  glm::vec3 net() const { return interreflected - blocked; }
};
// `shCount` 9: E_n with every band the clamped cosine has (Â_3 = 0); 4: bands 0–1 only (scene::Rtf::sh).
Shading shade(std::span<const Object> objects, const BounceResult& bounced, const dnrt::IrradianceSource& source,
              glm::vec3 r, glm::vec3 n, glm::vec3 rho, int skip, int shCount = 9);

// The source's 9 radiance coefficients padded with zeros to 16 (band 3 unknown to the source).
ShRgb sourceRadiance(const dnrt::IrradianceSource& source, glm::vec3 p);

}  // namespace bounce::gi::rtf
