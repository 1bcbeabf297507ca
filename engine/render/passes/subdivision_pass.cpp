#include "engine/render/passes/subdivision_pass.hpp"

#include "engine/render/mesh_gpu.hpp"

namespace bounce::render {

namespace {

struct SubdivisionData {
  rg::Handle<rg::Buffer> posed;
};

}  // namespace

rg::Handle<rg::Buffer> addSubdivisionPass(rg::RenderGraph& graph, const PassContext* pc, rg::Handle<rg::Buffer> posed) {
  const auto& out = graph.addPass<SubdivisionData>(
      "subdivision",
      [&](rg::Builder& b, SubdivisionData& d) {
        b.read(posed, rg::Usage::StorageRead);  // the skinned cages
        d.posed = b.write(posed, rg::Usage::StorageWrite);  // the refined vertices (other ranges)
      },
      [pc](const SubdivisionData& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        const auto& p = pc->pipelines->subdivision;
        gpu::Buffer& buffer = pc->backend->buffer(res.buffer(d.posed));
        p.bind(cmd);
        for (const SubdivisionJob& job : pc->world->subdivisionJobs) {
          VkDescriptorSet set = pc->frame().descriptors->allocate(pc->pipelines->subdivisionLayout);
          gpu::DescriptorWriter().buffer(0, buffer).buffer(1, job.mesh->stencilRows).buffer(2, job.mesh->stencilWeights).update(*pc->gpu, set);
          p.bindSet(cmd, 0, set);
          const struct {
            std::uint32_t vertexCount, srcBase, dstBase;
          } push{job.vertexCount, job.srcBase, job.dstBase};
          p.push(cmd, push);
          vkCmdDispatch(cmd, (job.vertexCount + kSubdivisionGroupSize - 1) / kSubdivisionGroupSize, 1, 1);
        }
      });
  graph.blackboard().put("skinning.vertices", out.posed);
  return out.posed;
}

}  // namespace bounce::render
