#pragma once
// RenderWorld: everything one frame draws, extracted from the ECS by GpuScene::extract(). Passes
// read only this (and the graph's resources), never the registry: the data flow of DESIGN.md.
#include <set>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/render/gpu_types.hpp"

namespace bounce::render {

struct MeshGpu;

struct DrawItem {
  const MeshGpu* mesh = nullptr;   // vertex (position, normal, uv0: 32 bytes) + uint32 index buffers
  std::uint32_t primitive = 0;     // index into mesh->primitives
  std::uint32_t instance = 0;      // index into RenderWorld::instances
  VkDescriptorSet material = VK_NULL_HANDLE;  // G-buffer set 1: base colour + emissive textures
  std::uint32_t entity = 0;        // entity index (per-object profiling, id buffer)
  bool dynamic = false;
  // A deformed (skinned or morphed) mesh: its vertices this frame start at vertex `posedBase` of
  // RenderWorld::posedVertices instead of mesh->vertices (indices and vertexOffset unchanged).
  static constexpr std::uint32_t kNotPosed = ~0u;
  std::uint32_t posedBase = kNotPosed;
  bool posed() const { return posedBase != kNotPosed; }
  // A posed draw's culling (GpuScene::extract, from the instance's conservative world bounds):
  // whether it can reach the camera's frustum / any shadow layer's. The G-buffer and shadow passes
  // skip a posed draw outside theirs and read the posed vertices only when one is inside, so with
  // no skinned entity visible or casting a shadow the graph culls the skinning and subdivision
  // passes (nothing reads their output). Always true for static draws.
  bool inView = true;
  bool inShadow = true;
  // An SL object with "local_lights" (scene::Sl::localLights, issue 13 §7.3): its shadow on point and
  // spot lights comes from the SL pass "sl.local" alone, so it is left out of their shadow layers
  // (directional lights keep it) — the hard shadow must not count twice.
  bool slLocal = false;
};

// One deformed instance for the skinning compute pass: morph mesh->skinVertices by its
// mesh->morphTargets targets with the weights from weightBase, then (when skinned) skin them with
// the joint matrices from jointBase, into RenderWorld::posedVertices from vertex dstBase.
struct SkinJob {
  const MeshGpu* mesh = nullptr;
  std::uint32_t vertexCount = 0;
  std::uint32_t jointBase = 0;   // into RenderWorld::jointMatrices
  std::uint32_t dstBase = 0;     // into RenderWorld::posedVertices, in vertices
  std::uint32_t weightBase = 0;  // into RenderWorld::morphWeights (mesh->morphTargets of them)
  bool skinned = true;           // false: morph targets only (the node's own frame)
};

// One subdivided skinned instance for the subdivision compute pass: evaluate mesh->stencilRows on
// the cage vertices the skinning pass wrote from srcBase, into RenderWorld::posedVertices from
// vertex dstBase.
struct SubdivisionJob {
  const MeshGpu* mesh = nullptr;
  std::uint32_t vertexCount = 0;  // refined vertices
  std::uint32_t srcBase = 0;      // the cage's posed vertices (a SkinJob's dstBase)
  std::uint32_t dstBase = 0;
};

// One shadow-atlas layer: the light view-projection that rendered it.
struct ShadowLayer {
  glm::mat4 viewProj;
  std::uint32_t light = 0;
};

struct RenderWorld {
  CameraGpu camera{};
  float cameraFar = 100.0f;
  std::vector<InstanceGpu> instances;
  std::vector<DrawItem> draws;
  std::vector<LightGpu> lights;
  std::vector<ShadowLayer> shadowLayers;  // empty when no light casts shadows or `shadows` is off
  glm::vec3 background{0.0f};
  glm::vec3 sceneMin{0.0f}, sceneMax{0.0f};  // world bounds of everything drawn
  std::set<std::string> effects;             // the level's effects (after --effects)
  // Vertices of every deformed mesh instance as posed this frame (engine/anim: morph targets, then
  // skinning), MeshVertex layout (8 floats: position, normal, uv0). Uploaded once per frame; every
  // raster pass reads the same buffer.
  std::vector<float> posedVertices;      // GPU-skinned ranges are placeholders the skinning pass overwrites
  std::vector<SkinJob> skinJobs;         // empty: no skinning pass
  std::vector<SubdivisionJob> subdivisionJobs;  // empty: no subdivision pass (needs skinJobs)
  std::vector<glm::mat4> jointMatrices;  // every skinned instance's joint matrices, back to back
  std::vector<float> morphWeights;       // every GPU-morphed instance's weights, one per target, back to back
  bool has(const std::string& effect) const { return effects.count(effect) != 0; }
  // Whether a posed draw is inside the camera's frustum / a shadow layer's (DrawItem::inView/inShadow).
  bool posedInView() const;
  bool posedInShadow() const;
};

// The distances the depth debug view maps to white (x) and black (y): from the camera to the
// nearest point of the scene bounds (0 inside them) to the farthest corner, capped at the far
// plane — so the view spreads over what is drawn instead of the whole near..far range (issue 16:
// cornell-1 with far 5 m was almost all white).
glm::vec2 depthViewRange(const RenderWorld& world);

}  // namespace bounce::render
