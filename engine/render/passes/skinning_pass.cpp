#include "engine/render/passes/skinning_pass.hpp"

#include "engine/render/mesh_gpu.hpp"

namespace bounce::render {

namespace {

struct SkinningData {
  rg::Handle<rg::Buffer> posed;
};

}  // namespace

rg::Handle<rg::Buffer> addSkinningPass(rg::RenderGraph& graph, const PassContext* pc, rg::Handle<rg::Buffer> posed) {
  const auto& out = graph.addPass<SkinningData>(
      "skinning",
      [&](rg::Builder& b, SkinningData& d) { d.posed = b.write(posed, rg::Usage::StorageWrite); },
      [pc](const SkinningData& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        const auto& p = pc->pipelines->skinning;
        gpu::Buffer& dst = pc->backend->buffer(res.buffer(d.posed));
        p.bind(cmd);
        for (const SkinJob& job : pc->world->skinJobs) {
          VkDescriptorSet set = pc->frame().descriptors->allocate(pc->pipelines->skinningLayout);
          gpu::DescriptorWriter().buffer(0, job.mesh->skinVertices).buffer(1, *pc->jointMatrices).buffer(2, dst).update(*pc->gpu, set);
          p.bindSet(cmd, 0, set);
          const struct {
            std::uint32_t vertexCount, jointBase, dstBase;
          } push{job.vertexCount, job.jointBase, job.dstBase};
          p.push(cmd, push);
          vkCmdDispatch(cmd, (job.vertexCount + kSkinningGroupSize - 1) / kSkinningGroupSize, 1, 1);
        }
      });
  graph.blackboard().put("skinning.vertices", out.posed);
  return out.posed;
}

void readSkinnedVertices(rg::RenderGraph& graph, rg::Builder& b, bool needed) {
  if (!needed) return;
  if (auto h = graph.blackboard().find<rg::Buffer>("skinning.vertices")) b.read(*h, rg::Usage::VertexBuffer);
}

}  // namespace bounce::render
