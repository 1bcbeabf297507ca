#pragma once
// The probes node (pass `probes`): per-pixel static indirect diffuse from the baked volume for
// every drawn surface, static or dynamic, added to "lighting.hdr" (shaders/probes/probes.frag).
// The volume is uploaded once, as two images read with texelFetch (SH with the valid flag,
// visibility moments): storage-buffer reads are what made this pass slow on lavapipe.
#include <array>
#include <functional>
#include <memory>
#include <optional>

#include "engine/gi/probes/probe_volume.hpp"
#include "engine/gi/probes/relight_pass.hpp"
#include "engine/gi/technique.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/renderer.hpp"

namespace bounce::gi::probes {

// The volume on the device as shaders/probes/probe_sh.glsl reads it (probes.frag, and the SL
// shadow on the probes' light): SH with the valid flag (RGBA32F) and visibility moments (RG32F).
std::unique_ptr<gpu::Image> uploadSh(gpu::Context& ctx, const ProbeVolume& v);
std::unique_ptr<gpu::Image> uploadMoments(gpu::Context& ctx, const ProbeVolume& v);
// probe_sh.glsl's push-constant block `pc`; bias.w is the includer's flag (probes.frag: multiply by
// "ao.term").
struct ProbePush {
  glm::vec4 originSpacing;
  glm::ivec4 countOrder;
  glm::vec4 bias;
};
ProbePush probePush(const ProbeVolume& v, float flag);

// DNRT's fused mode ("dnrt": {"mode": "fused"}; gi/dnrt/runtime.hpp Runtime::addFused): the dynamic
// objects' L_DNRT added by the probes pass itself (probes.frag kDnrt; dnrt.glsl dnrtFusedTerm for one
// object, dnrt/cluster.glsl for several) at the pixels it already shades, instead of a "dnrt" pass of its own. probes.frag's push block past
// ProbePush (128 bytes in all, the Vulkan minimum of maxPushConstantsSize).
// One object (probes.frag kDnrt 1): its record. Several (kDnrt 2): centreWorld holds 1 / the combined
// atlas's texels per axis (xyz) and the tiles per row (w); the records are in FusedDnrt::bindCluster's block.
struct FusedDnrtPush {
  glm::vec4 worldToQ[3]{};      // rows of r ↦ q (units of R), DnrtShaderObject's
  glm::vec4 centreWorld{0.0f};  // xyz o (m), w R (m)
  glm::vec4 extents{0.0f};      // x inner, y outer (units of R), z entity id + 1 (0 = none), w grid N
};
static_assert(sizeof(ProbePush) + sizeof(FusedDnrtPush) == 128, "probes.frag's push block");
struct FusedDnrt {
  // One object: this frame's Σ_j c_j M_j (pass dnrt.combine.fused), read trilinear. Several: the
  // combined atlas of the same pass, a padded brick per object (gi/dnrt/cluster.hpp).
  rg::Handle<rg::Texture> volume;
  FusedDnrtPush push;
  // Several objects (probes.frag kDnrt 2, the clustered mode's per-pixel visit): writes this frame's
  // tile masks (binding 10, storage) and object records (binding 11, uniform) into the probes pass's
  // set when it records; empty for one object (kDnrt 1).
  std::function<void(gpu::DescriptorWriter&, const render::PassContext&)> bindCluster;
  // Below full resolution (the level's "dnrt": {"resolution"}; step 2 or 4): pass dnrt.fused.reduced's
  // (w·s Σ_j c_j M_j, w) at G-buffer pixel step·j, blended bilinearly from one texelFetch a pixel (probes.frag
  // kDnrtStep, dnrtReducedQuadTap, binding 12;
  // README "DNRT's fused term at reduced resolution, session 17"). Unset at step 1 and for several objects (kDnrt 2 runs at full resolution).
  std::optional<rg::Handle<rg::Texture>> reduced;
  std::uint32_t step = 1;
  // One object (kDnrt 1) at full resolution with the eye inside its outer cube (gi/dnrt/cluster.hpp
  // eyeInsideOuterCube; dnrt::Node::addFused sets it at step 1 only, but any step works here): the pass
  // is drawn as the cube's faces twice (shaders/probes/outer_cube.vert), against the G-buffer depth as a
  // read-only attachment — the fused pipeline where the pixel's surface is not behind the face (the term may
  // be non-zero), the plain one where it is (outside the cube: s(r) = 0) — so the term is evaluated only
  // inside the cube (README "DNRT's fused term only inside its outer cube, session 19"). False: one
  // full-screen triangle with the fused pipeline.
  bool split = false;
};
// Called by the probes node before it adds its pass; adds the passes the fused term reads
// (dnrt.combine.fused, and dnrt.fused.reduced below full resolution) and returns it, or nothing (no fused object this frame: the plain pipeline).
using FusedDnrtHook = std::function<std::optional<FusedDnrt>(rg::RenderGraph&, const render::PassContext&)>;

// The largest |E| change per channel (W/m², E as sh::evalIrradiance) that the uniform block's 8-bit
// L_1/L_2 fractions of L_0 make at any receiver (node.cpp shPackedWords; derivation there): the
// probes pass's output moves by at most ρ/π·ao times it plus the fp16 roundings.
double packedShIrradianceError(const ProbeVolume& v);
// The largest |E| change per channel (W/m²) that the irradiance tiles' bilinear interpolation makes
// at any receiver (node.cpp tileIrradianceError: measured over dense normals, not derived).
double tileIrradianceError(const ProbeVolume& v);
// The uniform block's words (node.cpp shPackedWords; empty when the volume does not fit halves): what
// the probes pass reads, and what relight.comp's pack stage writes for baked + ΔSH (tests compare).
std::vector<std::uint32_t> packedShWords(const ProbeVolume& v);

class ProbeNode final : public TechniqueRuntime {
 public:
  // `pipelines` gives the shared frame layout (set 0: camera).
  // `shInUbo`: read the SH from a uniform block when they fit one (the default; probes.frag
  // kShInUbo), false: always from the image (tests compare the two paths).
  ProbeNode(gpu::Context& ctx, const render::Pipelines& pipelines, ProbeVolume volume, bool shInUbo = true,
            bool tiles = true);
  bool shInUbo() const { return shInUbo_; }
  bool momentsInUbo() const { return momentsInUbo_; }
  // The probes pass taps per-probe irradiance tiles (pass `probes.tiles`, probes.frag kTiles,
  // shaders/probes/probe_tiles.glsl) instead of reading the SH: when the SH are in the block and the
  // tile image fits the device. `tiles` false in the constructor keeps the SH path (tests compare).
  bool tiles() const { return tiles_; }
  // Reads the G-buffer from the blackboard ("gbuffer.albedo", "gbuffer.normal", "gbuffer.depth"),
  // blends into "lighting.hdr" and publishes the new version under the same key.
  void addPasses(rg::RenderGraph& graph, const render::PassContext* pc);
  // For Renderer::setNode("probes", …).
  render::Renderer::GraphNode node() override {
    return [this](rg::RenderGraph& graph, render::PassContext& pc) { addPasses(graph, &pc); };
  }
  const ProbeVolume& volume() const { return volume_; }
  // Level `"probes": {"relight": true}`: pass `probes.relight` (relight_pass.hpp) rewrites the
  // uniform block (when the volume fits it) and the SH image (when read: probes.frag's source past the
  // block, and the SL shadow's) each frame before this pass reads them; any volume size (session 10:
  // before, a volume past 2016 probes kept the baked light). `staticScene` (not owned) must outlive
  // the node: the static geometry V_static is traced against.
  void enableRelight(gpu::Context& ctx, RelightData data, const ref::SceneBvh& staticScene);
  RelightPass* relight() { return relight_.get(); }
  // The volume's device images (uploadSh, uploadMoments), for Services::probeSh / probeMoments.
  const gpu::Image& shImage() const { return *sh_; }
  gpu::Image& shImage() { return *sh_; }  // tests read it back (TRANSFER_SRC usage)
  const gpu::Image& momentsImage() const { return *moments_; }
  // DNRT's fused mode (FusedDnrtHook); an empty function removes it. The hook's owner must outlive the
  // node's frames or remove it first.
  void setFusedDnrt(FusedDnrtHook hook) { fusedDnrt_ = std::move(hook); }
  // Whether the last recorded probes pass was split at a fused object's outer cube (FusedDnrt::split). For tests.
  bool lastPassSplit() const { return lastPassSplit_; }
  // `bounce bench dnrt` only: on frames with a fused DNRT term, also draw pass "probes.baseline" — the same
  // pass without the term (probes.frag kDnrt 0, the full-screen triangle) into a scratch target of the same
  // format and blend, which nothing reads — alternately right before and right after "probes". The term's
  // marginal cost is then the two passes' difference within each frame (TimingCollector::pairedPercentileMs), not
  // across sessions a host's load drifts between (README "DNRT's fused quarter term timed within its frames,
  // session 23"). Off otherwise: it doubles the pass's cost.
  void setTermBaseline(bool on) { termBaseline_ = on; }

 private:
  ProbeVolume volume_;
  std::unique_ptr<gpu::Image> sh_, moments_;
  // sh_'s values in a uniform block when they fit kShUboBytes (probes.frag kShInUbo, layout in
  // node.cpp shPackedWords): llvmpipe gathers a uniform-array word per lane for less than a
  // texelFetch, and L_0 as halves with L_1, L_2 as 8-bit fractions of it take 8 words a probe at
  // order 3 instead of the image's 28 floats (README "What costs what on lavapipe"). Always kShUboBytes long, so the block the shader declares is always bound.
  gpu::Buffer shUbo_;
  bool shInUbo_ = false;
  // The visibility moments as (mean, σ) halves in a second block when they fit (and the SH block
  // is used: the same `shInUbo` switch): one uniform word per probe instead of an RG32F texelFetch.
  gpu::Buffer momentsUbo_;
  bool momentsInUbo_ = false;
  gpu::DescriptorSetLayout setLayout_;
  gpu::PipelineLayout layout_;
  gpu::Pipeline pipeline_;
  // probes.frag with kDnrt 1 at kDnrtStep 1, 2, 4 (one object) and kDnrt 2 (several; FusedDnrt), made on
  // first use; the dummy volume (binding 9), tile masks (10) and records (11) hold otherwise.
  std::array<gpu::Pipeline, 4> fusedPipelines_;
  // FusedDnrt::split's pipelines (outer_cube.vert, the G-buffer depth read-only): kDnrt 1 at kDnrtStep 1, 2, 4
  // where the surface is not behind the cube's face, and the plain one (kDnrt 0) where it is.
  std::array<gpu::Pipeline, 3> splitFusedPipelines_;
  gpu::Pipeline splitPlainPipeline_;
  bool lastPassSplit_ = false;
  bool termBaseline_ = false;
  std::uint64_t baselineFrames_ = 0;  // frames with probes.baseline so far: even ones draw it first
  // What the probes pass (and probes.baseline) read and write.
  struct PassData {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> hdr, ao, tiles, dnrt, dnrtReduced;
  };
  void recordPass(const PassData& d, const rg::PassResources& res, rg::CommandContext& c,
                  const render::PassContext* pc, bool withAo, const std::optional<FusedDnrt>& fused, bool baseline);
  std::vector<std::uint32_t> specialization_;  // kCoeffs, kShInUbo, kMomentsInUbo, kTiles
  std::unique_ptr<gpu::Image> noDnrt_;  // 1³ RGBA16F zero
  gpu::Buffer noDnrtTiles_, noDnrtObjects_;  // one zero mask; kDnrtObjectsBytes of zeros
  FusedDnrtHook fusedDnrt_;
  // Pass `probes.tiles` (shaders/probes/tiles.comp): each probe's E(n) over its octahedral tile,
  // every frame after `probes.relight` into a graph texture only the probes pass reads; without
  // relight no pass: bakedTiles_.
  bool tiles_ = false;
  gpu::DescriptorSetLayout tilesSetLayout_;
  gpu::PipelineLayout tilesLayout_;
  gpu::Pipeline tilesPipeline_;
  // A baked volume's tiles (no relight), built once in the constructor and imported each frame.
  std::unique_ptr<gpu::Image> bakedTiles_;
  void buildBakedTiles(gpu::Context& ctx);
  // Pass "probes.relight" (defined in relight_pass.cpp): reads "shadow.atlas" when there is one;
  // returns the block it wrote (graph buffer "probes.sh.block"), which the probes' passes read.
  rg::Handle<rg::Buffer> addRelightPass(rg::RenderGraph& graph, const render::PassContext* pc);
  std::unique_ptr<RelightPass> relight_;
  const ref::SceneBvh* relightScene_ = nullptr;
  std::vector<glm::vec3> relightBaked_;  // volume_.sh as baked (volume_.sh gets baked + ΔSH, relight_pass.cpp)
};

}  // namespace bounce::gi::probes
