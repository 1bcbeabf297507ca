// Mistakes in setup, execute and blackboard use: each throws InternalError whose message names
// what the user needs to find the mistake, and a failed setup leaves the graph as it was.
#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "graph_test_util.hpp"

using namespace bounce;
using namespace bounce::rg;
using namespace bounce::rg::test;

namespace {

// The message of the InternalError `f` throws ("" when it throws nothing).
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const InternalError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Errors, ReadingAStaleVersionNamesPassResourceAndNewerWriter) {
  RenderGraph g;
  auto v1 = colorPass(g, "gbuffer", {}, "gbuffer.normal");
  auto v2 = g.addPass<Tex>(
                 "decals", [&](Builder& b, Tex& d) { d.t = b.write(v1, Usage::ColorAttachment); }, NoOp{})
                .t;
  EXPECT_EQ(v2.version, 2u);
  std::string msg = errorOf([&] { colorPass(g, "lighting", {v1}, "lighting.hdr"); });
  EXPECT_TRUE(mentions(msg, {"'lighting'", "reads 'gbuffer.normal' version 1", "'decals'", "version 2"})) << msg;
  // The failed pass and the resource it created are gone; the current handle still works.
  EXPECT_EQ(g.passCount(), 2u);
  EXPECT_EQ(g.resourceCount(), 1u);
  colorPass(g, "lighting", {v2}, "lighting.hdr");
  EXPECT_EQ(g.passCount(), 3u);
}

TEST(Errors, WritingAStaleVersion) {
  RenderGraph g;
  auto v1 = colorPass(g, "opaque", {}, "hdr");
  g.addPass<Tex>("transparent", [&](Builder& b, Tex& d) { d.t = b.write(v1, Usage::ColorAttachment); }, NoOp{});
  std::string msg = errorOf([&] {
    g.addPass<Tex>("ui", [&](Builder& b, Tex& d) { d.t = b.write(v1, Usage::ColorAttachment); }, NoOp{});
  });
  EXPECT_TRUE(mentions(msg, {"'ui'", "writes 'hdr' version 1", "'transparent'"})) << msg;
}

TEST(Errors, ReadingATransientNothingWrote) {
  RenderGraph g;
  std::string msg = errorOf([&] {
    g.addPass<Tex>(
        "lighting", [&](Builder& b, Tex& d) { d.t = b.read(b.create<Texture>("hdr", color()), Usage::SampledFragment); },
        NoOp{});
  });
  EXPECT_TRUE(mentions(msg, {"'lighting'", "'hdr'", "before any pass wrote it"})) << msg;
  EXPECT_EQ(g.resourceCount(), 0u);
}

TEST(Errors, ResolvingAnUndeclaredResourceNamesPassAndResource) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto normal = colorPass(g, "gbuffer", {}, "gbuffer.normal");
  auto hdr = colorPass(g, "lighting", {normal}, "lighting.hdr");
  auto& out = g.addPass<Tex>(
      "tonemap",
      [&](Builder& b, Tex& d) {
        b.read(hdr, Usage::SampledFragment);
        d.t = b.write(bb, Usage::ColorAttachment);
      },
      [normal](const Tex&, const PassResources& r, CommandContext&) { r.texture(normal); });
  g.markOutput(out.t, Usage::Present);
  RecordingBackend backend;
  CommandContext ctx;
  std::string msg = errorOf([&] { g.execute(backend, ctx); });
  EXPECT_TRUE(mentions(msg, {"'tonemap'", "'gbuffer.normal'", "did not declare"})) << msg;
  EXPECT_EQ(backend.live, 0);  // the transients created for the frame were destroyed
}

TEST(Errors, BlackboardMissingKeyAndWrongKind) {
  RenderGraph g;
  auto hdr = colorPass(g, "lighting", {}, "lighting.hdr");
  g.blackboard().put("lighting.hdr", hdr);
  EXPECT_EQ(g.blackboard().get<Texture>("lighting.hdr"), hdr);
  EXPECT_FALSE(g.blackboard().find<Texture>("ao.term").has_value());
  std::string msg = errorOf([&] { g.blackboard().get<Texture>("gbuffer.normal"); });
  EXPECT_TRUE(mentions(msg, {"no entry 'gbuffer.normal'", "lighting.hdr"})) << msg;
  msg = errorOf([&] { g.blackboard().get<Buffer>("lighting.hdr"); });
  EXPECT_TRUE(mentions(msg, {"'lighting.hdr' is a texture", "asked for a buffer"})) << msg;
}

TEST(Errors, FailedSetupRestoresTheBlackboardAndVersions) {
  RenderGraph g;
  auto hdr = colorPass(g, "opaque", {}, "hdr");
  g.blackboard().put("hdr", hdr);
  std::string msg = errorOf([&] {
    g.addPass<Tex>(
        "broken",
        [&](Builder& b, Tex& d) {
          d.t = b.write(hdr, Usage::ColorAttachment);
          g.blackboard().put("hdr", d.t);
          b.read(d.t, Usage::VertexBuffer);  // a buffer usage on a texture
        },
        NoOp{});
  });
  EXPECT_TRUE(mentions(msg, {"'broken'", "VertexBuffer", "'hdr'", "texture"})) << msg;
  EXPECT_EQ(g.blackboard().get<Texture>("hdr"), hdr);
  // Version 1 is current again, so writing it is not stale.
  auto v2 = g.addPass<Tex>("ui", [&](Builder& b, Tex& d) { d.t = b.write(hdr, Usage::ColorAttachment); }, NoOp{}).t;
  EXPECT_EQ(v2.version, 2u);
}

TEST(Errors, UsageMustFitTheDeclarationAndTheResource) {
  RenderGraph g;
  auto hdr = colorPass(g, "opaque", {}, "hdr");
  auto pass = [&](const char* name, auto&& setup) {
    return errorOf([&] { g.addPass<Tex>(name, setup, NoOp{}); });
  };
  EXPECT_TRUE(mentions(pass("a", [&](Builder& b, Tex&) { b.read(hdr, Usage::ColorAttachment); }),
                       {"'a'", "write usage ColorAttachment to read()", "'hdr'"}));
  EXPECT_TRUE(mentions(pass("b", [&](Builder& b, Tex& d) { d.t = b.write(hdr, Usage::SampledFragment); }),
                       {"'b'", "read usage SampledFragment to write()"}));
  EXPECT_TRUE(mentions(pass("c",
                            [&](Builder& b, Tex& d) {
                              d.t = b.write(b.create<Texture>("z", depth()), Usage::ColorAttachment);
                            }),
                       {"'c'", "ColorAttachment", "'z'", "D32F"}));
  EXPECT_TRUE(mentions(pass("d", [&](Builder& b, Tex& d) { d.t = b.write(hdr, Usage::DepthAttachment); }),
                       {"'d'", "DepthAttachment", "RGBA16F"}));
  EXPECT_TRUE(mentions(pass("e", [&](Builder& b, Tex&) { b.read(hdr, Usage::Present); }), {"'e'", "markOutput"}));
  // Sampling and rendering to the same image in one pass is a feedback loop: no layout fits.
  EXPECT_TRUE(mentions(pass("f",
                            [&](Builder& b, Tex& d) {
                              b.read(hdr, Usage::SampledFragment);
                              d.t = b.write(hdr, Usage::ColorAttachment);
                            }),
                       {"'f'", "'hdr'", "different layouts", "ShaderReadOnly", "ColorAttachment"}));
  EXPECT_EQ(g.passCount(), 1u);
}

TEST(Errors, BadDescriptionsNamesAndOutputs) {
  RenderGraph g;
  EXPECT_TRUE(mentions(errorOf([&] { g.importTexture("env", TextureDesc{64, 32, 1, 6, 1, Format::RGBA16F, true}, kIdle, 1); }),
                       {"'env'", "cube"}));
  EXPECT_TRUE(mentions(errorOf([&] { g.importTexture("grid", TextureDesc{0, 8, 8, 1, 1, Format::R32F, false}, kIdle, 1); }),
                       {"'grid'", "at least 1"}));
  EXPECT_TRUE(mentions(errorOf([&] { g.importTexture("big", TextureDesc{64, 64, 1, 1, 8, Format::R32F, false}, kIdle, 1); }),
                       {"'big'", "mips", "(7)"}));
  EXPECT_TRUE(mentions(errorOf([&] { g.importBuffer("empty", BufferDesc{0}, kIdle, 1); }), {"'empty'", "size 0"}));
  EXPECT_TRUE(mentions(errorOf([&] { g.importBuffer("", BufferDesc{4}, kIdle, 1); }), {"needs a name"}));
  EXPECT_EQ(g.resourceCount(), 0u);
  auto hdr = colorPass(g, "opaque", {}, "hdr");
  EXPECT_TRUE(mentions(errorOf([&] { colorPass(g, "opaque", {}, "hdr2"); }), {"'opaque'", "twice"}));
  EXPECT_TRUE(mentions(errorOf([&] { g.markOutput(hdr, Usage::Present); }), {"'hdr'", "transient"}));
  EXPECT_TRUE(mentions(errorOf([&] { g.markOutput(Handle<Texture>{}, Usage::Present); }), {"invalid texture handle"}));
}
