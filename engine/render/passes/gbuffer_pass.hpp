#pragma once
// G-buffer pass: rasterises every draw of the RenderWorld into albedo, normal, emissive, entity id
// and depth (layout in shaders/common/gbuffer.glsl). Publishes "gbuffer.*" on the blackboard.
#include <cstdint>

#include "engine/gpu/descriptors.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::render {

struct GBuffer {
  rg::Handle<rg::Texture> albedo, normal, emissive, entity, depth;
};

// The normal target's w holds the entity id + 1 as a float up to this value and this value + 1 for
// every larger id (shaders/common/gbuffer.glsl; fp16 holds the integers to 2048 exactly). A reader
// compares it only with ids + 1 ≤ this, else it fetches "gbuffer.entity" (DNRT's self test).
inline constexpr std::uint32_t kEntityInNormalMax = 2047;

const GBuffer& addGBufferPass(rg::RenderGraph& graph, const PassContext* pc, VkExtent2D extent);

// What a deferred GI pass (probes, dnrt, vlm, sl, rtf) reads of the G-buffer: albedo, normal and
// depth, and the entity ids where the pass skips an object's own pixels — the gbuffer pass's
// blackboard names, sampled in the fragment stage. Each shader binds albedo, normal, depth at
// bindings 0, 1, 2 (point-sampled: one texel per pixel); where entity goes is the shader's.
struct DeferredInputs {
  rg::Handle<rg::Texture> albedo, normal, depth, entity;  // entity: invalid unless asked for
};
// `depthUsage`: SampledGraphics where the pass's vertex stage reads depth too (sl's tile cut).
DeferredInputs readDeferredInputs(rg::Builder& b, rg::Blackboard& bb, bool withEntity = false,
                                  rg::Usage depthUsage = rg::Usage::SampledFragment);
// Writes albedo, normal and depth at bindings 0, 1, 2 with the point sampler `point`, the opening of
// every deferred GI pass's descriptor set (the bindings after them are the pass's own).
// `depthLayout`: the depth's layout in the pass (DEPTH_READ_ONLY_OPTIMAL where the pass also tests
// against it as a read-only attachment, rg::Usage::DepthRead).
gpu::DescriptorWriter& writeDeferredInputs(gpu::DescriptorWriter& w, const DeferredInputs& g, const PassContext& pc,
                                           const rg::PassResources& res, VkSampler point,
                                           VkImageLayout depthLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

}  // namespace bounce::render
