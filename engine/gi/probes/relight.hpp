#pragma once
// Probes relit each frame (level `"probes": {"relight": true}`, pass `probes.relight`): the light the
// dynamic objects take from the STATIC surfaces — their direct shadows on walls and floor — and the
// room's interreflection of that loss reach the probes' light. The baked probes are traced without
// the dynamic objects (bake.hpp), so before this no technique saw that part of the transport (README
// "SL accuracy with the reference's noise taken out", RTF "Fourth pass": the room term ≈ the props'
// whole first-order effect).
//
// Bake (CPU, cached next to the probe volume under its own key): surfels on the static geometry and,
// per probe, the probe bake's own R directions (same strata, same seed, same virtual offset) traced
// with Embree against the static scene: the hit surfel per direction, or kRelightMiss. That is the
// probe's static light transport: its radiance SH = 4π/R Σ_dirs Y(ω) L(hit(ω)).
//
// Per frame (GPU, relight_pass.hpp / shaders/probes/relight.comp; math in shaders/probes/relight.glsl,
// compiled here as C++ for the reference below) the probes get baked + ΔSH, ΔSH the change of that
// projection when the surfels lose the light the dynamic objects shadow (a delta, not a full relight:
// with no dynamic object ΔSH = 0 exactly up to the shadow map's disagreement with Embree, so the
// level without objects keeps the baked, path-traced image; README "Probes relit each frame").
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/probes/bake.hpp"
#include "engine/gi/probes/probe_volume.hpp"
#include "engine/ref/scene_bvh.hpp"
#include "engine/render/gpu_types.hpp"

namespace bounce::gi::probes {

// Bump when the relight bake's output changes for the same inputs (part of its cache key).
inline constexpr std::uint32_t kRelightVersion = 2;  // 2: the directions regenerated on load, not stored
// Surfels on the static geometry. 4096: on cornell-1 (≈1.6 m² of static surface) one per ≈4 cm²,
// ≈2 cm apart, so the prop's 0.1 m lamp shadow covers ≈25 of them; the per-frame cost is linear in
// it (one shadow lookup per surfel and light) and the gather's cost does not depend on it.
inline constexpr std::uint32_t kRelightSurfels = 4096;
inline constexpr std::uint32_t kRelightMiss = 0xffffffffu;
// Iterations of the room's bounce per frame; ΔSH persists between frames, so the series of bounces
// goes on over frames (README "Probes relit each frame": convergence).
inline constexpr int kRelightIterationsPerFrame = 2;
// true: the CPU readers of the probes (incident::ProbeSource: DNRT's c_j, SL's pass 1, RTF's proxies)
// read baked + ΔSH, read back from the frame slot's last run (a frames-in-flight lag, no stall). OFF:
// measured (README "Probes relit each frame", Results) it moved cornell-1's DNRT rows by −0.003…0 and
// SL's by ±0.0001, but made most of cornell-5's DNRT and RTF rows slightly worse (effect +0.0001…+0.0005),
// so the CPU readers keep the baked SH.
inline constexpr bool kRelightCpuReaders = false;

struct Surfel {
  glm::vec3 position{0.0f};  // world, metres
  glm::vec3 normal{0.0f};    // unit, the triangle's front side
  glm::vec3 albedo{0.0f};    // clamp(factor × texture at the point, 0, 1), as the path tracer
  float area = 0.0f;         // m² of static surface the surfel stands for (total / count)
};

struct RelightData {
  std::vector<Surfel> surfels;
  std::uint32_t rays = 0;            // R per probe (the probe bake's)
  std::vector<glm::vec3> dirs;       // probes × R unit directions, the baker's (not in the cache file: regenerated)
  std::vector<std::uint32_t> hit;    // probes × R: the hit surfel or kRelightMiss
  std::size_t probes() const { return rays ? hit.size() / rays : 0; }
};

// `count` surfels, area-uniform over every triangle (stratified over the area CDF, deterministic).
std::vector<Surfel> sampleSurfels(const ref::SceneDesc& scene, std::uint32_t count, std::uint64_t seed = 0x5eed);

// The bake: surfels, then per probe of `grid` the probe bake's directions for `settings` traced
// from its virtual offset; a hit takes the nearest surfel facing the ray (n·ω < 0), a back-face
// hit or a miss is kRelightMiss (ΔL = 0 there: the background does not change). Progress bar.
RelightData bakeRelight(const ref::SceneBvh& bvh, const ProbeGrid& grid, const ProbeSettings& settings,
                        std::uint32_t surfels = kRelightSurfels, const std::string& label = "probes.relight");

// The bake's hit → surfel rule: the surfel facing `dir` (n·dir < 0) nearest to q (squared distance,
// ties to the lower index), or kRelightMiss. The scan over every surfel (the definition, tests) and
// the bake's grid search (relight.cpp SurfelGrid, the same answers) for many points at once.
std::uint32_t nearestFacingSurfel(std::span<const Surfel> surfels, const glm::vec3& q, const glm::vec3& dir);
std::vector<std::uint32_t> nearestFacingSurfels(std::span<const Surfel> surfels, std::span<const glm::vec3> q,
                                                std::span<const glm::vec3> dir);

std::vector<std::uint8_t> serializeRelight(const RelightData& data);
RelightData deserializeRelight(std::span<const std::uint8_t> bytes, const std::string& name);

// <probeCache>/<probe key>-relight-<key of the version, surfel count and grid>.bin: a bake job of the
// probes technique when the level asks for relight (`bounce bake`, kept by `bounce cache --prune`).
std::filesystem::path relightCachePath(const BakeInput& input, const ProbeGrid& grid, const std::filesystem::path& probeCache);
// The entry when valid (a corrupt one is a warning and counts as missing).
std::optional<RelightData> loadCachedRelight(const std::filesystem::path& file);
// Bakes (ignoring the cache) and writes relightCachePath atomically.
RelightData bakeRelightToCache(const BakeInput& input, const ProbeGrid& grid, const std::filesystem::path& probeCache);
// loadCachedRelight, else bakeRelightToCache.
RelightData loadOrBakeRelight(const BakeInput& input, const ProbeGrid& grid, const std::filesystem::path& probeCache);

// V_static per (surfel, light), surfel-major (s·lights + l): 1 when a ray from the surfel (lifted
// 1 mm along its normal) reaches the light through the static geometry, else 0.
std::vector<float> staticVisibility(const ref::SceneBvh& bvh, std::span<const Surfel> surfels,
                                    std::span<const render::LightGpu> lights);

// ---- CPU reference of the GPU pass (tests): the same relight.glsl functions ------------------------

// The direct part of a surfel's ΔE (W/m²): Σ_l relightDirectLoss with V_now, V_static per (s, l).
glm::vec3 surfelDirectLoss(const Surfel& s, std::size_t index, std::span<const render::LightGpu> lights,
                           std::span<const float> vNow, std::span<const float> vStatic);
// One probe's ΔSH (9 coefficients) from the surfels' outgoing ΔL.
void gatherProbe(const RelightData& data, std::size_t probe, std::span<const glm::vec3> surfelRadiance, glm::vec3 sh[9]);
// `iterations` steps from ΔSH = `delta` (probes × 9; updated): surfel ΔE = direct loss + the
// irradiance of ΔSH through `volume`'s lookup (its weights, visibility and grid), ΔL = ρ/π ΔE,
// then the gather. Invalid probes stay 0. `surfelRadiance` (optional) gets the last step's ΔL.
// `slBounce` (optional, per surfel, W/m²): the SLs' irradiance E_SL added to every step's ΔE
// (level `"probes": {"sl_bounce": true}`, RelightPass::setSlBounce).
void relightReference(const RelightData& data, const ProbeVolume& volume, std::span<const render::LightGpu> lights,
                      std::span<const float> vNow, std::span<const float> vStatic, int iterations,
                      std::vector<glm::vec3>& delta, std::vector<glm::vec3>* surfelRadiance = nullptr,
                      std::span<const glm::vec3> slBounce = {});

}  // namespace bounce::gi::probes
