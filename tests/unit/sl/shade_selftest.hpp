#pragma once
// The SL GPU tests' one way to run a `sl/*_selftest.comp` that reads pass 2's shading data: ShadeData
// at bindings 0–2 (spheres, intensity UBO, nearest sampler), the cases at binding 3 (a 16-byte header
// whose first uint is the count, then the cases, std430; with `countInPush` no header, the count in a
// uvec4 push constant's x, as sl/relight_bounce.comp reads relight's surfel buffer), one 16-byte
// Output per case at binding 4, local size 64. tests/support/compute_selftest.hpp is the same for shaders without ShadeData;
// the hierarchy tests (two dispatches, more bindings) build their own set.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"

namespace bounce::gi::sl::sltest {

template <class Output, class Case>
std::vector<Output> runShadeSelfTest(gpu::Context& ctx, const ShadeData& data, const gpu::Buffer& intensity,
                                     const std::string& shader, const gpu::SpecConstants& spec, std::span<const Case> cases,
                                     bool countInPush = false) {
  static_assert(sizeof(Output) == 16, "one vec4 / uvec4 per case");
  const std::uint32_t count = std::uint32_t(cases.size());
  const std::size_t header = countInPush ? 0 : 16;
  std::vector<std::uint8_t> in(std::max<std::size_t>(header + cases.size_bytes(), 16), 0);
  if (!countInPush) std::memcpy(in.data(), &count, 4);
  if (count) std::memcpy(in.data() + header, cases.data(), cases.size_bytes());
  gpu::Buffer inBuf(ctx, {in.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.test.cases"});
  std::memcpy(inBuf.mapped(), in.data(), in.size());
  gpu::Buffer outBuf(ctx, {std::max<std::size_t>(count, 1) * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           gpu::MemoryUsage::Readback, "sl.test.out"});
  std::vector<gpu::Binding> b = ShadeData::bindings(0);
  b.push_back({3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  b.push_back({4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  gpu::DescriptorSetLayout layout(ctx, b, "sl.test");
  gpu::PipelineLayout pipelineLayout(ctx, {layout}, {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, 16}}, "sl.test");
  gpu::Pipeline pipeline =
      gpu::createComputePipeline(ctx, pipelineLayout, gpu::ShaderModule(ctx, shader), shader, nullptr, spec);
  gpu::SamplerCache samplers(ctx);
  gpu::SamplerDesc nearest;
  nearest.filter = VK_FILTER_NEAREST;
  nearest.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  gpu::DescriptorAllocator descriptors(ctx);
  VkDescriptorSet set = descriptors.allocate(layout);
  gpu::DescriptorWriter w;
  data.write(w, 0, intensity, samplers.get(nearest));
  w.buffer(3, inBuf).buffer(4, outBuf).update(ctx, set);
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    pipeline.bindSet(cmd, 0, set);
    if (countInPush) pipeline.push(cmd, std::array<std::uint32_t, 4>{count, 0u, 0u, 0u});
    vkCmdDispatch(cmd, (count + 63) / 64, 1, 1);
  });
  const auto bytes = gpu::readback(ctx, outBuf);
  std::vector<Output> out(count);
  if (count) std::memcpy(out.data(), bytes.data(), count * sizeof(Output));
  return out;
}

}  // namespace bounce::gi::sl::sltest
