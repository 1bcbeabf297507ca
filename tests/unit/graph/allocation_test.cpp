// Transient allocation: lifetimes over the executed order, slots shared by non-overlapping
// transients with identical descriptions.
#include <gtest/gtest.h>

#include "graph_test_util.hpp"

using namespace bounce::rg;
using namespace bounce::rg::test;
using Names = std::vector<std::string>;

namespace {

// Execute on a recording backend and return its create events.
Names creations(RenderGraph& g, RecordingBackend& backend) {
  CommandContext ctx;
  g.execute(backend, ctx);
  Names out;
  for (auto& e : backend.events)
    if (e.rfind("create", 0) == 0) out.push_back(e);
  return out;
}

}  // namespace

TEST(Allocation, NonOverlappingSameDescriptionShareASlot) {
  // Ping-pong blur: x lives in passes [0,1], y in [1,2], z in [2,3]; x and z never meet.
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto x = colorPass(g, "a", {}, "x");
  auto y = colorPass(g, "b", {x}, "y");
  auto z = colorPass(g, "c", {y}, "z");
  bb = drawInto(g, "d", {z}, bb);
  g.markOutput(bb, Usage::Present);
  const GraphStats& s = g.compile();
  EXPECT_EQ(s.transientTextures, 3u);
  EXPECT_EQ(s.physicalTextures, 2u);
  // z's first use waits for x's last users of the shared memory, then discards the content.
  EXPECT_EQ(g.describeBarriers("c")[1],
            "z: Undefined/FragmentShader|ColorAttachmentOutput/ColorAttachmentWrite -> "
            "ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite");
  RecordingBackend backend;
  EXPECT_EQ(creations(g, backend), (Names{"create texture 1 x|z 64x64 RGBA16F", "create texture 2 y 64x64 RGBA16F"}));
  // The slot is created with every usage of both occupants.
  UsageSet expected;
  expected.add(Usage::ColorAttachment);
  expected.add(Usage::SampledFragment);
  EXPECT_EQ(backend.createdUsages[0], expected);
}

TEST(Allocation, OverlappingLifetimesDoNotShare) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto& ab = g.addPass<Tex2>(
      "gbuffer",
      [&](Builder& b, Tex2& d) {
        d.a = b.write(b.create<Texture>("gbuffer.albedo", color()), Usage::ColorAttachment);
        d.b = b.write(b.create<Texture>("gbuffer.normal", color()), Usage::ColorAttachment);
      },
      NoOp{});
  bb = drawInto(g, "lighting", {ab.a, ab.b}, bb);
  g.markOutput(bb, Usage::Present);
  EXPECT_EQ(g.compile().physicalTextures, 2u);
}

TEST(Allocation, DifferentDescriptionsDoNotShare) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto x = colorPass(g, "a", {}, "x", color(Format::RGBA16F));
  auto y = colorPass(g, "b", {x}, "y", color(Format::RGBA16F));
  auto z = colorPass(g, "c", {y}, "z", color(Format::RGBA8_UNORM));  // same size, other format
  auto w = colorPass(g, "d", {z}, "w", TextureDesc{32, 32, 1, 1, 1, Format::RGBA16F, false});  // other size
  bb = drawInto(g, "e", {w}, bb);
  g.markOutput(bb, Usage::Present);
  const GraphStats& s = g.compile();
  EXPECT_EQ(s.transientTextures, 4u);
  EXPECT_EQ(s.physicalTextures, 4u);
}

TEST(Allocation, BuffersAliasAndCulledTransientsAreNotAllocated) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto producer = [&](const char* pass, const char* name, std::vector<Handle<Buffer>> inputs) {
    return g.addPass<Buf>(
                pass,
                [&](Builder& b, Buf& d) {
                  for (auto in : inputs) b.read(in, Usage::StorageRead);
                  d.b = b.write(b.create<Buffer>(name, BufferDesc{4096}), Usage::StorageWrite);
                },
                NoOp{})
        .b;
  };
  auto p = producer("p", "bp", {});
  auto q = producer("q", "bq", {p});
  auto r = producer("r", "br", {q});
  producer("unused", "bu", {});
  g.addPass<Tex>(
      "draw",
      [&](Builder& b, Tex& d) {
        b.read(r, Usage::UniformBuffer);
        d.t = b.write(bb, Usage::ColorAttachment);
        bb = d.t;
      },
      NoOp{});
  g.markOutput(bb, Usage::Present);
  const GraphStats& s = g.compile();
  EXPECT_EQ(s.culledPasses, Names{"unused"});
  EXPECT_EQ(s.transientBuffers, 3u);
  EXPECT_EQ(s.physicalBuffers, 2u);
  EXPECT_EQ(s.physicalTextures, 0u);  // the backbuffer is imported
  RecordingBackend backend;
  EXPECT_EQ(creations(g, backend), (Names{"create buffer 1 bp|br 4096 bytes", "create buffer 2 bq 4096 bytes"}));
  // br reuses bp's memory: its first write waits for q's reads of bp (write-after-read).
  EXPECT_EQ(g.describeBarriers("r"),
            (Names{"bq: ComputeShader/ShaderStorageWrite -> ComputeShader/ShaderStorageRead",
                   "br: ComputeShader/ShaderStorageWrite -> ComputeShader/ShaderStorageWrite"}));
}
