#pragma once
// Shadow pass: renders every shadow-casting light's view(s) into one layer each of a depth
// atlas (a 2D array; point lights own six layers, one per cube face). Added only when the level
// names `shadows` and at least one light casts shadows. Publishes "shadow.atlas".
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::render {

// Slope-scaled rasteriser bias against shadow acne (units: Vulkan depth-bias units and the
// per-texel depth slope); the receiver-side normal offset in shadow.glsl does the rest.
inline constexpr float kShadowDepthBiasConstant = 1.25f;
inline constexpr float kShadowDepthBiasSlope = 1.75f;

struct ShadowAtlas {
  rg::Handle<rg::Texture> atlas;
};

const ShadowAtlas& addShadowPass(rg::RenderGraph& graph, const PassContext* pc, std::uint32_t resolution);

}  // namespace bounce::render
