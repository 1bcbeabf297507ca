#pragma once
// The SLs' bounce scale (ours; issue 13's "SL puts ~10× too much light on the floor around the
// feet"). Measured (tests/unit/sl/bake_test.cpp SlBake.UniformlyLitCharacterSlsVsItsMesh) under
// uniform light, where every surface point re-emits the same radiance and the truth at a receiver is
// that radiance times the MESH's cosine-weighted solid angle: the SLs of CesiumMan / Fox give 1.9–2.8×
// / 2.7–4.0× the mesh's light (8–32 spheres). Two causes, both geometric, neither a units error
// (tests/unit/sl/bounce_units_test.cpp checks every factor of pass 1 and 2 on a sphere), both caught
// by the fit below (on other receivers the scaled SLs give 0.84–0.98× the mesh's light):
//  - the spheres bound the surface and are fatter than it (the union's solid angle is 1.9–2.4× the
//    mesh's: volume overshoot 2.7–5);
//  - overlapping spheres of one object do not block each other (§6.2 ignores intersecting SLs; their
//    occlusion is baked only along the centre's own rays), so their caps add (1.4–1.8× the union at
//    32 spheres).
// Fit: s = Σ_p E_mesh(p) / Σ_p E_SL(p) over receivers on two shells around the set (1.1 and 2
// bounding radii, kBounceScaleDirections directions each, facing the centre), with every sample
// re-emitting 1 and white albedo; E_mesh by kBounceScaleRays cosine-weighted rays against the mesh,
// E_SL by sl::evaluate (per-sphere blocking, ratio form, the set's order). One bounce number per set,
// stored on each sphere (SlSphere::bounceScale) and multiplied into pass 1's Eq. 11 (both faces:
// intensity.cpp's reference and IntensityPass's albedo upload). Clamped to [kMinBounceScale, 1]: the
// SLs are bounds, so they are never made brighter than baked.
#include "engine/gi/sl/sphere_set.hpp"
#include "engine/ref/scene_bvh.hpp"

namespace bounce::gi::sl {

inline constexpr int kBounceScaleDirections = 26;
inline constexpr int kBounceScaleRays = 2048;
inline constexpr double kMinBounceScale = 0.05;

// The shadow's twin (SlSphere::shadowScale): sl.shadow's caps already count an object's overlapping
// spheres once (its union share u_o), but the union is still fatter than the mesh, so each cap's
// exact amount X_j is multiplied by s_shadow = Σ_p Ω_mesh(p) / Σ_p Ω_union(p), the two
// cosine-weighted solid angles on the same receivers and rays (Ω_union: a ray counts when it meets
// any sphere). Same clamp.
struct BounceScales {
  double bounce = 1.0;
  double shadow = 1.0;
};
// `set`: spheres with their samples and basis sums (bake step 3 done); `bvh`: the object's mesh, in
// the set's frame. Deterministic.
BounceScales fitBounceScale(const SphereSet& set, const ref::SceneBvh& bvh);

}  // namespace bounce::gi::sl
