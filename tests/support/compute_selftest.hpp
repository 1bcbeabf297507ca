#pragma once
// The GLSL-vs-C++ tests' one way to run a `*_selftest.comp` shader (DESIGN.md: every shared shader
// face is tested against its C++ face). The shaders share one interface: binding 0 = a 16-byte
// header whose first uint is the case count, then the cases (std430); binding 1 = one Output per
// case; local size 64. This uploads the cases, dispatches ceil(count/64) groups, waits and reads
// the outputs back. Tests whose shaders need more bindings (textures, UBOs) build their own set.
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"

namespace bounce::testgpu {

template <class Output, class Case>
std::vector<Output> runComputeSelfTest(gpu::Context& ctx, const std::string& shader, std::span<const Case> cases) {
  constexpr std::size_t kHeader = 16;  // uint count + 3 uints of std430 padding before the first vec4
  const std::uint32_t count = std::uint32_t(cases.size());
  std::vector<std::uint8_t> inBytes(kHeader + cases.size_bytes(), 0);
  std::memcpy(inBytes.data(), &count, sizeof(count));
  if (count) std::memcpy(inBytes.data() + kHeader, cases.data(), cases.size_bytes());

  gpu::Buffer in(ctx, {inBytes.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "selftest.in"});
  gpu::Buffer out(ctx, {std::max<std::size_t>(sizeof(Output) * count, sizeof(Output)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        gpu::MemoryUsage::Readback, "selftest.out"});
  gpu::upload(ctx, in, inBytes);
  gpu::DescriptorSetLayout layout(ctx, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}, {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                                  "selftest");
  gpu::PipelineLayout pipelineLayout(ctx, {layout}, {}, "selftest");
  gpu::ShaderModule module(ctx, shader);
  gpu::Pipeline pipeline = gpu::createComputePipeline(ctx, pipelineLayout, module, shader);
  gpu::DescriptorAllocator descriptors(ctx);
  VkDescriptorSet set = descriptors.allocate(layout);
  gpu::DescriptorWriter().buffer(0, in).buffer(1, out).update(ctx, set);
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    pipeline.bindSet(cmd, 0, set);
    vkCmdDispatch(cmd, (count + 63) / 64, 1, 1);
  });
  const std::vector<std::uint8_t> bytes = gpu::readback(ctx, out);
  std::vector<Output> results(count);
  if (count) std::memcpy(results.data(), bytes.data(), sizeof(Output) * count);
  return results;
}

}  // namespace bounce::testgpu
