// Exact barrier lists for small frames. Strings are describe(Barrier):
// "resource: layout/stages/accesses -> layout/stages/accesses" (buffers have no layout).
#include <gtest/gtest.h>

#include "graph_test_util.hpp"

using namespace bounce::rg;
using namespace bounce::rg::test;
using Names = std::vector<std::string>;

TEST(Barriers, GBufferLightingTonemapPresent) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto& gb = g.addPass<Tex2>(
      "gbuffer",
      [&](Builder& b, Tex2& d) {
        d.a = b.write(b.create<Texture>("gbuffer.normal", color()), Usage::ColorAttachment);
        d.b = b.write(b.create<Texture>("gbuffer.depth", depth()), Usage::DepthAttachment);
      },
      NoOp{});
  auto hdr = colorPass(g, "lighting", {gb.a, gb.b}, "lighting.hdr");
  bb = drawInto(g, "tonemap", {hdr}, bb);
  g.markOutput(bb, Usage::Present);
  g.compile();

  EXPECT_EQ(g.describeBarriers("gbuffer"),
            (Names{"gbuffer.normal: Undefined/None/None -> ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite",
                   "gbuffer.depth: Undefined/None/None -> DepthAttachment/EarlyFragmentTests|LateFragmentTests/"
                   "DepthStencilRead|DepthStencilWrite"}));
  EXPECT_EQ(g.describeBarriers("lighting"),
            (Names{"gbuffer.normal: ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite -> "
                   "ShaderReadOnly/FragmentShader/ShaderSampledRead",
                   "gbuffer.depth: DepthAttachment/EarlyFragmentTests|LateFragmentTests/DepthStencilWrite -> "
                   "ShaderReadOnly/FragmentShader/ShaderSampledRead",
                   "lighting.hdr: Undefined/None/None -> ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite"}));
  // The acquired image has no content (Undefined), so the write does not load it.
  EXPECT_EQ(g.describeBarriers("tonemap"),
            (Names{"lighting.hdr: ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite -> "
                   "ShaderReadOnly/FragmentShader/ShaderSampledRead",
                   "backbuffer: Undefined/ColorAttachmentOutput/None -> "
                   "ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite"}));
  EXPECT_EQ(g.describeBarriers(""),
            Names{"backbuffer: ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite -> Present/None/None"});
  // gbuffer.normal and lighting.hdr have the same description but overlap in "lighting".
  EXPECT_EQ(g.stats().physicalTextures, 3u);
}

TEST(Barriers, ComputeWriteThenFragmentReadThenCapture) {
  RenderGraph g;
  auto capture = g.importTexture("capture", color(Format::RGBA8_UNORM), kIdle, 5);
  auto& probes = g.addPass<Tex>(
      "probes",
      [&](Builder& b, Tex& d) { d.t = b.write(b.create<Texture>("probes.sh", color()), Usage::StorageWrite); },
      NoOp{});
  capture = drawInto(g, "apply", {probes.t}, capture);
  g.markOutput(capture, Usage::TransferSrc);
  g.compile();
  EXPECT_EQ(g.describeBarriers("probes"),
            Names{"probes.sh: Undefined/None/None -> General/ComputeShader/ShaderStorageWrite"});
  EXPECT_EQ(g.describeBarriers("apply"),
            (Names{"probes.sh: General/ComputeShader/ShaderStorageWrite -> ShaderReadOnly/FragmentShader/ShaderSampledRead",
                   "capture: Undefined/None/None -> ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite"}));
  EXPECT_EQ(g.describeBarriers(""),
            Names{"capture: ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite -> TransferSrc/Transfer/TransferRead"});
}

TEST(Barriers, ComputeWrittenBufferReadAsUniformAndIndirect) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto& cull = g.addPass<Buf>(
      "cull", [&](Builder& b, Buf& d) { d.b = b.write(b.create<Buffer>("draws", BufferDesc{256}), Usage::StorageWrite); },
      NoOp{});
  g.addPass<Tex>(
      "draw",
      [&](Builder& b, Tex& d) {
        b.read(cull.b, Usage::IndirectBuffer);
        b.read(cull.b, Usage::UniformBuffer);
        d.t = b.write(bb, Usage::ColorAttachment);
        bb = d.t;
      },
      NoOp{});
  g.markOutput(bb, Usage::Present);
  g.compile();
  // A fresh transient buffer needs no barrier before its first write (no layout, no earlier user).
  EXPECT_TRUE(g.describeBarriers("cull").empty());
  EXPECT_EQ(g.describeBarriers("draw"),
            (Names{"draws: ComputeShader/ShaderStorageWrite -> "
                   "DrawIndirect|VertexShader|FragmentShader|ComputeShader/IndirectCommandRead|UniformRead",
                   "backbuffer: Undefined/ColorAttachmentOutput/None -> "
                   "ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite"}));
}

TEST(Barriers, ReadAfterReadInTheSameLayoutNeedsNoBarrier) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto normal = colorPass(g, "gbuffer", {}, "gbuffer.normal");
  auto ao = colorPass(g, "ao", {normal}, "ao.term", color(Format::R8_UNORM));
  auto hdr = colorPass(g, "lighting", {normal, ao}, "lighting.hdr");
  // The same texture sampled by a compute shader: same layout, but a stage not yet synchronised.
  auto& probe = g.addPass<Tex>(
      "exposure",
      [&](Builder& b, Tex& d) {
        b.read(normal, Usage::SampledCompute);
        b.read(hdr, Usage::SampledCompute);
        d.t = b.write(b.create<Texture>("exposure.value", color(Format::R32F)), Usage::StorageWrite);
      },
      NoOp{});
  bb = drawInto(g, "tonemap", {hdr, probe.t}, bb);
  g.markOutput(bb, Usage::Present);
  g.compile();
  EXPECT_EQ(g.describeBarriers("ao"),
            (Names{"gbuffer.normal: ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite -> "
                   "ShaderReadOnly/FragmentShader/ShaderSampledRead",
                   "ao.term: Undefined/None/None -> ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite"}));
  // gbuffer.normal was already made visible to fragment sampling for "ao": nothing for it here.
  EXPECT_EQ(g.describeBarriers("lighting"),
            (Names{"ao.term: ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite -> "
                   "ShaderReadOnly/FragmentShader/ShaderSampledRead",
                   "lighting.hdr: Undefined/None/None -> ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite"}));
  // A compute read chains through the fragment stage that performed the layout transition.
  EXPECT_EQ(g.describeBarriers("exposure"),
            (Names{"gbuffer.normal: ShaderReadOnly/FragmentShader|ColorAttachmentOutput/ColorAttachmentWrite -> "
                   "ShaderReadOnly/ComputeShader/ShaderSampledRead",
                   "lighting.hdr: ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite -> "
                   "ShaderReadOnly/ComputeShader/ShaderSampledRead",
                   "exposure.value: Undefined/None/None -> General/ComputeShader/ShaderStorageWrite"}));
  // lighting.hdr is now synchronised with compute but not with fragment shading.
  EXPECT_EQ(g.describeBarriers("tonemap"),
            (Names{"lighting.hdr: ShaderReadOnly/ColorAttachmentOutput|ComputeShader/ColorAttachmentWrite -> "
                   "ShaderReadOnly/FragmentShader/ShaderSampledRead",
                   "exposure.value: General/ComputeShader/ShaderStorageWrite -> "
                   "ShaderReadOnly/FragmentShader/ShaderSampledRead",
                   "backbuffer: Undefined/ColorAttachmentOutput/None -> "
                   "ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite"}));
}

TEST(Barriers, WriteAfterReadWaitsForTheReaders) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto normal = colorPass(g, "gbuffer", {}, "gbuffer.normal");
  auto hdr = colorPass(g, "lighting", {normal}, "lighting.hdr");
  // Decals draw over the normals the lighting pass sampled: wait for that sampling, then load.
  normal = g.addPass<Tex>(
                "decals", [&](Builder& b, Tex& d) { d.t = b.write(normal, Usage::ColorAttachment); }, NoOp{})
               .t;
  bb = drawInto(g, "composite", {hdr, normal}, bb);
  g.markOutput(bb, Usage::Present);
  g.compile();
  EXPECT_EQ(g.describeBarriers("decals"),
            Names{"gbuffer.normal: ShaderReadOnly/FragmentShader|ColorAttachmentOutput/ColorAttachmentWrite -> "
                  "ColorAttachment/ColorAttachmentOutput/ColorAttachmentRead|ColorAttachmentWrite"});
  EXPECT_EQ(g.describeBarriers("composite")[1],
            "gbuffer.normal: ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite -> "
            "ShaderReadOnly/FragmentShader/ShaderSampledRead");
}

TEST(Barriers, WriteAfterReadInTheSameLayoutIsAnExecutionBarrier) {
  // A persistent histogram buffer: read by "reduce", then rewritten by "accumulate". The write
  // only has to wait for the read to finish (no memory to make available: source access None).
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto histogram = g.importBuffer("histogram", BufferDesc{1024}, kIdle, 9);
  auto& reduce = g.addPass<Buf>(
      "reduce",
      [&](Builder& b, Buf& d) {
        b.read(histogram, Usage::StorageRead);
        d.b = b.write(b.create<Buffer>("exposure", BufferDesc{16}), Usage::StorageWrite);
      },
      NoOp{});
  auto& accumulate = g.addPass<Buf>(
      "accumulate",
      [&](Builder& b, Buf& d) {
        d.b = b.write(histogram, Usage::StorageWrite);
        b.sideEffect();
      },
      NoOp{});
  g.addPass<Tex>(
      "tonemap",
      [&](Builder& b, Tex& d) {
        b.read(reduce.b, Usage::UniformBuffer);
        d.t = b.write(bb, Usage::ColorAttachment);
        bb = d.t;
      },
      NoOp{});
  g.markOutput(bb, Usage::Present);
  g.compile();
  EXPECT_TRUE(g.describeBarriers("reduce").empty());  // nothing pending on either buffer
  EXPECT_EQ(g.describeBarriers("accumulate"),
            Names{"histogram: ComputeShader/None -> ComputeShader/ShaderStorageWrite"});
  // What the next frame should import the histogram with.
  EXPECT_EQ(g.finalState(accumulate.b), (ResourceState{Layout::Undefined, Stage::ComputeShader, Access::ShaderStorageWrite}));
}

TEST(Barriers, ReadModifyWriteAndDepthTestWhileSampling) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto& gb = g.addPass<Tex>(
      "depth.prepass",
      [&](Builder& b, Tex& d) { d.t = b.write(b.create<Texture>("depth", depth()), Usage::DepthAttachment); },
      NoOp{});
  auto& sim = g.addPass<Tex>(
      "simulate",
      [&](Builder& b, Tex& d) { d.t = b.write(b.create<Texture>("field", color()), Usage::StorageWrite); }, NoOp{});
  auto& step = g.addPass<Tex>(
      "step",
      [&](Builder& b, Tex& d) {
        b.read(sim.t, Usage::StorageRead);
        d.t = b.write(sim.t, Usage::StorageWrite);
      },
      NoOp{});
  g.addPass<Tex>(
      "particles",
      [&](Builder& b, Tex& d) {
        b.read(gb.t, Usage::DepthRead);        // depth test without depth write
        b.read(gb.t, Usage::SampledFragment);  // soft particles sample the same depth
        b.read(step.t, Usage::SampledFragment);
        d.t = b.write(bb, Usage::ColorAttachment);
        bb = d.t;
      },
      NoOp{});
  g.markOutput(bb, Usage::Present);
  g.compile();
  EXPECT_EQ(g.describeBarriers("step"),
            Names{"field: General/ComputeShader/ShaderStorageWrite -> "
                  "General/ComputeShader/ShaderStorageRead|ShaderStorageWrite"});
  EXPECT_EQ(g.describeBarriers("particles")[0],
            "depth: DepthAttachment/EarlyFragmentTests|LateFragmentTests/DepthStencilWrite -> "
            "DepthReadOnly/FragmentShader|EarlyFragmentTests|LateFragmentTests/ShaderSampledRead|DepthStencilRead");
}
