#pragma once
// DNRT precompute (paper §5.1, Listing 1): for every vertex p_i of an N³ grid around one object O,
// Monte-Carlo estimates of
//   t_j = ∫_D Y_j(n_s) ρ_s / π² (ω·n_o)₊ dω                                  (Eq. 8, reflection)
//   k_j = ∫_D Y_j(ω) / π² (ω·n_o)₊ dω                                        (Eq. 13, anti-radiance)
// and m_j = t_j − k_j (§5.1.2), per RGB channel (ρ_s is RGB; k_j is grey), where D is the solid angle
// O subtends from p_i, n_o = normalize(o − p_i) the intermediate normal (§4.1.4), n_s the surface
// normal and ρ_s the albedo (factor × texture) at the first hit.
//
// Estimator: stratified cosine-weighted directions around n_o (pdf (ω·n_o)/π), ONE ray per
// direction serving every coefficient (§5.1.1): ∫_D f (ω·n_o)₊ dω ≈ (π/S) Σ_hits f, so
// t_j ≈ Σ_hits Y_j(n_s) ρ_s / (π S) and k_j ≈ Σ_hits Y_j(ω) / (π S).
// Improved anti-radiance (App. B.2): L_init(ω) ≈ Σ_j (c_j / Â_l) Y_j(ω) (the radiance whose
// irradiance the c_j are) instead of I(ω)/π, i.e. k_j scaled by π/Â_l: ×1 (l = 0), ×3/2 (l = 1),
// ×4 (l = 2). The runtime is unchanged (same c_j).
// FieldSettings::occlusionOnly bakes m_j = −k_j (t_j = 0): added with the lights' c_j negated, it
// cancels the lights' part of the anti-radiance when their occlusion is drawn elsewhere (runtime.hpp).
// bakeWithOcclusion gives a field and its occlusion-only field from the same rays (one trace).
//
// Vertices inside O (most hits are back faces) and the vertex at o itself (n_o undefined) have no
// meaningful value: they are filled from valid neighbours (repeated averaging of the valid
// 26-neighbours) so trilinear filtering next to O's surface does not pull in garbage.
// Deterministic: vertex i draws its samples from Pcg32::fromIndex(i), whatever the thread count.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/dnrt/field.hpp"
#include "engine/ref/scene_bvh.hpp"

namespace bounce::gi::dnrt {

struct BoundingSphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};
// Centre of the axis-aligned bounds, radius = farthest vertex from it (a bounding sphere, not the
// minimal one; exact for spheres and boxes). Throws InternalError on an object without vertices.
BoundingSphere boundingSphere(const ref::SceneDesc& object);

struct BakeResult {
  Field field;                    // quantised, what the runtime uploads
  std::vector<glm::vec3> values;  // unquantised m_j: values[vertex·shCount + j]
  std::size_t insideVertices = 0;  // vertices detected inside O (or at o) and filled
  QuantizationError quantization;
  bool withinAnalyticBound = true;  // rangesWithinAnalyticBound(field): false is a bug (warned)
};

// `object`: ONE object's meshes in its local frame (metres), materials and textures.
BakeResult bake(const ref::SceneDesc& object, const FieldSettings& settings);

// `settings`' field and its occlusion-only field (settings with occlusionOnly set: m_j = −k_j) from
// ONE pass of rays: k_j is summed for the first anyway, so the second costs no trace. Each is value
// for value what bake() gives for its settings (the rays are seeded per vertex).
struct BakePair {
  BakeResult field, occlusion;
};
BakePair bakeWithOcclusion(const ref::SceneDesc& object, const FieldSettings& settings);

// Cache key: the settings and the baker/format version, plus what the object is: its
// SceneDesc::sourceKey when set (objectScene sets it from the cooked asset's content key, so a
// bake job's key needs no decoding: objectSourceKey()), else every mesh, material and texture byte.
std::string cacheKey(const ref::SceneDesc& object, const FieldSettings& settings);
// The same key from the object's source key alone (what cacheKey computes when sourceKey is set).
std::string cacheKey(const std::string& objectSourceKey, const FieldSettings& settings);

// Where bakeCached keeps the field: `cacheDir`/dnrt-<cacheKey>.field.
std::filesystem::path cachePath(const ref::SceneDesc& object, const FieldSettings& settings,
                                const std::filesystem::path& cacheDir);
std::filesystem::path cachePath(const std::string& key, const std::filesystem::path& cacheDir);

// The quantised field from `cacheDir`/dnrt-<key>.field, baking and storing it on a miss (a corrupt
// cache file is rebaked with a warning). `fromCache` (optional) tells which happened.
Field bakeCached(const ref::SceneDesc& object, const FieldSettings& settings, const std::filesystem::path& cacheDir,
                 bool* fromCache = nullptr);

// Both entries of bakeWithOcclusion (each its own cache file, keyed as bakeCached keys it); a miss on
// either bakes the pair once. `baked` (optional): how many of the two entries were baked (0, 1 or 2).
struct FieldPair {
  Field field, occlusion;
};
FieldPair bakeCachedWithOcclusion(const ref::SceneDesc& object, const FieldSettings& settings,
                                  const std::filesystem::path& cacheDir, int* baked = nullptr);
// `settings` with occlusionOnly set: the second field's settings (and cache key).
FieldSettings occlusionSettings(FieldSettings settings);

// What an object's `dnrt` needs through the cache, the one place that picks: the field alone
// (bakeCached) when "lights_in_anti_radiance" is true, else the field and its occlusion-only field
// from the same rays (bakeCachedWithOcclusion; runtime.hpp). `baked` (optional): entries baked (0–2).
// The Runtime and `bounce bench dnrt` call it; a bake job (technique.cpp) bakes uncached (--force)
// and writes its entries itself, choosing bakeWithOcclusion for the same reason.
struct CachedFields {
  Field field;
  std::optional<Field> occlusion;  // set when !lightsInAntiRadiance
};
CachedFields bakeCachedFor(const ref::SceneDesc& object, const FieldSettings& settings, bool lightsInAntiRadiance,
                           const std::filesystem::path& cacheDir, int* baked = nullptr);

}  // namespace bounce::gi::dnrt
