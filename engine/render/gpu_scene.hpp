#pragma once
// GpuScene: the bridge from the ECS to the renderer. load() cooks (through the content cache) and
// uploads every glTF asset the registry's MeshRef components name; extract() turns the registry's
// current state into a RenderWorld — instances, draws, lights, camera and shadow layers — so that
// passes never touch the registry.
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

#include "engine/asset/cooked_asset.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/image.hpp"
#include "engine/render/mesh_gpu.hpp"
#include "engine/render/pipelines.hpp"
#include "engine/render/render_world.hpp"
#include "engine/scene/level.hpp"

namespace bounce::render {

struct ExtractOptions {
  VkExtent2D extent{1, 1};
  std::uint32_t shadowResolution = 1024;
  // Skinned meshes: skinned by the GPU pass (true) or posed on the CPU and uploaded (false; the CPU
  // face of the same evaluation, for comparison and for meshes the pass does not take).
  bool gpuSkinning = true;
};

class GpuScene {
 public:
  GpuScene(gpu::Context& ctx, const Pipelines& pipelines, gpu::SamplerCache& samplers,
           std::filesystem::path cookCache);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Cooks and uploads every asset named by a MeshRef (once per distinct asset + options).
  void load(ecs::Registry& registry);
  // Fills `world` from the registry's transforms (run the transform system first).
  void extract(ecs::Registry& registry, const scene::Level& level, const ExtractOptions& options,
               RenderWorld& world) const;

  std::size_t assetCount() const { return assets_.size(); }
  std::size_t triangleCount() const { return triangles_; }

 private:
  struct AssetGpu {
    asset::CookedAsset cpu;
    std::vector<std::unique_ptr<MeshGpu>> meshes;
    std::vector<gpu::Image> textures;
    std::vector<VkDescriptorSet> materialSets;  // one per material, +1 default at the end
  };
  const AssetGpu& upload(const scene::MeshRef& ref);
  void uploadSkinVertices(AssetGpu& a);  // MeshGpu::skinVertices of every GPU-skinnable mesh (or cage)
  void uploadStencils(AssetGpu& a, std::size_t mesh);  // MeshGpu::stencilRows/Weights of a refined mesh
  static std::string key(const scene::MeshRef& ref);

  gpu::Context& ctx_;
  const Pipelines& pipelines_;
  gpu::SamplerCache& samplers_;
  std::filesystem::path cache_;
  gpu::DescriptorAllocator materialDescriptors_;  // never reset: material sets live with the scene
  gpu::Image white_;                              // 1×1 white, bound where a material has no texture
  std::map<std::string, std::unique_ptr<AssetGpu>> assets_;
  std::size_t triangles_ = 0;
};

// Shadow-atlas layers of every shadow-casting light (point: six cube faces, +X −X +Y −Y +Z −Z as
// lights.glsl's cubeFace(); spot: one perspective; directional: one orthographic fitted to the
// scene bounds), and the matching LightGpu::shadow fields. Exposed for tests.
void buildShadowLayers(RenderWorld& world, std::uint32_t resolution);

// Whether the world-space box [lo, hi] can reach the frustum of `viewProj` (Vulkan clip space);
// conservative (a box near a frustum corner may pass). nearPlane false: ignore z ≥ 0.
bool boxMeetsFrustum(const glm::mat4& viewProj, glm::vec3 lo, glm::vec3 hi, bool nearPlane);

// Vulkan projection (depth 0..1, +Y down in clip space) from glTF-style parameters.
glm::mat4 perspectiveVk(float yfovRad, float aspect, float near, float far);

}  // namespace bounce::render
