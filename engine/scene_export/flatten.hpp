#pragma once
// A level flattened to world space at one simulation time, as the renderer would draw it:
// the same expansion as GpuScene::extract (engine/render/gpu_scene.cpp), without a GPU.
//
//   FlatScene s = flattenLevel(level, /*timeSeconds=*/1.0, cookCache);
//
// - An entity with a MeshRef instances its asset's node subtree (the named node, or every root
//   of the default scene), each node's world matrix = entity WorldTransform · node local chain.
// - KHR_lights_punctual lights inside the instanced subtree become lights (shadows on, as the
//   renderer does), beside the level's own light entities.
// - Cameras are the level's camera entities; `active` marks the one the renderer uses.
// The motion, animation and transform systems run at `timeSeconds` first, so dynamic props are
// where a frame at that time draws them, and animated characters are in that frame's pose. Everything is listed in level file order, then node pre-order.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/asset/cooked_asset.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/level.hpp"

namespace bounce::scene_export {

struct FlatEntity {
  std::string id;
  bool dynamic = false;
  std::optional<scene::MaterialOverride> material;
};

// One cooked asset with the cook options its MeshRef implies (subdivision).
struct FlatAsset {
  std::filesystem::path source;
  asset::CookedAsset cooked;
};

// One asset node with a mesh, placed in the world.
struct MeshInstance {
  std::size_t entity = 0;  // index into FlatScene::entities
  std::size_t asset = 0;   // index into FlatScene::assets
  int node = -1;           // node of that asset (its name names the instance)
  int mesh = -1;           // mesh of that asset
  glm::mat4 world{1.0f};   // local-to-world, as the renderer's InstanceGpu::model
  // A deformed mesh (skinned or morphed, engine/anim) at the level's time: per primitive, its posed
  // positions and normals (empty = the cooked vertices), in the frame `world` places.
  std::vector<std::vector<glm::vec3>> posedPositions, posedNormals;
};

// A punctual light in Bounce units (README "Level format": point/spot intensity is radiant
// intensity, irradiance I·cosθ/d²; directional intensity is irradiance).
struct LightInstance {
  std::size_t entity = 0;
  std::string name;         // "<entity id>/light", or "<entity id>/<asset node name>"
  asset::Light light;       // type, colour, intensity, range (0 = none), cone angles (radians)
  bool shadows = true;
  glm::mat4 world{1.0f};    // rigid (orthonormal rotation + translation); the light shines down −Z
};

struct CameraInstance {
  std::size_t entity = 0;
  scene::Camera camera;     // yfov (radians), near, far (metres)
  glm::mat4 world{1.0f};    // rigid; the camera looks down −Z with +Y up
  bool active = false;      // the camera the renderer draws from
};

struct FlatScene {
  std::string name;  // the level's name
  std::vector<FlatEntity> entities;  // every level entity, file order
  std::vector<FlatAsset> assets;
  std::vector<MeshInstance> meshes;
  std::vector<LightInstance> lights;
  std::vector<CameraInstance> cameras;
};

// Cooks (through the cache in `cookCache`) every asset the level names and flattens the level at
// `timeSeconds`. Errors: the cook's and the MeshRef's InputErrors (bad asset, unknown node).
FlatScene flattenLevel(const scene::Level& level, double timeSeconds, const std::filesystem::path& cookCache);

// The local matrix of an asset node: `matrix`, or T·R·S (glTF order).
glm::mat4 nodeLocal(const asset::Node& node);

// `m` with its scale (and any shear) removed: translation kept, local −Z direction kept exactly,
// +Y made orthogonal to it (Gram–Schmidt), X = Y × Z. For lights and cameras.
glm::mat4 rigid(const glm::mat4& m);

}  // namespace bounce::scene_export
