#pragma once
// G-buffer pass: rasterises every draw of the RenderWorld into albedo, normal, emissive, entity id
// and depth (layout in shaders/common/gbuffer.glsl). Publishes "gbuffer.*" on the blackboard.
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::render {

struct GBuffer {
  rg::Handle<rg::Texture> albedo, normal, emissive, entity, depth;
};

const GBuffer& addGBufferPass(rg::RenderGraph& graph, const PassContext* pc, VkExtent2D extent);

}  // namespace bounce::render
