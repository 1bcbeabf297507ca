#include <gtest/gtest.h>

#include <cctype>
#include <sstream>

#include "graph_test_util.hpp"

using namespace bounce::rg;
using namespace bounce::rg::test;
using Names = std::vector<std::string>;

TEST(Culling, PassWhoseOutputNothingReadsIsCulled) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto albedo = colorPass(g, "gbuffer", {}, "gbuffer.albedo");
  colorPass(g, "debug", {albedo}, "debug.view");
  bb = drawInto(g, "tonemap", {albedo}, bb);
  g.markOutput(bb, Usage::Present);
  const GraphStats& s = g.compile();
  EXPECT_EQ(s.culledPasses, Names{"debug"});
  EXPECT_EQ(s.executedPasses, (Names{"gbuffer", "tonemap"}));
  EXPECT_EQ(s.transientTextures, 1u);  // debug.view is never allocated
}

TEST(Culling, ChainFeedingTheOutputSurvivesInDeclarationOrder) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto a = colorPass(g, "gbuffer", {}, "gbuffer.albedo");
  auto b = colorPass(g, "lighting", {a}, "lighting.hdr");
  auto c = colorPass(g, "bloom", {b}, "bloom.out");
  bb = drawInto(g, "tonemap", {b, c}, bb);
  g.markOutput(bb, Usage::Present);
  const GraphStats& s = g.compile();
  EXPECT_TRUE(s.culledPasses.empty());
  EXPECT_EQ(s.executedPasses, (Names{"gbuffer", "lighting", "bloom", "tonemap"}));
}

TEST(Culling, SideEffectPassSurvivesWithItsProducers) {
  RenderGraph g;
  auto persistent = g.importBuffer("probes.sh", BufferDesc{1024}, kIdle, 7);
  auto shadow = colorPass(g, "shadow", {}, "shadow.map", color(Format::R32F));
  colorPass(g, "unused", {}, "unused.out");
  g.addPass<Buf>(
      "probes.update",
      [&](Builder& b, Buf& d) {
        b.read(shadow, Usage::SampledCompute);
        d.b = b.write(persistent, Usage::StorageWrite);
        b.sideEffect();
      },
      NoOp{});
  const GraphStats& s = g.compile();
  EXPECT_EQ(s.executedPasses, (Names{"shadow", "probes.update"}));
  EXPECT_EQ(s.culledPasses, Names{"unused"});
}

TEST(Culling, WritingAPersistentBufferWithoutSideEffectIsCulled) {
  RenderGraph g;
  auto persistent = g.importBuffer("probes.sh", BufferDesc{1024}, kIdle, 7);
  g.addPass<Buf>(
      "probes.update", [&](Builder& b, Buf& d) { d.b = b.write(persistent, Usage::StorageWrite); }, NoOp{});
  EXPECT_EQ(g.compile().culledPasses, Names{"probes.update"});
}

TEST(Culling, SwitchedOffKeepsEveryPass) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto albedo = colorPass(g, "gbuffer", {}, "gbuffer.albedo");
  auto shadow = colorPass(g, "shadow", {}, "shadow.map");
  colorPass(g, "dnrt", {shadow}, "dnrt.term");
  bb = drawInto(g, "tonemap", {albedo}, bb);
  g.markOutput(bb, Usage::Present);
  g.setCullingEnabled(false);
  const GraphStats& s = g.compile();
  EXPECT_TRUE(s.culledPasses.empty());
  EXPECT_EQ(s.executedPasses, (Names{"gbuffer", "shadow", "dnrt", "tonemap"}));
  EXPECT_EQ(s.transientTextures, 3u);
  // Switching it back on recompiles with culling.
  g.setCullingEnabled(true);
  EXPECT_EQ(g.compile().culledPasses, (Names{"shadow", "dnrt"}));
}

TEST(Culling, CullingAPassReleasesItsProducersTransitively) {
  // shadow -> dnrt.inject -> dnrt.apply, nothing reads dnrt.apply's output: the whole chain goes,
  // while gbuffer (read by the culled dnrt.apply AND by tonemap) stays.
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto albedo = colorPass(g, "gbuffer", {}, "gbuffer.albedo");
  auto shadow = colorPass(g, "shadow", {}, "shadow.map");
  auto injected = colorPass(g, "dnrt.inject", {shadow}, "dnrt.grid");
  colorPass(g, "dnrt.apply", {injected, albedo}, "dnrt.term");
  bb = drawInto(g, "tonemap", {albedo}, bb);
  g.markOutput(bb, Usage::Present);
  const GraphStats& s = g.compile();
  EXPECT_EQ(s.culledPasses, (Names{"shadow", "dnrt.inject", "dnrt.apply"}));
  EXPECT_EQ(s.executedPasses, (Names{"gbuffer", "tonemap"}));
}

TEST(Culling, AWriteKeepsThePreviousWriterAlive) {
  // transparent loads what opaque drew, so opaque must survive although nobody reads v1.
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto hdr = colorPass(g, "opaque", {}, "hdr");
  hdr = g.addPass<Tex>(
             "transparent", [&](Builder& b, Tex& d) { d.t = b.write(hdr, Usage::ColorAttachment); }, NoOp{})
            .t;
  EXPECT_EQ(hdr.version, 2u);
  bb = drawInto(g, "tonemap", {hdr}, bb);
  g.markOutput(bb, Usage::Present);
  EXPECT_EQ(g.compile().executedPasses, (Names{"opaque", "transparent", "tonemap"}));
}

TEST(Culling, OutputWithoutWriterCullsEverythingAndStillTransitions) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  colorPass(g, "gbuffer", {}, "gbuffer.albedo");
  g.markOutput(bb, Usage::Present);
  const GraphStats& s = g.compile();
  EXPECT_EQ(s.culledPasses, Names{"gbuffer"});
  EXPECT_TRUE(s.executedPasses.empty());
  EXPECT_EQ(s.physicalTextures, 0u);
  EXPECT_EQ(g.describeBarriers(""),
            Names{"backbuffer: Undefined/ColorAttachmentOutput/None -> Present/None/None"});
}

TEST(Dot, NamesEveryPassVerbatimAndMarksCulledOnes) {
  RenderGraph g;
  auto bb = importBackbuffer(g);
  auto albedo = colorPass(g, "gbuffer", {}, "gbuffer.albedo");
  colorPass(g, "vlm \"debug\"", {albedo}, "vlm.debug");
  bb = drawInto(g, "tonemap", {albedo}, bb);
  g.markOutput(bb, Usage::Present);
  std::string dot = g.toDot();
  auto lineWith = [&](const std::string& needle) {
    auto at = dot.find(needle);
    if (at == std::string::npos) return std::string();
    auto begin = dot.rfind('\n', at) + 1;
    return dot.substr(begin, dot.find('\n', at) - begin);
  };
  EXPECT_EQ(dot.rfind("digraph", 0), 0u);
  EXPECT_NE(lineWith("label=\"gbuffer\""), "");
  EXPECT_NE(lineWith("label=\"tonemap\""), "");
  // The quote in the name is escaped for DOT; the culled pass is dashed, the others are not.
  std::string culled = lineWith("label=\"vlm \\\"debug\\\"\"");
  ASSERT_NE(culled, "");
  EXPECT_NE(culled.find("dashed"), std::string::npos);
  EXPECT_EQ(lineWith("label=\"gbuffer\"").find("dashed"), std::string::npos);
  // Resource versions and the edges between them and the passes.
  EXPECT_NE(dot.find("gbuffer.albedo\\nv1"), std::string::npos);
  EXPECT_NE(dot.find("p0 -> r1_v1 [label=\"ColorAttachment\""), std::string::npos);
  EXPECT_NE(dot.find("r1_v1 -> p2 [label=\"SampledFragment\""), std::string::npos);
  // A level without an effect has no pass of it.
  EXPECT_EQ(dot.find("dnrt"), std::string::npos);
  // Every resource version drawn has an edge (issue 16: the backbuffer's unread version 0 floated
  // alone), and a legend explains the notation.
  std::istringstream lines(dot);
  for (std::string line; std::getline(lines, line);) {
    if (line.size() < 4 || line.rfind("  r", 0) != 0 || !std::isdigit(static_cast<unsigned char>(line[3])) ||
        line.find(" -> ") != std::string::npos)
      continue;
    const std::string node = line.substr(2, line.find(' ', 2) - 2);
    EXPECT_TRUE(dot.find(node + " -> ") != std::string::npos || dot.find(" -> " + node + " ") != std::string::npos)
        << "unconnected: " << line;
  }
  EXPECT_EQ(dot.find("r0_v0 ["), std::string::npos) << "the backbuffer's version 0 is never read";
  EXPECT_NE(dot.find("subgraph cluster_legend"), std::string::npos);
}
