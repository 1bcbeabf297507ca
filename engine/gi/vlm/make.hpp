#pragma once
// `bounce vlm-make`: subtractive VLM creation (VLM thesis §3.7). "The artist will start from a VLM
// containing the visible geometry. They then must simplify that mesh [...] until they reach the
// desired performance budget. Finally, they must adjust the simplified mesh to make it adhere to
// the previously discussed restrictions" — here done as a first draft the artist then edits:
//   1. sources: the real geometry, one per level entity (or per glTF mesh node of one asset);
//   2. simplify each to its share of the triangle budget (shares by surface area, water-filled) with meshoptimizer (positions welded first
//      so hard-edge seams can collapse); a share below what topology-preserving simplification
//      reaches goes to meshopt_simplifySloppy, and as a last resort keeps the largest triangles;
//   3. offset every vertex along −normal so the virtual geometry sits BEHIND the real surface it
//      stands for (§3.4, Fig. 3.5): by `offset / min_f (n_v · n_f)` along the vertex normal n_v, so
//      the vertex is at least `offset` behind the plane of every face f around it (a cube corner
//      moves `offset` along each axis);
//   4. tags (§3.4): an entity's existing vlm_tag, else the next unused id;
//   5. a glTF with one node per source, extras {"bounce_vlm": {"tag": N}} (reflectance left to the
//      paired real material's albedo, engine/gi/vlm/vlm_mesh.hpp), plus the level snippet to use it.
//
//   MakeResult r = makeVlm(sourcesFromLevel(level, cookCache), {.triangles = 200, .offset = 0.005f});
//   writeVlmGltf(r, "vlm.gltf");  std::puts(levelSnippet(r, "vlm.gltf").c_str());
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/level.hpp"

namespace bounce::gi::vlm {

// One piece of real geometry, world space (level) or asset space (asset), counter-clockwise front.
struct MakeSource {
  std::string name;          // the entity id, or the node name
  std::uint32_t tag = 0;     // 0: assign the next free one
  glm::vec3 albedo{1.0f};    // area-weighted mean base colour (written as the glTF material)
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // triangles
};

struct MakeOptions {
  std::size_t triangles = 1000;  // budget over every source together
  float offset = 0.005f;         // metres behind the real surface (§3.4)
};

// One simplified, offset mesh: a glTF node "vlm-<source name>".
struct MadeMesh {
  std::string source;
  std::uint32_t tag = 0;
  glm::vec3 albedo{1.0f};
  std::vector<glm::vec3> positions, normals;  // normals: the source-side vertex normals (before offset)
  std::vector<std::uint32_t> indices;
  std::size_t inputTriangles = 0;
  bool tagAssigned = false;  // true when the tag was new (the real geometry needs "vlm_tag")
};

struct MakeResult {
  std::vector<MadeMesh> meshes;
  std::size_t inputTriangles = 0, outputTriangles = 0;
  std::size_t skippedDynamic = 0;  // level entities left out (dynamic: attach a VLM by hand)
};

// Simplifies and offsets `sources` (pure geometry, no files). Errors (InputError, `what` names the
// caller's option): an empty source list, a budget below the number of sources, a negative or
// non-finite offset.
MakeResult makeVlm(std::span<const MakeSource> sources, const MakeOptions& options, const std::string& what = "bounce vlm-make");

// Sources from a level: every static entity with a mesh (not a VLM, not dynamic), world space, its
// vlm_tag kept. Nodes marked bounce_vlm are not real geometry and are left out.
std::vector<MakeSource> sourcesFromLevel(const scene::Level& level, const std::filesystem::path& cookCache,
                                         std::size_t* skippedDynamic = nullptr);
// Sources from one glTF asset: every mesh node of the default scene, or of `node`'s subtree, in the
// asset's frame. An unknown node is an InputError naming the asset.
std::vector<MakeSource> sourcesFromAsset(const std::filesystem::path& asset, const std::optional<std::string>& node,
                                         const std::filesystem::path& cookCache);

// Writes `result` as a .gltf with the buffer embedded (one file to hand to an artist): per mesh a
// root node "vlm-<source>" with extras.bounce_vlm.tag, POSITION/NORMAL/indices, and a material
// named after the source whose base colour is its albedo. InternalError when it cannot be written.
void writeVlmGltf(const MakeResult& result, const std::filesystem::path& out);

// The JSON to paste into a level's "entities": one entity referencing `assetFromLevel` (the glTF as
// the level sees it) and, for every tag vlm-make assigned, the "vlm_tag" to add to the real entity.
std::string levelSnippet(const MakeResult& result, const std::string& assetFromLevel);

}  // namespace bounce::gi::vlm
