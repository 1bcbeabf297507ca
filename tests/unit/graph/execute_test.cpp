// execute(): what the backend is asked to do, in which order, and what passes resolve.
#include <gtest/gtest.h>

#include "graph_test_util.hpp"

using namespace bounce::rg;
using namespace bounce::rg::test;
using Names = std::vector<std::string>;

namespace {

// A command context that passes append to, so the test sees which callbacks ran in which order.
struct LogContext : CommandContext {
  Names log;
};

}  // namespace

TEST(Execute, BackendCallsInOrder) {
  RenderGraph g;
  auto bb = importBackbuffer(g, 100);
  struct Data {
    Handle<Texture> normal, hdr;
  };
  auto& gb = g.addPass<Tex>(
      "gbuffer", [&](Builder& b, Tex& d) { d.t = b.write(b.create<Texture>("gbuffer.normal", color()), Usage::ColorAttachment); },
      [](const Tex& d, const PassResources& r, CommandContext& ctx) {
        auto& log = static_cast<LogContext&>(ctx).log;
        log.push_back("gbuffer renders to " + std::to_string(r.texture(d.t)) +
                      (r.keepsContents(d.t) ? " (load)" : " (clear)"));
      });
  g.addPass<Tex>("debug", [&](Builder& b, Tex& d) { d.t = b.write(b.create<Texture>("debug", color()), Usage::ColorAttachment); },
                 [](const Tex&, const PassResources&, CommandContext& ctx) {
                   static_cast<LogContext&>(ctx).log.push_back("debug ran");
                 });
  auto& tm = g.addPass<Data>(
      "tonemap",
      [&](Builder& b, Data& d) {
        d.normal = b.read(gb.t, Usage::SampledFragment);
        d.hdr = b.write(bb, Usage::ColorAttachment);
      },
      [](const Data& d, const PassResources& r, CommandContext& ctx) {
        auto& log = static_cast<LogContext&>(ctx).log;
        log.push_back("tonemap samples " + std::to_string(r.texture(d.normal)) + " " + describe(r.desc(d.normal)) +
                      " into " + std::to_string(r.texture(d.hdr)) + (r.keepsContents(d.hdr) ? " (load)" : " (clear)"));
      });
  g.markOutput(tm.hdr, Usage::Present);

  RecordingBackend backend;
  LogContext ctx;
  g.execute(backend, ctx);
  EXPECT_EQ(backend.events, (Names{"create texture 1 gbuffer.normal 64x64 RGBA16F", "barrier 1", "begin gbuffer", "end",
                                   "barrier 2", "begin tonemap", "end", "barrier 1", "destroy texture 1"}));
  EXPECT_EQ(ctx.log, (Names{"gbuffer renders to 1 (clear)", "tonemap samples 1 64x64 RGBA16F into 100 (clear)"}));
  // Barriers reach the backend with physical ids filled in.
  ASSERT_EQ(backend.barrierBatches.size(), 3u);
  EXPECT_EQ(backend.barrierBatches[1][0].physical, 1u);
  EXPECT_EQ(backend.barrierBatches[1][1].physical, 100u);
  EXPECT_EQ(backend.barrierBatches[2][0].after.layout, Layout::Present);
  EXPECT_EQ(backend.live, 0);
}

TEST(Execute, SecondWriteLoadsAndImportedContentIsKept) {
  RenderGraph g;
  // A persistent image with content from the previous frame (sampled last).
  auto history = g.importTexture("taa.history", color(),
                                 ResourceState{Layout::ShaderReadOnly, Stage::FragmentShader, Access::ShaderSampledRead}, 42);
  Names log;
  auto keeps = [&log](const Tex& d, const PassResources& r, CommandContext&) {
    log.push_back(r.passName() + (r.keepsContents(d.t) ? " loads" : " clears"));
  };
  auto v1 = g.addPass<Tex>("first", [&](Builder& b, Tex& d) { d.t = b.write(history, Usage::ColorAttachment); }, keeps).t;
  auto v2 = g.addPass<Tex>("second", [&](Builder& b, Tex& d) { d.t = b.write(v1, Usage::ColorAttachment); }, keeps).t;
  g.markOutput(v2, Usage::SampledFragment);
  RecordingBackend backend;
  CommandContext ctx;
  g.execute(backend, ctx);
  EXPECT_EQ(log, (Names{"first loads", "second loads"}));
  EXPECT_EQ(g.describeBarriers("first"),
            Names{"taa.history: ShaderReadOnly/FragmentShader/None -> "
                  "ColorAttachment/ColorAttachmentOutput/ColorAttachmentRead|ColorAttachmentWrite"});
  EXPECT_EQ(g.finalState(v2), (ResourceState{Layout::ShaderReadOnly, Stage::FragmentShader | Stage::ColorAttachmentOutput,
                                             Access::ShaderSampledRead | Access::ColorAttachmentWrite}));
}

TEST(Execute, AddingAPassInvalidatesTheCompiledGraph) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  bb = drawInto(g, "clear", {}, bb);
  g.markOutput(bb, Usage::Present);
  EXPECT_EQ(g.compile().executedPasses, Names{"clear"});
  EXPECT_TRUE(g.compiled());
  bb = drawInto(g, "ui", {}, bb);
  g.markOutput(bb, Usage::Present);
  EXPECT_FALSE(g.compiled());
  RecordingBackend backend;
  CommandContext ctx;
  g.execute(backend, ctx);
  EXPECT_EQ(g.stats().executedPasses, (Names{"clear", "ui"}));
}
