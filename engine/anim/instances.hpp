#pragma once
// Where posed geometry goes in the world, for everything that draws, traces or exports a level
// (the renderer, the reference tracer, the exporter), so the three agree:
//   - a node's world matrix: scene::forEachInstancedNode with the pose's local matrices;
//   - a skinned node's vertices (posePrimitive(): asset space): skinFrame(), the entity's world
//     matrix taken back through the instanced root's ancestors, since the spec ignores the skinned
//     node's own transform.
#include <glm/glm.hpp>

#include "engine/anim/pose.hpp"
#include "engine/asset/cooked_asset.hpp"
#include "engine/scene/components.hpp"

namespace bounce::anim {

// entityWorld · inverse(model of the instanced root's parent): asset space → world. For a MeshRef
// without a node (the default scene), entityWorld itself.
glm::mat4 skinFrame(const asset::CookedAsset& asset, const scene::MeshRef& ref, const glm::mat4& entityWorld,
                    const Pose& pose);

}  // namespace bounce::anim
