#pragma once
// The DNRT render-graph node (paper §5.2): one pass "dnrt" that adds every object's L_DNRT
// (shaders/dnrt/dnrt.frag, Eq. 16) to "lighting.hdr" with additive blending, reading
// "gbuffer.albedo", "gbuffer.normal", "gbuffer.depth" and "gbuffer.entity" from the blackboard. Each
// object's own pixels are skipped by their entity id, read from the normal's w where the id fits it
// (NodeSettings::selfInNormal), else from "gbuffer.entity".
//
// Modes (scene::DnrtMode: NodeObject::mode from the level's "mode", NodeSettings::mode for all):
// - box (default), better than the paper's full-screen pass per object: each object rasterises its
//   outer cube (back faces, depth-tested GREATER_OR_EQUAL against the G-buffer depth, read-only, so
//   surfaces behind the cube never reach the shader), so the cost follows the pixels the cube covers
//   whose surface is not behind it (inside the cube or in front of it);
// - fullscreen: the paper's mode (a full-screen triangle per object), for comparison;
// - clustered (issue 15, cluster.hpp): one full-screen draw per 32 objects, each pixel reading the
//   G-buffer once and visiting only the objects whose outer cube covers its 16×16 tile, the fields
//   read from one 3D atlas. An object with intrusion, or whose field no longer fits the atlas, is
//   drawn as a box instead. Same image as the others within fp16 blending (one blend, not one per object).
// A box or full-screen object's draw sits in its own GPU timestamp scope "dnrt/<name>" inside the
// pass's scope (profiling per object); a clustered draw has none of its own (it is all objects).
//
// Intrusion (§5.2.3), per object: a pass "dnrt.cube/<name>" renders every OTHER drawn mesh from o
// into six 90° views (distance from o, R32F, 128² per face); the object's term then reaches r only
// if nothing lies between o and r (shaders/dnrt/intrusion.glsl).
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/gi/dnrt/cluster.hpp"
#include "engine/gi/dnrt/field.hpp"
#include "engine/gi/dnrt/gpu_object.hpp"
#include "engine/gi/probes/node.hpp"
#include "engine/gi/upsample_pass.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"
#include "engine/scene/components.hpp"

namespace bounce::gi::dnrt {

using Mode = scene::DnrtMode;

// One field's 3 (4 SH) or 7 (9 SH) RGBA8 3D textures (Table 2), uploaded once. Keeps the field's
// CPU copy for the clustered mode's atlas, which is built when a new field first appears there.
class FieldTextures {
 public:
  FieldTextures(gpu::Context& ctx, const Field& field, const std::string& name);
  // Slot 0..6 of the shader's set 2; a 4-SH field answers its texture 0 for slots 3..6 (never read).
  VkImageView view(int slot) const;
  const Field& field() const { return *field_; }
  const std::shared_ptr<const Field>& sharedField() const { return field_; }
  // Unique for the process (an address may be reused by a later FieldTextures, an id is not).
  std::uint64_t id() const { return id_; }

 private:
  std::vector<std::unique_ptr<gpu::Image>> images_;
  std::shared_ptr<const Field> field_;
  std::uint64_t id_ = 0;
};

struct NodeObject {
  const FieldTextures* textures = nullptr;  // must outlive the frame's execution
  DnrtObjectGpu data;                       // packObject(field, world, radiance SH at o)
  std::string name;                         // timestamp scope "dnrt/<name>" (the entity id)
  bool intrusion = false;                   // render and test an intrusion map (§5.2.3)
  Mode mode = Mode::Box;                    // the level's "mode"
  // Optional second term of the same object, summed into its combined volume in the same dispatch
  // (combine.comp kOcclusion): an occlusion-only field (−k_j) with the lights' c_j negated
  // ("lights_in_anti_radiance": false, runtime.hpp). Same placement as `data`; null: none.
  const FieldTextures* occlusion = nullptr;
  DnrtObjectGpu occlusionData;
};

struct NodeSettings {
  std::optional<Mode> mode;  // every object in this mode, whatever NodeObject::mode says (key M)
  std::uint32_t intrusionResolution = 128;  // texels per cube face
  // Clustered mode: cut each tile's mask by its pixels' depth range on the GPU (tile_cull.comp)
  // before the draw. Off: the CPU's screen-hull masks as they are (same image; tests compare them).
  bool tileCull = true;
  // The self test reads the entity id + 1 from the normal's w where the object's id (clustered: every
  // id of the batch) fits it (render::kEntityInNormalMax). Off: every draw fetches gbuffer.entity, the
  // path of larger ids (same image; tests compare them).
  bool selfInNormal = true;
  // G-buffer pixels per shaded sample along each axis: 1 (full), 2 (half), 4 (quarter) — the level's
  // "dnrt": {"resolution"} (scene::DnrtConfig; names and checks gi/resolution.hpp). Below full, the
  // box, full-screen and clustered draws shade the transient "dnrt.half" / "dnrt.quarter"
  // (⌈size/step⌉, cleared to 0, no depth attachment) at G-buffer pixel step·j, without ρ_r, and the pass
  // "dnrt.upsample" (gi/upsample_pass.hpp) adds ρ_r times its depth- and normal-aware upsample
  // (SL's weights, gi/upsample.hpp) to "lighting.hdr" at every pixel.
  std::uint32_t step = 1;
  // The fused mode with one object at full resolution (addFused): draw the probes pass as the object's outer
  // cube, its term evaluated only where the pixel's surface is not behind the cube (probes::FusedDnrt::split),
  // whenever eyeInsideOuterCube (cluster.hpp) holds. Off: one full-screen draw evaluates it everywhere (tests
  // compare the two). Below full resolution never (measured dearer there).
  bool splitProbes = true;
};


// View-projection of cube face `face` (0..5: +X, −X, +Y, −Y, +Z, −Z) seen from `origin`, 90° square,
// depth 0..1 (Vulkan): the mapping shaders/dnrt/intrusion.glsl inverts.
glm::mat4 cubeFaceViewProj(int face, glm::vec3 origin, float nearM, float farM);

class Node {
 public:
  Node(gpu::Context& ctx, const render::Pipelines& shared, std::uint32_t framesInFlight);

  // Adds the pass when `objects` is not empty (no visible object with a field: no pass, as
  // DESIGN.md asks) and puts the new "lighting.hdr" version on the blackboard.
  void addTo(rg::RenderGraph& graph, const render::PassContext& pc, std::vector<NodeObject> objects,
             NodeSettings settings = {});

  // The tile masks the last clustered draw read (after tile_cull.comp when on; batch b's mask of tile
  // (tx, ty) at b·tiles + ty·tilesX + tx, as binObjects), read back once its frame has completed.
  // Empty before a clustered draw. For tests.
  std::vector<std::uint32_t> lastTileMasks() const;

  // The fused mode ("dnrt": {"mode": "fused"}; runtime.hpp Runtime::addFused): adds pass
  // "dnrt.combine.fused" for `object` alone (its own record buffer: the box draws' buffer may hold other
  // objects this frame) and returns its volume and the record the probes pass adds its term with
  // (probes.frag kDnrt). The object has no intrusion and its entity id + 1 ≤ kEntityInNormalMax (the
  // self test reads the normal's w). `step` 2 or 4 (the level's "dnrt": {"resolution"}) also adds pass
  // "dnrt.fused.reduced" (shaders/dnrt/fused_reduced.comp): the term's position-only factor at G-buffer
  // pixel step·j, which the probes pass blends bilinearly from one texelFetch a pixel (README "DNRT's fused
  // term at reduced resolution, session 17", "DNRT's fused quarter term …, session 18"). `split`
  // (NodeSettings::splitProbes): the probes pass is drawn as the object's outer cube when the eye is
  // inside it (cluster.hpp eyeInsideOuterCube; FusedDnrt::split).
  probes::FusedDnrt addFused(rg::RenderGraph& graph, const render::PassContext& pc, const NodeObject& object,
                             std::uint32_t step = 1, bool split = true);
  // The fused mode with several objects (probes.frag kDnrt 2): the clustered mode's per-pixel visit
  // inside the probes pass. Adds pass "dnrt.combine.fused" for `objects` (at most kClusterBatch, each as
  // addFused asks): their bricks of a combined atlas (combine.comp), this frame's tile masks (the CPU's
  // screen hulls, cut by tile_cull.comp when `tileCull`) and records. `taken[i]`: object i is in the
  // probes pass (false: its field has no room in the atlas; draw it with addTo). Nothing when none is.
  std::optional<probes::FusedDnrt> addFusedCluster(rg::RenderGraph& graph, const render::PassContext& pc,
                                                   const std::vector<NodeObject>& objects, bool tileCull,
                                                   std::vector<bool>& taken);

 private:
  // A shader variant: specialization constants of dnrt.vert/.frag (one pipeline each, made on first use).
  // No SH-count variant: the draw reads this frame's combined volume (combine.comp) for 4 and 9 SH.
  struct Variant {
    bool intrusion = false, fullScreen = false;
    bool selfInNormal = false;  // the object's entity id + 1 ≤ render::kEntityInNormalMax (dnrt.frag)
    std::uint32_t step = 1;     // NodeSettings::step (dnrt.frag kStep; above 1: no depth attachment)
  };
  const gpu::Pipeline& pipeline(const Variant& v);

  // The clustered mode's field atlas (cluster.hpp): every field seen in that mode so far, so it is
  // rebuilt only when a new field appears (after the device is idle: frames in flight read it).
  struct Atlas {
    std::vector<std::uint64_t> ids;        // FieldTextures::id per brick, in atlas order
    std::vector<std::shared_ptr<const Field>> fields;  // the bricks' fields
    AtlasLayout layout;
    std::vector<std::unique_ptr<gpu::Image>> slots;
  };
  // The atlas holding `objects`' fields (grown if needed); brick index per object, -1 = no room.
  std::vector<int> atlasFor(const std::vector<const FieldTextures*>& textures);
  // One object of the clustered draw (addTo) or of the fused probes pass's visit (addFusedCluster).
  struct ClusterItem {
    std::size_t object = 0;   // index into the caller's objects (its record in objectBuffer's buffer)
    int brick = 0;            // its field's brick in the RGBA8 atlas
    int occlusionBrick = -1;  // its occlusion field's brick (NodeObject::occlusion), -1: none
    std::uint32_t z = 0;      // its own brick in this frame's combined atlas (combine.comp)
  };
  // The objects `asked` (indices into `objects`) that have room in the atlas (atlasFor) and in this
  // frame's combined atlas, whose size `combinedSize` grows by each one's padded brick; the others
  // are left out (the caller draws them alone).
  std::vector<ClusterItem> placeInAtlas(const std::vector<NodeObject>& objects, const std::vector<std::size_t>& asked,
                                        glm::uvec3& combinedSize);
  // combine.comp into each item's brick of the combined atlas `target` (`records`: objectBuffer's for `objects`).
  void recordAtlasCombine(VkCommandBuffer cmd, const render::PassContext& pc, gpu::Buffer& records,
                          const std::vector<NodeObject>& objects, const std::vector<ClusterItem>& items,
                          VkImageView target);
  // The items' records (DnrtClusterObject, std140, kClusterBatch a batch) into `records` and this
  // frame's tile masks (the CPU's screen hulls, binObjects) into `tiles`, each (re)made as
  // "<prefix>cluster-objects" / "<prefix>tiles" when too small. Returns the number of masks.
  std::size_t writeClusterBuffers(const render::PassContext& pc, const std::vector<NodeObject>& objects,
                                  const std::vector<ClusterItem>& items, glm::uvec2 resolution, gpu::Buffer& tiles,
                                  gpu::Buffer& records, const std::string& prefix);
  // tile_cull.comp over `batches` batches (each batch's masks cut by its tiles' depth range; `depth` in
  // `depthLayout`), then a barrier before the fragment shaders that read the masks.
  void recordTileCull(VkCommandBuffer cmd, const render::PassContext& pc, VkImageView depth, VkImageLayout depthLayout,
                      gpu::Buffer& tiles, gpu::Buffer& records, std::size_t batches, glm::uvec2 resolution);
  const gpu::Pipeline& clusteredPipeline(bool single, bool selfInNormal, std::uint32_t step);
  // This frame slot's buffer of folded records (DnrtShaderObject per object), written now.
  gpu::Buffer& objectBuffer(std::uint32_t slot, const std::vector<NodeObject>& objects);
  // The same into `ring` (objectBuffers_, or fusedBuffers_ for addFused).
  gpu::Buffer& objectBuffer(std::vector<gpu::Buffer>& ring, std::uint32_t slot, const std::vector<NodeObject>& objects);
  // Object i's combine.comp dispatch (pass dnrt.combine): its vertices [0, size)³ from `slot`'s views at
  // layer srcZ into `target` at layer dstZ, with its occlusion term (`occlusionSlot` non-null; record
  // count + i) from layer occlusionZ summed in the same dispatch. `records`: objectBuffer's, `count` objects.
  using Slots = std::function<VkImageView(int)>;
  void recordCombine(VkCommandBuffer cmd, const render::PassContext& pc, gpu::Buffer& records, std::size_t count,
                     const NodeObject& object, std::size_t i, const Slots& slot, const Slots* occlusionSlot,
                     VkImageView target, std::int32_t srcZ, std::int32_t occlusionZ, std::int32_t dstZ,
                     std::int32_t size);

  gpu::Context& ctx_;
  gpu::DescriptorSetLayout inputLayout_, fieldLayout_;
  gpu::PipelineLayout layout_, cubeLayout_;
  gpu::ShaderModule vert_, frag_;
  // index: intrusion | fullScreen << 1 | selfInNormal << 2 | stepIndex << 3 (step 1, 2, 4: 0, 1, 2)
  std::array<gpu::Pipeline, 24> variants_;
  gpu::Pipeline cube_;
  std::unique_ptr<gpu::Image> noIntrusion_;  // 1×1×6 R32F "nothing nearer than 1e30 m"
  std::vector<gpu::Buffer> objectBuffers_;  // per frame slot, DnrtObjectGpu[]
  std::vector<gpu::Buffer> fusedBuffers_;   // per frame slot, the fused object's records (addFused)
  // Per frame slot, addFusedCluster's tile masks and DnrtClusterObject records (the probes pass's
  // bindings 10 and 11; apart from the clustered draw's, which may run in the same frame).
  std::vector<gpu::Buffer> fusedTileBuffers_, fusedClusterBuffers_;
  gpu::DescriptorSetLayout clusterLayout_;
  gpu::PipelineLayout clusterPipelineLayout_;
  gpu::ShaderModule fullscreenVert_, clusterFrag_;
  std::array<gpu::Pipeline, 12> clustered_;  // index: single | selfInNormal << 1 | stepIndex << 2 (clustered.frag)
  Atlas atlas_;
  std::vector<gpu::Buffer> tileBuffers_, clusterObjectBuffers_;  // per frame slot: masks, DnrtClusterObject[]
  // combine.comp: Σ_j c_j M_j per grid vertex for the box and full-screen draws (index: sh9 |
  // occlusion << 1; occlusion sums the object's occlusion term in the same dispatch).
  gpu::DescriptorSetLayout combineLayout_;
  gpu::PipelineLayout combinePipelineLayout_;
  std::array<gpu::Pipeline, 4> combine_;
  // tile_cull.comp: the clustered draw's tile masks cut by each tile's depth range (one dispatch a batch).
  gpu::DescriptorSetLayout cullLayout_;
  gpu::PipelineLayout cullPipelineLayout_;
  gpu::Pipeline cull_;
  // "dnrt.upsample" (step 2, 4; gi/upsample_pass.hpp).
  ReducedUpsample upsample_;
  // "dnrt.fused.reduced" (fused_reduced.comp, step 2, 4): depth, normal, the combined volume, the target.
  gpu::DescriptorSetLayout fusedReducedInputs_;
  gpu::PipelineLayout fusedReducedLayout_;
  std::array<gpu::Pipeline, 2> fusedReduced_;  // index: step 2, 4 (kStep), made on first use
  std::size_t lastTileSlot_ = 0, lastTileCount_ = 0;  // lastTileMasks: the buffer and its masks
};

}  // namespace bounce::gi::dnrt
