#pragma once
// How a MeshRef becomes world-space geometry. One definition shared by everything that draws,
// traces or exports a level (the renderer's GpuScene, the reference path tracer, the exporter), so
// the ground truth and the picture can never expand a level differently.
//   - the asset is cooked with the MeshRef's subdivision request (cookForRef);
//   - an entity instances its asset's named node subtree, or every root of the default scene;
//   - a node's world matrix = entity WorldTransform · the node-local chain (glTF T·R·S or matrix).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/asset/cook.hpp"
#include "engine/asset/cooked_asset.hpp"
#include "engine/scene/components.hpp"

namespace bounce::scene {

// A node's local matrix: `matrix`, or T·R·S (glTF order).
glm::mat4 nodeLocal(const asset::Node& node);

// Identifies a MeshRef's cooked result: the asset path plus any subdivision request.
std::string assetKey(const MeshRef& ref);

// The cook options a MeshRef implies: its subdivision request on the named node, or on every node
// with a mesh when no node is named (learnt from a plain cook through `cacheDir`).
asset::CookOptions cookOptionsForRef(const MeshRef& ref, const std::filesystem::path& cacheDir);

// Cooks (through `cacheDir`) the MeshRef's asset with its subdivision request: on the named node,
// or on every node with a mesh when no node is named.
asset::CookedAsset cookForRef(const MeshRef& ref, const std::filesystem::path& cacheDir);

// The asset node a MeshRef names, or -1 for "the default scene". An unknown name or an index out
// of range is an InputError naming the asset.
int findNode(const asset::CookedAsset& asset, const MeshRef& ref);

// Visits every node of the instanced subtree in pre-order (children in file order) with its world
// matrix. Checks the node first (findNode). `locals` (one matrix per node, an animation pose's:
// engine/anim) replaces nodeLocal() when given.
void forEachInstancedNode(const asset::CookedAsset& asset, const MeshRef& ref, const glm::mat4& entityWorld,
                          const std::function<void(int node, const glm::mat4& world)>& visit,
                          const std::vector<glm::mat4>* locals = nullptr);

}  // namespace bounce::scene
