#include "engine/gi/vlm/vlm_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "engine/asset/cook.hpp"
#include "engine/scene/asset_instances.hpp"
#include "engine/scene/components.hpp"

namespace bounce::gi::vlm {
namespace {

// World-space area-weighted mean albedo of the real geometry per vlm_tag (the "paired real
// material" of §3.4). Real nodes only: a node marked bounce_vlm is not real geometry.
std::map<int, glm::vec3> pairedAlbedos(ecs::Registry& registry, const std::filesystem::path& cookCache) {
  std::map<int, glm::dvec4> sums;  // rgb·area, area
  registry.view<scene::VlmTag, scene::MeshRef>().each([&](ecs::Entity e, scene::VlmTag& tag, scene::MeshRef& ref) {
    const asset::CookedAsset a = scene::cookForRef(ref, cookCache);
    const auto* world = registry.tryGet<scene::WorldTransform>(e);
    const auto* over = registry.tryGet<scene::MaterialOverride>(e);
    scene::forEachInstancedNode(a, ref, world ? world->matrix : glm::mat4(1.0f), [&](int n, const glm::mat4& m) {
      const asset::Node& node = a.nodes[std::size_t(n)];
      if (node.mesh < 0 || node.vlm.present) return;
      for (const asset::Primitive& p : a.meshes[std::size_t(node.mesh)].primitives) {
        glm::vec3 albedo(1.0f);
        if (p.material >= 0) albedo = glm::vec3(a.materials[std::size_t(p.material)].baseColorFactor);
        if (over && over->albedo) albedo = *over->albedo;
        double area = 0.0;
        for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
          auto at = [&](std::size_t i) { return glm::dvec3(m * glm::vec4(p.positions[p.indices[t + i]], 1.0f)); };
          area += 0.5 * glm::length(glm::cross(at(1) - at(0), at(2) - at(0)));
        }
        sums[tag.tag] += glm::dvec4(glm::dvec3(albedo) * area, area);
      }
    });
  });
  std::map<int, glm::vec3> out;
  for (const auto& [tag, s] : sums)
    if (s.w > 0.0) out[tag] = glm::vec3(glm::dvec3(s) / s.w);
  return out;
}

// The light parameters of one VLM node, by the precedence collectVlms() documents.
struct NodeParams {
  std::uint32_t tag = 0;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  std::optional<glm::vec3> reflectance;  // unset: paired albedo, else the primitive's base colour
};

NodeParams paramsFor(const scene::Vlm* c, const asset::NodeVlm& x) {
  NodeParams p;
  if (x.present) {
    p.tag = x.tag;
    if (x.hasColor) p.color = x.color;
    if (x.hasIntensity) p.intensity = x.intensity;
    if (x.hasReflectance) p.reflectance = x.reflectance;
  }
  if (c) {
    p.tag = std::uint32_t(c->tag);
    if (c->color) p.color = *c->color;
    if (c->intensity) p.intensity = *c->intensity;
    if (c->reflectance) p.reflectance = *c->reflectance;
    else if (!x.hasReflectance && c->albedoOverride) p.reflectance = *c->albedoOverride;
  }
  return p;
}

}  // namespace

VlmLightGpu pack(const VirtualLight& l) {
  return {glm::vec4(l.v0, float(l.tag)), glm::vec4(l.v1, 0.0f), glm::vec4(l.v2, 0.0f), glm::vec4(l.scale, 0.0f)};
}

std::vector<VlmMesh> collectVlms(ecs::Registry& registry, const std::filesystem::path& cookCache) {
  std::vector<ecs::Entity> entities;
  registry.view<scene::Vlm>().each([&](ecs::Entity e, scene::Vlm&) { entities.push_back(e); });
  // Plain meshes may carry VLM nodes (extras.bounce_vlm); they are checked below.
  registry.view<scene::MeshRef>().each([&](ecs::Entity e, scene::MeshRef&) { entities.push_back(e); });
  std::sort(entities.begin(), entities.end());  // deterministic light order
  entities.erase(std::unique(entities.begin(), entities.end()), entities.end());
  const std::map<int, glm::vec3> paired = pairedAlbedos(registry, cookCache);
  std::vector<VlmMesh> out;
  for (ecs::Entity e : entities) {
    const scene::Vlm* c = registry.tryGet<scene::Vlm>(e);
    const scene::MeshRef& ref = c ? c->mesh : registry.get<scene::MeshRef>(e);
    const asset::CookedAsset a = scene::cookForRef(ref, cookCache);  // as the renderer cooks it
    VlmMesh m;
    m.entity = e;
    const auto* name = registry.tryGet<scene::Name>(e);
    m.name = name ? name->id : std::to_string(e.index());
    m.dynamic = registry.has<scene::Dynamic>(e);
    // Node transforms only: the entity's own world matrix is applied per frame (appendPlaced).
    scene::forEachInstancedNode(a, ref, glm::mat4(1.0f), [&](int n, const glm::mat4& local) {
      const asset::Node& node = a.nodes[std::size_t(n)];
      if (node.mesh < 0 || (!c && !node.vlm.present)) return;
      const NodeParams params = paramsFor(c, node.vlm);
      const bool mirror = glm::determinant(glm::mat3(local)) < 0.0f;
      for (const asset::Primitive& p : a.meshes[std::size_t(node.mesh)].primitives) {
        glm::vec3 refl(1.0f);
        if (params.reflectance) refl = *params.reflectance;
        else if (auto it = paired.find(int(params.tag)); it != paired.end()) refl = it->second;
        else if (p.material >= 0 && std::size_t(p.material) < a.materials.size())
          refl = glm::vec3(a.materials[std::size_t(p.material)].baseColorFactor);
        const glm::vec3 scale = refl * params.color * params.intensity;
        for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {  // cook validated every index
          auto at = [&](std::size_t i) { return glm::vec3(local * glm::vec4(p.positions[p.indices[t + i]], 1.0f)); };
          VirtualLight l{at(0), at(1), at(2), scale, params.tag};
          if (mirror) std::swap(l.v1, l.v2);
          m.local.push_back(l);
        }
      }
    });
    if (c || !m.local.empty()) out.push_back(std::move(m));
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

glm::vec3 applyOverride(glm::vec3 scale, const scene::VlmOverride& o) {
  if (o.hueDeg != 0.0f) {
    // Rotation by θ about the unit grey axis k: v cosθ + (k × v) sinθ + k (k·v)(1 − cosθ). It keeps
    // the grey component k·v (so white stays white) and turns the chroma: red → green at 120°.
    const float theta = o.hueDeg * std::numbers::pi_v<float> / 180.0f;
    const glm::vec3 k(std::numbers::inv_sqrt3_v<float>);
    const float c = std::cos(theta), s = std::sin(theta);
    scale = glm::max(scale * c + glm::cross(k, scale) * s + k * glm::dot(k, scale) * (1.0f - c), glm::vec3(0.0f));
  }
  return scale * o.color * o.intensity;
}

std::vector<std::uint32_t> tagsOf(std::span<const VirtualLight> lights) {
  std::vector<std::uint32_t> tags;
  for (const auto& l : lights)
    if (l.tag) tags.push_back(l.tag);
  std::sort(tags.begin(), tags.end());
  tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
  return tags;
}

}  // namespace bounce::gi::vlm
