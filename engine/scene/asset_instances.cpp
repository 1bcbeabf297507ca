#include "engine/scene/asset_instances.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <utility>
#include <vector>

#include "engine/core/error.hpp"

namespace bounce::scene {
namespace {

asset::Subdivision toAsset(const Subdivision& s) {
  return {static_cast<asset::SubdivisionScheme>(static_cast<std::uint32_t>(s.scheme)),
          static_cast<std::uint32_t>(s.levels)};
}

std::string nodeKey(const std::variant<std::string, std::uint32_t>& node) {
  return std::holds_alternative<std::string>(node) ? std::get<std::string>(node)
                                                   : std::to_string(std::get<std::uint32_t>(node));
}

}  // namespace

glm::mat4 nodeLocal(const asset::Node& n) {
  if (n.hasMatrix) return n.matrix;
  return glm::translate(glm::mat4(1.0f), n.translation) * glm::mat4_cast(n.rotation) *
         glm::scale(glm::mat4(1.0f), n.scale);
}

std::string assetKey(const MeshRef& ref) {
  std::string k = ref.asset.string();
  if (ref.subdivision) {
    k.append("|subdiv:").append(std::to_string(int(ref.subdivision->scheme)));
    k.append(":").append(std::to_string(ref.subdivision->levels));
    if (ref.node) k.append(":").append(nodeKey(*ref.node));
  }
  return k;
}

asset::CookOptions cookOptionsForRef(const MeshRef& ref, const std::filesystem::path& cacheDir) {
  asset::CookOptions options;
  if (ref.subdivision) {
    if (ref.node) {
      options.subdivision[nodeKey(*ref.node)] = toAsset(*ref.subdivision);
    } else {  // every node with a mesh: learn the node list from a plain cook first
      const auto plain = asset::loadOrCook(ref.asset, cacheDir, {});
      for (std::size_t i = 0; i < plain.nodes.size(); ++i)
        if (plain.nodes[i].mesh >= 0) options.subdivision[std::to_string(i)] = toAsset(*ref.subdivision);
    }
  }
  return options;
}

asset::CookedAsset cookForRef(const MeshRef& ref, const std::filesystem::path& cacheDir) {
  auto cooked = asset::loadOrCook(ref.asset, cacheDir, cookOptionsForRef(ref, cacheDir));
  findNode(cooked, ref);  // reject a bad node name before anything uses the asset
  return cooked;
}

int findNode(const asset::CookedAsset& a, const MeshRef& ref) {
  if (!ref.node) return -1;
  if (const auto* index = std::get_if<std::uint32_t>(&*ref.node)) {
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

void forEachInstancedNode(const asset::CookedAsset& a, const MeshRef& ref, const glm::mat4& entityWorld,
                          const std::function<void(int node, const glm::mat4& world)>& visit,
                          const std::vector<glm::mat4>* locals) {
  // Pre-order walk; the stack holds (node, parent's world matrix), pushed in reverse so children
  // come out in file order. Cycles cannot occur: the cooker rejects them.
  std::vector<std::pair<int, glm::mat4>> stack;
  if (const int root = findNode(a, ref); root >= 0) {
    stack.push_back({root, entityWorld});
  } else {
    for (auto r = a.rootNodes.rbegin(); r != a.rootNodes.rend(); ++r) stack.push_back({*r, entityWorld});
  }
  while (!stack.empty()) {
    const auto [n, parent] = stack.back();
    stack.pop_back();
    const asset::Node& node = a.nodes[n];
    const glm::mat4 world = parent * (locals ? (*locals)[std::size_t(n)] : nodeLocal(node));
    visit(n, world);
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
  }
}

}  // namespace bounce::scene
