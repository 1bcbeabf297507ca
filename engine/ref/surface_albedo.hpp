#pragma once
// A surface's albedo where a ray hit it, as the rasteriser shades it (scene_bvh.hpp's conventions,
// gbuffer.frag): clamp(albedo factor × base colour texture at the hit's uv, 0, 1). The one
// evaluation of it: the path tracer (and through it the probe bake), DNRT's and SL's bakes, RTF's room
// shadows and its bake's per-vertex albedo.
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "engine/ref/scene_bvh.hpp"

namespace bounce::ref {

// Material `material` of `scene` at texture coordinate `uv`. A material index outside the scene (none
// in a SceneBvh's, which checks them) reads white.
inline glm::vec3 surfaceAlbedo(const SceneDesc& scene, std::uint32_t material, glm::vec2 uv) {
  if (material >= scene.materials.size()) return glm::vec3(1.0f);
  const RefMaterial& m = scene.materials[material];
  glm::vec3 a = m.albedo;
  if (m.albedoTexture >= 0 && std::size_t(m.albedoTexture) < scene.textures.size())
    a *= scene.textures[std::size_t(m.albedoTexture)].sample(uv);
  return glm::clamp(a, glm::vec3(0.0f), glm::vec3(1.0f));
}

// At `hit`, from a SceneBvh over `scene` (or a scene with the same meshes and materials).
inline glm::vec3 surfaceAlbedo(const SceneDesc& scene, const Hit& hit) { return surfaceAlbedo(scene, hit.material, hit.uv); }

}  // namespace bounce::ref
