#include "engine/scene_export/flatten.hpp"

#include <map>
#include <variant>

#include <glm/gtc/quaternion.hpp>

#include "engine/anim/animator.hpp"
#include "engine/anim/instances.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/scene/asset_instances.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::scene_export {
namespace {

asset::LightType toAsset(scene::LightType t) {
  switch (t) {
    case scene::LightType::Point: return asset::LightType::Point;
    case scene::LightType::Spot: return asset::LightType::Spot;
    case scene::LightType::Directional: break;
  }
  return asset::LightType::Directional;
}

}  // namespace

glm::mat4 nodeLocal(const asset::Node& n) { return scene::nodeLocal(n); }

glm::mat4 rigid(const glm::mat4& m) {
  const glm::vec3 z = glm::normalize(glm::vec3(m[2]));
  glm::vec3 y = glm::vec3(m[1]);
  y = y - glm::dot(y, z) * z;
  // A degenerate Y (parallel to Z) cannot happen for the invertible transforms levels allow; fall
  // back to any perpendicular so the result stays a rotation.
  if (glm::dot(y, y) < 1e-20f) y = std::abs(z.y) < 0.9f ? glm::vec3(0, 1, 0) - z.y * z : glm::vec3(1, 0, 0) - z.x * z;
  y = glm::normalize(y);
  const glm::vec3 x = glm::normalize(glm::cross(y, z));
  glm::mat4 r(1.0f);
  r[0] = glm::vec4(x, 0.0f);
  r[1] = glm::vec4(y, 0.0f);
  r[2] = glm::vec4(z, 0.0f);
  r[3] = glm::vec4(glm::vec3(m[3]), 1.0f);
  return r;
}

FlatScene flattenLevel(const scene::Level& level, double timeSeconds, const std::filesystem::path& cookCache) {
  FlatScene out;
  out.name = level.name;

  // Cook first, so an asset error leaves nothing behind and the registry is only built once.
  std::map<std::string, std::size_t> assetIndex;
  for (const auto& e : level.entities) {
    if (!e.mesh) continue;
    const std::string k = scene::assetKey(*e.mesh);
    if (assetIndex.count(k)) continue;
    FlatAsset a{e.mesh->asset, scene::cookForRef(*e.mesh, cookCache)};  // also rejects a bad node name
    assetIndex[k] = out.assets.size();
    out.assets.push_back(std::move(a));
  }

  ecs::Registry registry;
  const std::vector<ecs::Entity> entities = scene::instantiate(level, registry);
  scene::motionSystem(registry, timeSeconds);
  anim::attachAnimators(registry, cookCache);
  anim::animationSystem(registry, timeSeconds);
  scene::transformSystem(registry);
  const ecs::Entity activeCamera = scene::activeCamera(registry);

  for (std::size_t ei = 0; ei < entities.size(); ++ei) {
    const ecs::Entity e = entities[ei];
    const scene::EntityDesc& desc = level.entities[ei];
    out.entities.push_back({desc.id, registry.has<scene::Dynamic>(e), desc.material});
    const glm::mat4 world = registry.get<scene::WorldTransform>(e).matrix;

    if (const auto* ref = registry.tryGet<scene::MeshRef>(e)) {
      const std::size_t ai = assetIndex.at(scene::assetKey(*ref));
      const asset::CookedAsset& a = out.assets[ai].cooked;
      const anim::Pose* pose = registry.tryGet<anim::Pose>(e);
      const glm::mat4 skinFrame = pose ? anim::skinFrame(a, *ref, world, *pose) : world;
      scene::forEachInstancedNode(a, *ref, world, [&](int n, const glm::mat4& m) {
        const asset::Node& node = a.nodes[std::size_t(n)];
        const std::string nodeName = node.name.empty() ? "node" + std::to_string(n) : node.name;
        if (node.light >= 0)
          out.lights.push_back({ei, desc.id + "/" + nodeName, a.lights[std::size_t(node.light)], true, rigid(m)});
        if (node.mesh < 0 || node.vlm.present) return;  // VLM nodes are not real
        MeshInstance inst{ei, ai, n, node.mesh, m, {}, {}};
        if (pose && anim::isDeformed(a, n)) {  // the same CPU evaluation the renderer draws
          const std::size_t prims = a.meshes[std::size_t(node.mesh)].primitives.size();
          inst.posedPositions.resize(prims);
          inst.posedNormals.resize(prims);
          for (std::size_t pi = 0; pi < prims; ++pi)
            if (anim::posePrimitive(a, n, pi, pose, inst.posedPositions[pi], inst.posedNormals[pi])) inst.world = skinFrame;
        }
        out.meshes.push_back(std::move(inst));
      }, pose ? &pose->local : nullptr);
    }

    if (const auto* L = registry.tryGet<scene::Light>(e)) {
      asset::Light light;
      light.name = desc.id + "/light";
      light.type = toAsset(L->type);
      light.color = L->color;
      light.intensity = L->intensity;
      light.range = L->range.value_or(0.0f);
      light.innerConeAngle = L->innerConeRad;
      light.outerConeAngle = L->outerConeRad;
      out.lights.push_back({ei, desc.id + "/light", light, L->shadows, rigid(world)});
    }

    if (const auto* cam = registry.tryGet<scene::Camera>(e))
      out.cameras.push_back({ei, *cam, rigid(world), e == activeCamera});
  }
  return out;
}

}  // namespace bounce::scene_export
