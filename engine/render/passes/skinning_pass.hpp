#pragma once
// Skinning pass (compute, shaders/skinning/skinning.comp): once per frame, every skinned instance
// of the RenderWorld (its SkinJobs) is skinned into the frame's posed-vertex buffer, which the
// shadow and G-buffer passes then read as their vertex buffer (so the debug views and entity ids,
// made from the G-buffer, see the same pose). Added only when the world has a skinned instance;
// culled by the graph when no pass draws. Publishes "skinning.vertices".
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::render {

// `posed` is the imported posed-vertex buffer (RenderWorld::posedVertices, uploaded this frame).
// Returns its version after the pass, also put on the blackboard as "skinning.vertices".
rg::Handle<rg::Buffer> addSkinningPass(rg::RenderGraph& graph, const PassContext* pc, rg::Handle<rg::Buffer> posed);

// What a raster pass's setup calls: declares the vertex-buffer read of "skinning.vertices" when
// the skinning pass ran this frame (so the graph orders it and places the barrier).
// `needed` false (the pass draws no posed geometry this frame): nothing is declared, so without
// another reader the graph culls the skinning (and subdivision) pass.
void readSkinnedVertices(rg::RenderGraph& graph, rg::Builder& b, bool needed = true);

}  // namespace bounce::render
