#pragma once
// PipelineTable: the pipelines a Context has built, kept for the Context's life and handed again to
// an identical request. Every createComputePipeline / createGraphicsPipeline goes through it.
//
// Why: a Session builds every pipeline of its renderer and techniques, and `bounce accuracy` builds
// two Sessions per row on one Context — 1 696 pipelines, 122 distinct, most of the run's time
// inside lavapipe's vkCreate*Pipelines (README "CI time, session 17"; its VkPipelineCache does not
// reuse anything across pipelines). Keyed here, each distinct pipeline is built once per Context.
//
// The key is the full creation input: the SPIR-V of each stage (ShaderModule::spirvHash), the
// specialisation constants, every fixed-function field of GraphicsPipelineDesc (vertex input,
// topology, rasterisation, depth, blend, attachment formats) and the pipeline layout by CONTENT —
// each set layout's bindings (binding, type, count, stages) and the push-constant ranges — not by
// handle. Debug names and the VkPipelineCache are not in it (they do not change the pipeline).
//
// Lifetimes (no use-after-destroy under validation): a held pipeline is created with the table's
// own copy of its layout (set layouts + pipeline layout built from the content), so it never
// depends on the requester's layout objects, which a Session destroys with itself. The requester
// binds sets and pushes constants through its own layout, which Vulkan calls compatible (identically
// defined set layouts and push ranges; the validation layer compares them by definition). At Context
// teardown, after vkDeviceWaitIdle, the table destroys its pipelines, then its pipeline layouts,
// then its set layouts, then the device goes. A Pipeline object handed out from the table only
// forgets its handle on reset(); like every gpu object it must not outlive its Context.
//
// Memory: the table holds each distinct pipeline once — for one Session the same pipelines it
// would hold anyway; across Sessions the union of their variants (122 in the accuracy run), freed
// with the Context. That bound (the technique variants the program can make) is why reuse is on by
// default rather than switched on by `bounce accuracy` / `bench` alone: every test and the game's
// effect toggles then run the same code path that CI times. Off (ContextOptions::reusePipelines or
// BOUNCE_PIPELINE_REUSE=0) every request builds and owns its pipeline, as before.
//
// Threads: lookups and inserts are under one mutex; the driver builds outside it, so two threads
// building different pipelines do not wait on each other. Two threads racing for the same key may
// both build it: the loser destroys its own (never handed out) and returns the winner's.
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>

#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;

class PipelineTable {
 public:
  PipelineTable(Context& ctx, bool reuse);
  ~PipelineTable();  // the Context destroys it after vkDeviceWaitIdle, before the device
  PipelineTable(const PipelineTable&) = delete;
  PipelineTable& operator=(const PipelineTable&) = delete;

  bool reuses() const { return reuse_; }

  struct Counts {
    std::uint64_t built = 0;   // pipelines the driver built through this table (reuse on or off)
    std::uint64_t reused = 0;  // requests answered with a held pipeline
    std::size_t held = 0;      // distinct pipelines held now (0 with reuse off)
  };
  Counts counts() const;

  // Builds a pipeline with the given layout handle (the table's own copy of `layout` when reuse is
  // on, `layout.handle()` when off); called at most once per obtain().
  using Build = std::function<VkPipeline(VkPipelineLayout)>;
  // The pipeline for `key` — the creation input apart from the layout (pipeline.cpp writes it) —
  // with `layout`'s content appended to it. Names a newly built pipeline `name`.
  Pipeline obtain(const std::string& key, const PipelineLayout& layout, VkPipelineBindPoint bindPoint,
                  const std::string& name, const Build& build);

  // The layout's content as key bytes: per set its bindings, then the push ranges.
  static std::string layoutKey(const PipelineLayout& layout);

 private:
  struct OwnedLayout {
    std::vector<VkDescriptorSetLayout> sets;
    VkPipelineLayout layout = VK_NULL_HANDLE;
  };
  // The table's own layout with `layout`'s content (built on first use). Caller holds mutex_.
  VkPipelineLayout ownLayout(const std::string& key, const PipelineLayout& layout);

  Context& ctx_;
  const bool reuse_;
  mutable std::mutex mutex_;
  std::map<std::string, VkPipeline> pipelines_;  // full key → pipeline
  std::map<std::string, OwnedLayout> layouts_;   // layoutKey → the table's copy
  std::uint64_t built_ = 0, reused_ = 0;
};

}  // namespace bounce::gpu
