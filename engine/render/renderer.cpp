#include "engine/render/renderer.hpp"

#include <algorithm>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/format.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/passes/lighting_pass.hpp"
#include "engine/render/passes/shadow_pass.hpp"
#include "engine/render/passes/skinning_pass.hpp"
#include "engine/render/passes/subdivision_pass.hpp"
#include "engine/render/passes/tonemap_pass.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::render {

const char* debugViewName(DebugView v) {
  switch (v) {
    case DebugView::None: return "lit";
    case DebugView::Albedo: return "albedo";
    case DebugView::Normal: return "normal";
    case DebugView::Depth: return "depth";
    case DebugView::Shadow: return "shadow";
    case DebugView::EntityId: return "entity-id";
  }
  return "?";
}

namespace {

constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;

// The render-graph state an imported image is in, from its tracked Vulkan layout. The stages and
// writes cover everything that may have touched it since (last frame's passes, the presenter's
// copy), so the first barrier of the frame waits for all of them.
rg::ResourceState importedState(const gpu::Image& image) {
  rg::ResourceState s;
  switch (image.layout()) {
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: s.layout = rg::Layout::ColorAttachment; break;
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: s.layout = rg::Layout::ShaderReadOnly; break;
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: s.layout = rg::Layout::TransferSrc; break;
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: s.layout = rg::Layout::TransferDst; break;
    case VK_IMAGE_LAYOUT_GENERAL: s.layout = rg::Layout::General; break;
    default: s.layout = rg::Layout::Undefined; return s;
  }
  s.stages = rg::Stage::FragmentShader | rg::Stage::ColorAttachmentOutput | rg::Stage::Transfer;
  s.access = rg::Access::ColorAttachmentWrite | rg::Access::TransferWrite;
  return s;
}

template <class T>
void fill(gpu::Context& ctx, gpu::Buffer& buffer, const std::vector<T>& data, VkBufferUsageFlags usage,
          const char* name) {
  // At least one element: a zero-sized binding is invalid, and shaders index only below the count.
  const VkDeviceSize bytes = std::max<VkDeviceSize>(sizeof(T), data.size() * sizeof(T));
  if (!buffer || buffer.size() < bytes)
    buffer = gpu::Buffer(ctx, {std::max<VkDeviceSize>(bytes, buffer ? buffer.size() * 2 : 0), usage,
                               gpu::MemoryUsage::Upload, name});
  if (!data.empty()) std::memcpy(buffer.mapped(), data.data(), data.size() * sizeof(T));
}

}  // namespace

Renderer::Renderer(gpu::Context& ctx, std::uint32_t framesInFlight)
    : ctx_(ctx),
      pipelines_(std::make_unique<Pipelines>(ctx)),
      samplers_(std::make_unique<gpu::SamplerCache>(ctx)),
      frames_(std::make_unique<gpu::FrameRing>(ctx, framesInFlight)),
      backend_(std::make_unique<VkBackend>(ctx, framesInFlight)),
      slots_(framesInFlight) {
  gpu::ImageDesc d;
  d.format = VK_FORMAT_D32_SFLOAT;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  d.name = "shadow.dummy";
  dummyAtlas_ = std::make_unique<gpu::Image>(ctx, d);
  // Depth 1 = "nothing closer": a lookup into the dummy atlas never shadows.
  const float one = 1.0f;
  gpu::upload(ctx, *dummyAtlas_, {reinterpret_cast<const std::uint8_t*>(&one), sizeof one});
}

Renderer::~Renderer() { frames_->waitIdle(); }

void Renderer::ensureTargets(VkExtent2D extent) {
  if (hdr_ && hdr_->desc().width == extent.width && hdr_->desc().height == extent.height) return;
  frames_->waitIdle();
  gpu::ImageDesc d;
  d.width = extent.width;
  d.height = extent.height;
  d.format = render::kLightingHdrFormat;
  d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.name = "lighting.hdr";
  hdr_ = std::make_unique<gpu::Image>(ctx_, d);
  d.format = kDisplayFormat;
  d.name = "display";
  display_ = std::make_unique<gpu::Image>(ctx_, d);
}

void Renderer::writeFrameData(std::uint32_t slot, const RenderWorld& world, PassContext& pc) {
  SlotBuffers& b = slots_[slot];
  fill(ctx_, b.camera, std::vector<CameraGpu>{world.camera}, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "frame.camera");
  fill(ctx_, b.instances, world.instances, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "frame.instances");
  std::vector<LightGpu> lights = world.lights;
  if (!world.has("direct")) lights.clear();  // no direct lighting asked for: emission only
  if (lights.size() > kMaxLights || world.shadowLayers.size() > kMaxShadowLayers)
    throw InternalError("renderer: " + std::to_string(lights.size()) + " lights and " +
                        std::to_string(world.shadowLayers.size()) + " shadow layers (the lighting pass holds at most " +
                        std::to_string(kMaxLights) + " and " + std::to_string(kMaxShadowLayers) + ")");
  const std::uint32_t lightCount = static_cast<std::uint32_t>(lights.size());
  // Padded to the uniform blocks' size (gpu_types.hpp); storage-buffer readers index below the count.
  lights.resize(kMaxLights);
  constexpr VkBufferUsageFlags kBoth = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  fill(ctx_, b.lights, lights, kBoth, "frame.lights");
  std::vector<glm::mat4> matrices(kMaxShadowLayers, glm::mat4(0.0f));
  for (std::size_t i = 0; i < world.shadowLayers.size(); ++i) matrices[i] = world.shadowLayers[i].viewProj;
  fill(ctx_, b.shadowMatrices, matrices, kBoth, "frame.shadow-matrices");
  fill(ctx_, b.posedVertices, world.posedVertices, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
       "frame.posed-vertices");
  fill(ctx_, b.jointMatrices, world.jointMatrices, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "frame.joint-matrices");
  pc.posedVertices = &b.posedVertices;
  pc.jointMatrices = &b.jointMatrices;
  fill(ctx_, b.morphWeights, world.morphWeights, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "frame.morph-weights");
  pc.morphWeights = &b.morphWeights;
  lastSlot_ = slot;
  lastPosedFloats_ = world.posedVertices.size();

  pc.frameSet = frames_->current().descriptors->allocate(pipelines_->frameLayout);
  gpu::DescriptorWriter()
      .buffer(0, b.camera, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      .buffer(1, b.instances)
      .buffer(2, b.shadowMatrices)
      .update(ctx_, pc.frameSet);
  pc.lights = &b.lights;
  pc.lightCount = lightCount;
  pc.shadowMatrices = &b.shadowMatrices;
}

void Renderer::buildGraph(rg::RenderGraph& graph, PassContext& pc, VkExtent2D extent, const FrameSettings& s,
                          rg::PhysicalId hdrId, rg::PhysicalId displayId, rg::PhysicalId posedId) {
  graph.setCullingEnabled(s.culling);
  const rg::TextureDesc hdrDesc{extent.width, extent.height, 1, 1, 1, rg::Format::RGBA16F, false};
  const rg::TextureDesc displayDesc{extent.width, extent.height, 1, 1, 1, rg::Format::RGBA8_UNORM, false};
  auto hdr = graph.importTexture("lighting.hdr", hdrDesc, hdr_ ? importedState(*hdr_) : rg::ResourceState{}, hdrId);
  auto display =
      graph.importTexture("display", displayDesc, display_ ? importedState(*display_) : rg::ResourceState{}, displayId);

  // Skinned instances: one compute pass poses them all before anything draws (DESIGN.md data flow).
  if (!pc.world->skinJobs.empty()) {
    const rg::BufferDesc posedDesc{pc.world->posedVertices.size() * sizeof(float)};
    const auto skinned =
        addSkinningPass(graph, &pc, graph.importBuffer("posed-vertices", posedDesc, rg::ResourceState{}, posedId));
    // Subdivided skinned instances: their limit surfaces from the cages just skinned.
    if (!pc.world->subdivisionJobs.empty()) addSubdivisionPass(graph, &pc, skinned);
  }
  std::optional<rg::Handle<rg::Texture>> atlas;
  // Shadows only modulate direct light: without `direct` there is nothing to shadow.
  if (pc.world->has("shadows") && pc.world->has("direct") && !pc.world->shadowLayers.empty())
    atlas = addShadowPass(graph, &pc, s.shadowResolution).atlas;
  const GBuffer& gbuffer = addGBufferPass(graph, &pc, extent);
  addLightingPass(graph, &pc, gbuffer, atlas, hdr);
  for (const auto& [effect, node] : nodes_)
    if (node && pc.world->has(effect)) node(graph, pc);
  const auto litHdr = graph.blackboard().get<rg::Texture>("lighting.hdr");  // the last node's version
  rg::Handle<rg::Texture> out = s.debugView == DebugView::None
                                    ? addTonemapPass(graph, &pc, litHdr, display)
                                    : addDebugViewPass(graph, &pc, gbuffer, atlas, display);
  graph.markOutput(out, rg::Usage::TransferSrc);
  if (s.keepHdr) graph.markOutput(litHdr, rg::Usage::TransferSrc);
}

void Renderer::setNode(const std::string& effect, GraphNode node) {
  auto it = std::find_if(nodes_.begin(), nodes_.end(), [&](const auto& n) { return n.first == effect; });
  if (it != nodes_.end()) {
    if (node) it->second = std::move(node);
    else nodes_.erase(it);
  } else if (node) {
    nodes_.emplace_back(effect, std::move(node));
  }
}

void Renderer::render(const RenderWorld& world, gpu::Presenter& presenter, const FrameSettings& settings) {
  const VkExtent2D extent = presenter.extent();
  ensureTargets(extent);
  gpu::Frame& frame = frames_->begin();
  // An error while recording (a technique's update, a pass, the presenter) must leave the ring
  // usable: the session's destructor waits for it, and a second throw there would terminate. The
  // graph's barriers already moved the tracked layouts of the images they name; put them back to
  // what the GPU holds so that the next frame renders (tests/unit/render/frame_unwind_test.cpp).
  try {
    backend_->beginFrame(frame.slot, frame.timestamps.get());

    PassContext pc;
    pc.gpu = &ctx_;
    pc.backend = backend_.get();
    pc.frames = frames_.get();
    pc.samplers = samplers_.get();
    pc.pipelines = pipelines_.get();
    pc.world = &world;
    pc.dummyShadowAtlas = dummyAtlas_.get();
    pc.debugView = static_cast<int>(settings.debugView);
    pc.exposure = settings.exposure;
    writeFrameData(frame.slot, world, pc);

    rg::RenderGraph graph;
    buildGraph(graph, pc, extent, settings, backend_->importImage(*hdr_), backend_->importImage(*display_),
               backend_->importBuffer(slots_[frame.slot].posedVertices));
    executed_ = graph.compile().executedPasses;
    VkCommandContext cc;
    cc.cmd = frame.cmd;
    cc.backend = backend_.get();
    graph.execute(*backend_, cc);
    presenter.present(*frames_, *display_);
  } catch (...) {
    // Only an unsubmitted frame's barriers are undone: a presenter that throws after
    // FrameRing::submit (a present error, the capture's waitIdle) leaves them to the GPU, which
    // runs them, so the tracked layouts are already true.
    if (frames_->current().recording) backend_->abandonFrame();
    frames_->abandon();
    throw;
  }
}

std::string Renderer::graphDot(const RenderWorld& world, VkExtent2D extent, const FrameSettings& settings) {
  PassContext pc;
  pc.world = &world;
  rg::RenderGraph graph;
  buildGraph(graph, pc, extent, settings, 1, 2, 3);
  return graph.toDot();
}

std::vector<float> Renderer::readPosedVertices() {
  frames_->waitIdle();
  std::vector<float> out(lastPosedFloats_);
  if (!out.empty()) std::memcpy(out.data(), slots_[lastSlot_].posedVertices.mapped(), out.size() * sizeof(float));
  return out;
}

std::vector<float> Renderer::readHdr() {
  frames_->waitIdle();
  auto bytes = gpu::readback(ctx_, *hdr_);
  const std::size_t pixels = std::size_t(hdr_->desc().width) * hdr_->desc().height;
  if (bytes.size() != pixels * 8) throw InternalError("render: HDR readback size mismatch");
  std::vector<float> rgb(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < 3; ++c) {
      std::uint16_t h;
      std::memcpy(&h, &bytes[i * 8 + c * 2], 2);
      rgb[i * 3 + c] = gpu::halfToFloat(h);
    }
  return rgb;
}

}  // namespace bounce::render
