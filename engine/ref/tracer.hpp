#pragma once
// The reference path tracer: ground truth for every GI technique.
//
// Light transport (Kajiya 1986, "The Rendering Equation"), Lambertian surfaces only, as the
// rasteriser treats every glTF material (albedo ρ = base colour, BRDF ρ/π):
//   L(x→eye) = Le(x) + ρ(x)/π · Σ_lights E_i(x) (n·l_i)₊ V_i(x) + ∫ ρ(x)/π L(y→x) cosθ dω
// estimated per pixel sample by one path:
//   - camera rays through pixel centres with the rasteriser's projection (cameraRay());
//   - next-event estimation to every punctual light with a shadow ray at every path vertex;
//   - emissive surfaces and the background are light that paths find by hitting them (no
//     next-event estimation towards emissive triangles: unbiased, just noisier for small ones);
//   - bounces cosine-weighted about the shading normal, so each bounce multiplies the path
//     throughput by ρ (BRDF·cos/pdf = ρ/π · cosθ / (cosθ/π)); a direction (bounce or light) on the
//     far side of the geometric normal gets nothing, as in pbrt-v3, so shading normals never
//     leak light through a surface;
//   - Russian roulette from the 4th indirect bounce on (after bounce 3): survival probability
//     p = max channel of the throughput after the bounce, clamped to ≤ 1, survivors divided by p.
//
// `bounces` counts indirect bounces: 0 = direct light only (Le + punctual lights with exact
// shadows, which is what the rasteriser's direct pass computes with shadow maps), 1 = one
// indirect bounce, … Emission and background reached after k bounces count as k-bounce light,
// so for a closed furnace of albedo ρ and emission Le, bounces N gives Le·(1 − ρ^{N+1})/(1 − ρ).
//
// Deterministic: pixel (x, y) sample s draws from Pcg32::fromIndex((y·W + x)·2^32 + s), and each
// pixel sums its samples in index order, so the image is bit-identical for any thread count and
// any split of the samples into progressive passes.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "engine/gpu/image_io.hpp"
#include "engine/math/sampling.hpp"
#include "engine/ref/scene_bvh.hpp"

namespace bounce::ref {

// Bump whenever the tracer's output changes for the same inputs (it is part of the cache key).
inline constexpr std::uint32_t kTracerVersion = 1;
// "Unlimited" bounces: Russian roulette ends almost every path long before this cap.
inline constexpr std::uint32_t kUnlimitedBounces = 64;
// Indirect bounces before Russian roulette starts.
inline constexpr std::uint32_t kRouletteAfter = 3;

struct TraceSettings {
  std::uint32_t width = 256;
  std::uint32_t height = 256;
  std::uint32_t spp = 64;                       // samples per pixel
  std::uint32_t bounces = kUnlimitedBounces;    // indirect bounces (0 = direct only)
  std::uint32_t passSpp = 16;                   // samples per progressive pass
  std::string label = "reference";              // progress bar label; empty: no progress bar
};

struct TraceStats {
  std::uint64_t rays = 0;  // camera + bounce + shadow rays
  double seconds = 0.0;
  double raysPerSecond() const { return seconds > 0.0 ? double(rays) / seconds : 0.0; }
};

struct CameraRay {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f};  // unit
  float tMin = 0.0f, tMax = 0.0f;  // the near and far planes along this ray
};

// The ray through the centre of pixel (x, y) (row 0 at the top), for the projection the
// rasteriser uses: perspectiveVk(yfov, width/height, near, far) (glm::perspectiveRH_ZO with
// clip-space +Y down), view = inverse(camera.world). tMin/tMax put the near and far planes where
// the rasteriser clips.
CameraRay cameraRay(const RefCamera& camera, std::uint32_t width, std::uint32_t height, std::uint32_t x,
                    std::uint32_t y);

// Renders the scene seen from scene.camera; returns linear radiance, rows top to bottom.
gpu::FloatImage trace(const SceneBvh& scene, const TraceSettings& settings, TraceStats* stats = nullptr);

// One path for pixel (x, y), sample `sample` (exposed for tests); `rays` counts the rays cast.
glm::dvec3 tracePath(const SceneBvh& scene, const TraceSettings& settings, std::uint32_t x, std::uint32_t y,
                     std::uint32_t sample, std::uint64_t& rays);

// One path from any ray o + t·d (d unit), t in [tMin, tMax): the radiance arriving at o from
// direction −d, with the same light transport as tracePath (which calls it for camera rays).
// Probe bakes trace from probe positions with it. `firstHit` (optional) receives the first
// intersection; the return of `hitAnything` says whether there was one.
glm::dvec3 tracePathFrom(const SceneBvh& scene, glm::vec3 origin, glm::vec3 dir, float tMin, float tMax,
                         std::uint32_t bounces, math::Pcg32& rng, std::uint64_t& rays, Hit* firstHit = nullptr,
                         bool* hitAnything = nullptr);

}  // namespace bounce::ref
