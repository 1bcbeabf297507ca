#include "engine/gi/vlm/vlm_mesh.hpp"

#include <algorithm>

#include "engine/asset/cook.hpp"
#include "engine/scene/asset_instances.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/level.hpp"

namespace bounce::vlm {

VlmLightGpu pack(const VirtualLight& l) {
  return {glm::vec4(l.v0, float(l.tag)), glm::vec4(l.v1, 0.0f), glm::vec4(l.v2, 0.0f), glm::vec4(l.scale, 0.0f)};
}

std::vector<VlmMesh> collectVlms(ecs::Registry& registry, const std::filesystem::path& cookCache) {
  std::vector<ecs::Entity> entities;
  registry.view<scene::Vlm>().each([&](ecs::Entity e, scene::Vlm&) { entities.push_back(e); });
  std::sort(entities.begin(), entities.end());  // deterministic light order
  std::vector<VlmMesh> out;
  for (ecs::Entity e : entities) {
    const scene::Vlm& c = registry.get<scene::Vlm>(e);
    const asset::CookedAsset a = scene::cookForRef(c.mesh, cookCache);  // as the renderer cooks it
    VlmMesh m;
    m.entity = e;
    const auto* name = registry.tryGet<scene::Name>(e);
    m.name = name ? name->id : std::to_string(e.index());
    m.dynamic = registry.has<scene::Dynamic>(e);
    // Node transforms only: the entity's own world matrix is applied per frame (appendPlaced).
    scene::forEachInstancedNode(a, c.mesh, glm::mat4(1.0f), [&](int n, const glm::mat4& local) {
      const asset::Node& node = a.nodes[std::size_t(n)];
      if (node.mesh < 0) return;
      const bool mirror = glm::determinant(glm::mat3(local)) < 0.0f;
      for (const asset::Primitive& p : a.meshes[std::size_t(node.mesh)].primitives) {
        glm::vec3 refl(1.0f);
        if (p.material >= 0 && std::size_t(p.material) < a.materials.size())
          refl = glm::vec3(a.materials[std::size_t(p.material)].baseColorFactor);
        if (c.albedoOverride) refl = *c.albedoOverride;
        if (c.reflectance) refl = *c.reflectance;
        const glm::vec3 scale = refl * c.color * c.intensity;
        for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {  // cook validated every index
          auto at = [&](std::size_t i) { return glm::vec3(local * glm::vec4(p.positions[p.indices[t + i]], 1.0f)); };
          VirtualLight l{at(0), at(1), at(2), scale, std::uint32_t(c.tag)};
          if (mirror) std::swap(l.v1, l.v2);
          m.local.push_back(l);
        }
      }
    });
    out.push_back(std::move(m));
  }
  return out;
}

void appendPlaced(const VlmMesh& mesh, const glm::mat4& world, std::vector<VirtualLight>& out) {
  const bool mirror = glm::determinant(glm::mat3(world)) < 0.0f;
  for (VirtualLight l : mesh.local) {
    l.v0 = glm::vec3(world * glm::vec4(l.v0, 1.0f));
    l.v1 = glm::vec3(world * glm::vec4(l.v1, 1.0f));
    l.v2 = glm::vec3(world * glm::vec4(l.v2, 1.0f));
    if (mirror) std::swap(l.v1, l.v2);
    out.push_back(l);
  }
}

}  // namespace bounce::vlm
