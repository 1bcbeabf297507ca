#pragma once
// `bounce export`: a composed level as ONE glTF 2.0 binary (.glb), so that it can be opened and
// cross-checked in other tools (Blender, glTF viewers, other renderers).
//
//   scene_export::ExportOptions o;  o.timeSeconds = 1.0;  o.cookCache = game::cookCacheDir();
//   scene_export::exportLevel(scene::loadLevel("content/levels/cornell-5.json"), "out.glb", o);
//
// What the file holds (flattenLevel() in flatten.hpp says which instances exist):
// - one root node per level entity, named by its id, identity transform (extras.dynamic marks
//   dynamic entities); its children are world-space nodes: one per instanced asset node with a
//   mesh ("<id>/<node name>"), one per light, one for a camera;
// - meshes are shared: one glTF mesh per (asset mesh, material override) and one set of
//   accessors per asset primitive (POSITION, NORMAL, TEXCOORD_0 float; uint32 indices); the
//   instance node's world matrix is written as `matrix` when it is decomposable into TRS
//   (orthogonal columns, glTF 2.0 §3.5.3). A sheared world matrix (a non-uniform scale above a
//   rotation) is not: that instance gets its own mesh with world-space vertices and an identity
//   node, winding flipped when the determinant is negative;
// - materials: baseColorFactor (level `albedo` replaces rgb), emissiveFactor (level `emissive`
//   replaces it; above 1 it is written as factor / max with KHR_materials_emissive_strength = max),
//   base colour and emissive textures as PNG inside the GLB buffer, metallicFactor 0 and
//   roughnessFactor 1 (Bounce shades every material as Lambertian diffuse);
// - cameras: perspective yfov, znear, zfar, no aspectRatio (the viewer's), on rigid nodes;
// - lights: KHR_lights_punctual, on rigid nodes shining down −Z, spot cone angles in radians.
//
// Light units. Bounce's lighting pass (shaders/passes/lighting.frag) computes outgoing radiance
// L = albedo/π · Σ E_i with E = I·cosθ/d² (point, spot) or E (directional). That is the
// photometric relation of glTF's KHR_lights_punctual with I in candela and E in lux, when one
// Bounce linear radiance unit is read as 1 cd/m² (nit). The conversion is therefore the identity:
// 1 Bounce point/spot intensity unit = 1 cd, 1 Bounce directional unit = 1 lux. The only change
// made: the extension's colour is in [0, 1], so a colour whose largest channel c exceeds 1 is
// written as colour / c with intensity · c (same colour × intensity). Bounce's spot falloff
// (t² of the cosine ramp) and glTF's recommended one (smooth ramp) differ inside the cone
// edge only; the cone angles are written unchanged.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "engine/scene/level.hpp"
#include "engine/scene_export/flatten.hpp"

namespace bounce::scene_export {

struct ExportOptions {
  double timeSeconds = 0.0;           // the motion and transform systems run at this time first
  std::filesystem::path cookCache;    // cooked-asset cache folder (game::cookCacheDir())
};

// Counts of what was written (for the command's summary line and tests).
struct ExportStats {
  std::size_t nodes = 0, meshes = 0, materials = 0, textures = 0, cameras = 0, lights = 0;
  std::size_t instances = 0;   // mesh instance nodes (asset nodes with a mesh)
  std::size_t triangles = 0;   // over all instances
  std::size_t bytes = 0;       // size of the .glb
};

// The GLB bytes of a flattened scene. Throws InternalError if tinygltf cannot serialise it or a
// texture cannot be encoded.
std::vector<std::uint8_t> writeGlb(const FlatScene& scene, ExportStats* stats = nullptr);

// flattenLevel + writeGlb + an atomic write of `out`. Errors: the level's and the assets'
// InputErrors; InternalError naming `out` when it cannot be written.
ExportStats exportLevel(const scene::Level& level, const std::filesystem::path& out, const ExportOptions& options);

}  // namespace bounce::scene_export
