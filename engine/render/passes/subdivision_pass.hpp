#pragma once
// Subdivision pass (compute, shaders/subdivision/subdivision.comp): once per frame, after the
// skinning pass, every subdivided skinned instance of the RenderWorld (its SubdivisionJobs) has
// its limit stencils evaluated on the cage the skinning pass just posed, into the same
// posed-vertex buffer, which the shadow and G-buffer passes then draw from (the refined mesh's
// index buffer). Added only when the world has such an instance; culled with the skinning pass
// when no pass draws. Reads and republishes "skinning.vertices" (so later passes read the refined
// version and the graph orders skinning → subdivision → draws).
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::render {

// `posed` is the skinning pass's output. Returns the buffer's version after this pass.
rg::Handle<rg::Buffer> addSubdivisionPass(rg::RenderGraph& graph, const PassContext* pc, rg::Handle<rg::Buffer> posed);

}  // namespace bounce::render
