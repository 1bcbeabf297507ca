#pragma once
// shaders/test/fill.comp, shared by the compute and pipeline-table tests: out[i] = a·i² + b for
// i < count (64 invocations a workgroup, bounds-checked), its push block and a dispatch that reads the
// buffer back.
#include <cstdint>
#include <cstring>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/pipeline.hpp"

namespace bounce::gpu::testkit {

struct FillPush {
  std::uint32_t count;
  float a, b;
};
inline const VkPushConstantRange kFillPush{VK_SHADER_STAGE_ALL, 0, sizeof(FillPush)};

// Runs `pipeline` (fill.comp) over `count` elements with `set` bound at 0 (it holds `out`) and
// returns all of `out`, as floats. The barrier orders an earlier upload into `out` before the writes.
inline std::vector<float> dispatchFill(Context& ctx, const Pipeline& pipeline, VkDescriptorSet set, const Buffer& out,
                                       FillPush push) {
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    fullBarrier(cmd);
    pipeline.bind(cmd);
    pipeline.bindSet(cmd, 0, set);
    pipeline.push(cmd, push);
    vkCmdDispatch(cmd, (push.count + 63) / 64, 1, 1);
  });
  const auto bytes = readback(ctx, out);
  std::vector<float> v(bytes.size() / sizeof(float));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
  return v;
}

}  // namespace bounce::gpu::testkit
