// The Context's pipeline table (engine/gpu/pipeline_table.hpp): an identical request gets the held
// pipeline, whichever layout objects it comes with; any difference in the creation input builds
// another; a held pipeline outlives the layouts it was first asked with and still runs (validation
// on: no use of a destroyed object); with reuse off every request builds and owns its pipeline.
#include <gtest/gtest.h>

#include <cstring>
#include <set>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/pipeline_table.hpp"
#include "engine/gpu/testing.hpp"
#include "tests/unit/gpu/fill_shader.hpp"

using namespace bounce;
using namespace bounce::gpu;

namespace {

using testkit::FillPush;
using testkit::kFillPush;
const Binding kOut{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT};

ContextOptions reuse(bool on) {
  ContextOptions o;
  o.reusePipelines = on;
  return o;
}

}  // namespace

TEST(PipelineTable, IdenticalRequestGetsTheHeldPipelineWhateverItsLayoutObjects) {
  Context ctx(reuse(true));
  ASSERT_TRUE(ctx.pipelines().reuses());
  // Two sessions' worth of objects: equal content, distinct handles.
  DescriptorSetLayout setA(ctx, {kOut}, "a"), setB(ctx, {kOut}, "b");
  PipelineLayout layoutA(ctx, {setA}, {kFillPush}, "a"), layoutB(ctx, {setB}, {kFillPush}, "b");
  ShaderModule shaderA(ctx, "test/fill.comp.spv"), shaderB(ctx, "test/fill.comp.spv");
  ASSERT_NE(layoutA.handle(), layoutB.handle());
  EXPECT_EQ(shaderA.spirvHash(), shaderB.spirvHash());

  Pipeline first = createComputePipeline(ctx, layoutA, shaderA, "fill a");
  Pipeline second = createComputePipeline(ctx, layoutB, shaderB, "fill b");
  EXPECT_EQ(first.handle(), second.handle());
  EXPECT_TRUE(first.heldByTable() && second.heldByTable());
  EXPECT_EQ(first.layout(), layoutA.handle()) << "each requester binds through its own layout";
  EXPECT_EQ(second.layout(), layoutB.handle());
  const PipelineTable::Counts c = ctx.pipelines().counts();
  EXPECT_EQ(c.built, 1u);
  EXPECT_EQ(c.reused, 1u);
  EXPECT_EQ(c.held, 1u);
  first.reset();  // forgets the handle only: the table still holds it
  EXPECT_EQ(createComputePipeline(ctx, layoutA, shaderA, "fill again").handle(), second.handle());
}

// Each request differs from the base in one part of its key: each builds a pipeline of its own.
TEST(PipelineTable, AnyDifferenceInTheCreationInputBuildsAnother) {
  Context ctx(reuse(true));
  DescriptorSetLayout set(ctx, {kOut}, "out");
  DescriptorSetLayout setAllStages(ctx, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_ALL}}, "all stages");
  DescriptorSetLayout setTwo(ctx, {kOut, {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}}, "two");
  PipelineLayout base(ctx, {set}, {}, "base");
  PipelineLayout stages(ctx, {setAllStages}, {}, "binding stages");
  PipelineLayout bindings(ctx, {setTwo}, {}, "two bindings");
  PipelineLayout pushed(ctx, {set}, {kFillPush}, "push range");
  PipelineLayout twoSets(ctx, {set, set}, {}, "two sets");
  ShaderModule spec(ctx, "test/spec.comp.spv"), fill(ctx, "test/fill.comp.spv");
  EXPECT_NE(spec.spirvHash(), fill.spirvHash());

  std::set<VkPipeline> handles;
  handles.insert(createComputePipeline(ctx, base, spec, "base").handle());
  handles.insert(createComputePipeline(ctx, base, spec, "constants", nullptr, {5u}).handle());
  handles.insert(createComputePipeline(ctx, base, spec, "more constants", nullptr, {5u, 0u}).handle());
  handles.insert(createComputePipeline(ctx, stages, spec, "stages").handle());
  handles.insert(createComputePipeline(ctx, bindings, spec, "bindings").handle());
  handles.insert(createComputePipeline(ctx, pushed, spec, "push").handle());
  handles.insert(createComputePipeline(ctx, twoSets, spec, "sets").handle());
  handles.insert(createComputePipeline(ctx, pushed, fill, "shader").handle());  // as "push" but the shader

  // Graphics: one fixed-function field at a time.
  ShaderModule vs(ctx, "test/fullscreen.vert.spv"), fs(ctx, "test/solid.frag.spv");
  PipelineLayout color(ctx, {}, {{VK_SHADER_STAGE_ALL, 0, 16}}, "solid");
  GraphicsPipelineDesc d;
  d.vertex = &vs;
  d.fragment = &fs;
  d.colorFormats = {VK_FORMAT_R16G16B16A16_SFLOAT};
  d.name = "solid";
  const std::vector<void (*)(GraphicsPipelineDesc&)> variants = {
      [](GraphicsPipelineDesc&) {},
      [](GraphicsPipelineDesc& g) { g.blend = Blend::Additive; },
      [](GraphicsPipelineDesc& g) { g.colorFormats = {VK_FORMAT_R8G8B8A8_UNORM}; },
      [](GraphicsPipelineDesc& g) { g.depthFormat = VK_FORMAT_D32_SFLOAT; },
      [](GraphicsPipelineDesc& g) {
        g.depthFormat = VK_FORMAT_D32_SFLOAT;
        g.depthTest = true;
      },
      [](GraphicsPipelineDesc& g) { g.cull = VK_CULL_MODE_BACK_BIT; },
      [](GraphicsPipelineDesc& g) { g.frontFace = VK_FRONT_FACE_CLOCKWISE; },
      [](GraphicsPipelineDesc& g) { g.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP; },
      [](GraphicsPipelineDesc& g) {  // depth only, as shadow maps
        g.fragment = nullptr;
        g.colorFormats = {};
        g.depthFormat = VK_FORMAT_D32_SFLOAT;
      },
      [](GraphicsPipelineDesc& g) {
        g.bindings = {{0, 8, false}};
        g.attributes = {{0, 0, VK_FORMAT_R32G32_SFLOAT, 0}};
      },
      [](GraphicsPipelineDesc& g) {
        g.bindings = {{0, 8, true}};
        g.attributes = {{0, 0, VK_FORMAT_R32G32_SFLOAT, 0}};
      },
      [](GraphicsPipelineDesc& g) { g.specialization = {1u}; },
  };
  for (auto vary : variants) {
    GraphicsPipelineDesc g = d;
    vary(g);
    handles.insert(createGraphicsPipeline(ctx, color, g).handle());
  }
  const std::size_t distinct = 8 + variants.size();
  EXPECT_EQ(handles.size(), distinct);
  EXPECT_EQ(ctx.pipelines().counts().built, distinct);
  EXPECT_EQ(ctx.pipelines().counts().reused, 0u);
  // The debug name is not part of the key.
  d.name = "another name";
  EXPECT_TRUE(handles.count(createGraphicsPipeline(ctx, color, d).handle()));
  EXPECT_EQ(ctx.pipelines().counts().reused, 1u);
}

// The first requester's layouts go (as a Session's do); the held pipeline, built with the table's
// own copy of the layout, runs with a second requester's sets and push constants and gives the
// formula's values. The validation listener fails the test on any use of a destroyed object.
TEST(PipelineTable, HeldPipelineOutlivesTheLayoutsItWasFirstAskedWith) {
  Context ctx(reuse(true));
  VkPipeline built = VK_NULL_HANDLE;
  {
    DescriptorSetLayout set(ctx, {kOut}, "first");
    PipelineLayout layout(ctx, {set}, {kFillPush}, "first");
    built = createComputePipeline(ctx, layout, ShaderModule(ctx, "test/fill.comp.spv"), "fill").handle();
  }
  const std::uint32_t count = 100;
  Buffer out(ctx, {count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                   MemoryUsage::GpuOnly, "fill out"});
  DescriptorSetLayout set(ctx, {kOut}, "second");
  PipelineLayout layout(ctx, {set}, {kFillPush}, "second");
  Pipeline pipeline = createComputePipeline(ctx, layout, ShaderModule(ctx, "test/fill.comp.spv"), "fill");
  ASSERT_EQ(pipeline.handle(), built);
  DescriptorAllocator descriptors(ctx);
  VkDescriptorSet ds = descriptors.allocate(set);
  DescriptorWriter().buffer(0, out).update(ctx, ds);
  const std::vector<float> v = testkit::dispatchFill(ctx, pipeline, ds, out, FillPush{count, 0.5f, 3.0f});
  ASSERT_EQ(v.size(), count);
  for (std::uint32_t i = 0; i < count; ++i) ASSERT_EQ(v[i], 0.5f * float(i) * float(i) + 3.0f) << "element " << i;
}

TEST(PipelineTable, OffBuildsAndOwnsEveryPipeline) {
  Context ctx(reuse(false));
  EXPECT_FALSE(ctx.pipelines().reuses());
  DescriptorSetLayout set(ctx, {kOut}, "out");
  PipelineLayout layout(ctx, {set}, {kFillPush}, "fill");
  ShaderModule shader(ctx, "test/fill.comp.spv");
  Pipeline a = createComputePipeline(ctx, layout, shader, "a"), b = createComputePipeline(ctx, layout, shader, "b");
  EXPECT_NE(a.handle(), b.handle());
  EXPECT_FALSE(a.heldByTable() || b.heldByTable());
  EXPECT_EQ(ctx.pipelines().counts().built, 2u);
  EXPECT_EQ(ctx.pipelines().counts().reused, 0u);
  EXPECT_EQ(ctx.pipelines().counts().held, 0u);
}
