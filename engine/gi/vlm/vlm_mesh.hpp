#pragma once
// Virtual Light Meshes of a level (thesis §3.1): every entity with a scene::Vlm component gives
// its mesh's triangles, each a one-sided diffuse virtual light, in the entity's local frame (glTF
// node transforms applied); each frame they are placed with the entity's world matrix, so VLMs on
// dynamic entities move with them (§3.5 "animation", issue 5 §5).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/ecs/registry.hpp"
#include "engine/scene/level.hpp"

namespace bounce::gi::vlm {

// One virtual light. scale = reflectance × colour × intensity (§3.3, §3.5): the emitted radiance is
// L = scale · E / π for the irradiance E the real lights deliver to it (phase 1).
struct VirtualLight {
  glm::vec3 v0{0.0f}, v1{0.0f}, v2{0.0f};  // counter-clockwise seen from the emitting side
  glm::vec3 scale{0.0f};
  std::uint32_t tag = 0;  // §3.4 id; 0 = none
};

// std430 mirror of VlmLight in shaders/vlm/vlm_common.glsl.
struct VlmLightGpu {
  glm::vec4 v0, v1, v2, scale;  // v0.w = tag as a float (exact below 2^24: level.cpp caps tags there)
};
static_assert(sizeof(VlmLightGpu) == 64);
VlmLightGpu pack(const VirtualLight& l);

struct VlmMesh {
  ecs::Entity entity;
  std::string name;  // the entity's id
  bool dynamic = false;
  std::vector<VirtualLight> local;  // entity-local triangles
};

// Every VLM of the registry (sorted by entity), assets cooked through `cookCache`:
//   - an entity with a `vlm` component: every mesh node of its instanced subtree;
//   - an entity with a plain `mesh`: the nodes whose glTF extras say "bounce_vlm" (its other nodes
//     are real geometry, drawn as usual).
// Per node, each key is the first given of: the entity's `vlm` component, the node's
// extras.bounce_vlm, the default. tag: component, extras (a mesh node of a `vlm` entity without
// extras takes the component's tag). color [1,1,1] and intensity 1 by default. reflectance:
// component, extras, the `vlm` entity's "material" albedo, then the PAIRED real material's albedo
// (the area-weighted mean base colour — level albedo override, else the glTF base colour factor;
// textures are not averaged — of the real geometry whose vlm_tag equals the tag, §3.4), and last
// the VLM primitive's own base colour factor. InputError for a broken asset.
std::vector<VlmMesh> collectVlms(ecs::Registry& registry, const std::filesystem::path& cookCache);

// Per-tag artistic override (§3.5, Fig. 5.5) applied to a light's scale: the hue rotated by
// o.hueDeg about the grey axis (Rodrigues; negative channels clamped to 0), times o.color and
// o.intensity.
glm::vec3 applyOverride(glm::vec3 scale, const scene::VlmOverride& o);
// The tags of `lights`, sorted, each once (0 = none is left out).
std::vector<std::uint32_t> tagsOf(std::span<const VirtualLight> lights);

// Appends `mesh`'s triangles placed by `world`; a mirroring matrix (det < 0) swaps two vertices so
// the emitting side stays the one the artist modelled.
void appendPlaced(const VlmMesh& mesh, const glm::mat4& world, std::vector<VirtualLight>& out);

}  // namespace bounce::gi::vlm
