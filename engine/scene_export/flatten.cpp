#include "engine/scene_export/flatten.hpp"

#include <map>
#include <variant>

#include <glm/gtc/quaternion.hpp>

#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::scene_export {
namespace {

std::string nodeKey(const std::variant<std::string, std::uint32_t>& node) {
  return std::holds_alternative<std::string>(node) ? std::get<std::string>(node)
                                                   : std::to_string(std::get<std::uint32_t>(node));
}

asset::Subdivision toAsset(const scene::Subdivision& s) {
  return {static_cast<asset::SubdivisionScheme>(static_cast<std::uint32_t>(s.scheme)),
          static_cast<std::uint32_t>(s.levels)};
}

// Same key and cook options as GpuScene::key/upload, so the export draws what the renderer draws.
std::string assetKey(const scene::MeshRef& ref) {
  std::string k = ref.asset.string();
  if (ref.subdivision) {
    k += "|subdiv:" + std::to_string(int(ref.subdivision->scheme)) + ":" + std::to_string(ref.subdivision->levels);
    if (ref.node) k += ':' + nodeKey(*ref.node);
  }
  return k;
}

asset::CookedAsset cookFor(const scene::MeshRef& ref, const std::filesystem::path& cache) {
  asset::CookOptions options;
  if (ref.subdivision) {
    if (ref.node) {
      options.subdivision[nodeKey(*ref.node)] = toAsset(*ref.subdivision);
    } else {  // every node with a mesh: learn the node list from a plain cook first
      const auto plain = asset::loadOrCook(ref.asset, cache, {});
      for (std::size_t i = 0; i < plain.nodes.size(); ++i)
        if (plain.nodes[i].mesh >= 0) options.subdivision[std::to_string(i)] = toAsset(*ref.subdivision);
    }
  }
  return asset::loadOrCook(ref.asset, cache, options);
}

// The node a MeshRef names, or -1 for the default scene; the renderer's messages for bad names.
int findNode(const asset::CookedAsset& a, const scene::MeshRef& ref) {
  if (!ref.node) return -1;
  if (auto* index = std::get_if<std::uint32_t>(&*ref.node)) {
    if (*index >= a.nodes.size())
      throwInputError(ref.asset.string(), "/nodes", "node " + std::to_string(*index) + " does not exist",
                      "an index below " + std::to_string(a.nodes.size()));
    return static_cast<int>(*index);
  }
  const auto& name = std::get<std::string>(*ref.node);
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    if (a.nodes[i].name == name) return static_cast<int>(i);
  throwInputError(ref.asset.string(), "/nodes", "no node named '" + name + "'", "a node name of the asset");
}

asset::LightType toAsset(scene::LightType t) {
  switch (t) {
    case scene::LightType::Point: return asset::LightType::Point;
    case scene::LightType::Spot: return asset::LightType::Spot;
    case scene::LightType::Directional: break;
  }
  return asset::LightType::Directional;
}

}  // namespace

glm::mat4 nodeLocal(const asset::Node& n) {
  if (n.hasMatrix) return n.matrix;
  return glm::translate(glm::mat4(1.0f), n.translation) * glm::mat4_cast(n.rotation) *
         glm::scale(glm::mat4(1.0f), n.scale);
}

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
    const std::string k = assetKey(*e.mesh);
    if (assetIndex.count(k)) continue;
    FlatAsset a{e.mesh->asset, cookFor(*e.mesh, cookCache)};
    findNode(a.cooked, *e.mesh);  // reject a bad node name before anything is exported
    assetIndex[k] = out.assets.size();
    out.assets.push_back(std::move(a));
  }

  ecs::Registry registry;
  const std::vector<ecs::Entity> entities = scene::instantiate(level, registry);
  scene::motionSystem(registry, timeSeconds);
  scene::transformSystem(registry);
  const ecs::Entity activeCamera = scene::activeCamera(registry);

  for (std::size_t ei = 0; ei < entities.size(); ++ei) {
    const ecs::Entity e = entities[ei];
    const scene::EntityDesc& desc = level.entities[ei];
    out.entities.push_back({desc.id, registry.has<scene::Dynamic>(e), desc.material});
    const glm::mat4 world = registry.get<scene::WorldTransform>(e).matrix;

    if (const auto* ref = registry.tryGet<scene::MeshRef>(e)) {
      const std::size_t ai = assetIndex.at(assetKey(*ref));
      const asset::CookedAsset& a = out.assets[ai].cooked;
      // Pre-order walk; the stack holds (node, parent world matrix).
      std::vector<std::pair<int, glm::mat4>> stack;
      if (int root = findNode(a, *ref); root >= 0) {
        stack.push_back({root, world});
      } else {
        for (auto r = a.rootNodes.rbegin(); r != a.rootNodes.rend(); ++r) stack.push_back({*r, world});
      }
      while (!stack.empty()) {
        auto [n, parent] = stack.back();
        stack.pop_back();
        const asset::Node& node = a.nodes[std::size_t(n)];
        const glm::mat4 m = parent * nodeLocal(node);
        for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, m});
        const std::string nodeName = node.name.empty() ? "node" + std::to_string(n) : node.name;
        if (node.light >= 0)
          out.lights.push_back({ei, desc.id + "/" + nodeName, a.lights[std::size_t(node.light)], true, rigid(m)});
        if (node.mesh >= 0) out.meshes.push_back({ei, ai, n, node.mesh, m});
      }
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
