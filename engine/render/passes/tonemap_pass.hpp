#pragma once
// The end of the frame: tonemap (HDR → sRGB display image) or, when a debug view is selected,
// the debug-view pass writing the display image instead (the lighting chain is then culled).
#include <optional>

#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"

namespace bounce::render {

rg::Handle<rg::Texture> addTonemapPass(rg::RenderGraph& graph, const PassContext* pc, rg::Handle<rg::Texture> hdr,
                                       rg::Handle<rg::Texture> display);

rg::Handle<rg::Texture> addDebugViewPass(rg::RenderGraph& graph, const PassContext* pc, const GBuffer& gbuffer,
                                         std::optional<rg::Handle<rg::Texture>> shadowAtlas,
                                         rg::Handle<rg::Texture> display);

}  // namespace bounce::render
