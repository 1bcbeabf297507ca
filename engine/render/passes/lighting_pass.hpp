#pragma once
// Deferred direct lighting (shaders/passes/lighting.frag): Lambertian reflection of every
// punctual light with its shadow term, plus emission, into the HDR radiance target. Publishes
// "lighting.hdr" — the buffer later GI nodes add their indirect terms to.
#include <optional>

#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"

namespace bounce::render {

struct Lighting {
  rg::Handle<rg::Texture> hdr;
};

const Lighting& addLightingPass(rg::RenderGraph& graph, const PassContext* pc, const GBuffer& gbuffer,
                                std::optional<rg::Handle<rg::Texture>> shadowAtlas, rg::Handle<rg::Texture> hdr);

// Binds what the lighting and debug-view shaders share in set 1: G-buffer textures, the shadow
// atlas (or the 1×1 dummy), shadow matrices and lights.
VkDescriptorSet writeGBufferSet(const PassContext* pc, const rg::PassResources& res, const gpu::DescriptorSetLayout& layout,
                                const GBuffer& gbuffer, std::optional<rg::Handle<rg::Texture>> shadowAtlas,
                                bool entityInsteadOfEmissive);

}  // namespace bounce::render
