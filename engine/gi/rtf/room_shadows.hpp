#pragma once
// The posed objects' lamp shadows on the room, as the proxies see it (issue 14, session 18, step 2;
// README "RTF's lamp through the other objects, session 18").
//
// The proxies' indirect light is the baked probes' (incident::ProbeSource): a room without the dynamic
// objects, so the floor under the truck reads lit where the textured box (and the truck itself) shadow
// it from the lamp. Session 17 traced the room's l = 0 at the truck's proxies at 0.42 of the probes'.
// Algorithm 1 (§5) cannot carry it: the paper's environment is a distant light with a constant SRF,
// and the OOFs (already multiplied into the whole source light at bounce 0, evaluate.cpp) hide the
// directions ONTO the other objects, not the shadows they cast on the room. A departure, ours: at a
// proxy χ, the room's one-bounce lamp light that the posed objects take away, along N fixed
// directions ω_s (the spherical Fibonacci lattice) to the static surface x_s they hit first:
//   ΔL_i(χ) = −(4π/N) Σ_s Y_i(ω_s) ρ(x_s)/π Σ_lights E(x_s) max(n_s·l, 0) V_static(x_s) (1 − V_objects(x_s))
// (radiance SH, W/(m²·sr), world axes; E the light's irradiance, incident::lightIrradiance; ρ the
// static surface's albedo at the hit, texture included (ref::surfaceAlbedo, what the probe bake's
// paths reflect), so `level` must hold its textures (incident::SessionLight::surfaces());
// V_objects through EVERY posed object, the proxy's own included: its shadow on the room is the
// room's, not Eq. 8's self-shadowing). Only the lamp's first bounce off the room is taken away: the
// probes' higher orders stay.
#include <span>

#include <glm/glm.hpp>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/rtf/occluders.hpp"
#include "engine/ref/scene_bvh.hpp"
#include "engine/render/gpu_types.hpp"

namespace bounce::gi::rtf {

// Directions per proxy: 64 (≈ 0.2 sr each; the truck's floor shadow from 0.46 m spans ~0.3 sr).
inline constexpr int kRoomShadowDirections = 64;

// ΔL at χ (9 radiance SH, world; ≤ 0 in its mean) for `lights` through `level` (the static scene, with
// its materials and textures) and the posed objects `poses` of `occluders`. Safe to call from several
// threads at once (const reads and Embree queries only).
incident::RadianceSH roomShadow(const ref::SceneBvh& level, const PosedOccluders& occluders,
                                std::span<const PosedOccluders::Pose> poses, std::span<const render::LightGpu> lights,
                                glm::vec3 chi, int directions = kRoomShadowDirections);

// L + ΔL, never taking more than L's mean holds, per channel (ΔL scaled down where L₀ + ΔL₀ < 0). The
// baked probes hold only the bake's lights: a light moved, brightened or added since then has more
// to lose in roomShadow() than they ever held, and the difference would be negative radiance
// (session-18 review). Where ΔL₀ ≤ L₀ nothing changes.
incident::RadianceSH withRoomShadow(const incident::RadianceSH& L, incident::RadianceSH dL);

}  // namespace bounce::gi::rtf
