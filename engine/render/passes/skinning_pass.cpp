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
          // Without targets binding 3 is never read; the skin vertices stand in for a valid binding.
          const gpu::Buffer& morph = job.mesh->morphTargets ? job.mesh->morphDeltas : job.mesh->skinVertices;
          gpu::DescriptorWriter()
              .buffer(0, job.mesh->skinVertices)
              .buffer(1, *pc->jointMatrices)
              .buffer(2, dst)
              .buffer(3, morph)
              .buffer(4, *pc->morphWeights)
              .update(*pc->gpu, set);
          p.bindSet(cmd, 0, set);
          const struct {
            std::uint32_t vertexCount, jointBase, dstBase, weightBase, targetCount, skinned;
          } push{job.vertexCount, job.jointBase, job.dstBase, job.weightBase, job.mesh->morphTargets, job.skinned ? 1u : 0u};
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
