#include "engine/anim/instances.hpp"

#include "engine/scene/asset_instances.hpp"

namespace bounce::anim {

glm::mat4 skinFrame(const asset::CookedAsset& a, const scene::MeshRef& ref, const glm::mat4& entityWorld,
                    const Pose& pose) {
  const int root = scene::findNode(a, ref);
  if (root < 0) return entityWorld;
  for (std::size_t n = 0; n < a.nodes.size(); ++n)
    for (std::int32_t c : a.nodes[n].children)
      if (c == root) return entityWorld * glm::inverse(pose.model[n]);
  return entityWorld;  // the root has no parent
}

}  // namespace bounce::anim
