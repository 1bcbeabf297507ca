// Graphics pipelines with dynamic rendering: a full-screen solid colour into RGBA8 and
// RGBA16F, and a known triangle with inside/outside pixels and additive blending.
#include <gtest/gtest.h>

#include <cstring>

#include "draw_helpers.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/format.hpp"
#include "engine/gpu/testing.hpp"

using namespace bounce::gpu;
using testkit::Color;

namespace {
// Float → UNORM8 conversion may round to either neighbour for values off the 1/255 grid (the
// Vulkan spec's fixed-point conversion allows implementation rounding), hence ±1 for 0.2.
constexpr int kUnormTolerance = 1;
constexpr VkImageUsageFlags kTarget = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

Color halfPixel(const std::vector<std::uint8_t>& bytes, std::uint32_t width, std::uint32_t x, std::uint32_t y) {
  Color c;
  for (int k = 0; k < 4; ++k) {
    std::uint16_t h;
    std::memcpy(&h, bytes.data() + 8 * (y * width + x) + 2 * k, 2);
    c[k] = halfToFloat(h);
  }
  return c;
}
}  // namespace

TEST(Graphics, FullScreenTriangleFillsRgba8) {
  Context& ctx = testkit::sharedContext();
  Image target(ctx, {ImageType::Tex2D, VK_FORMAT_R8G8B8A8_UNORM, 32, 24, 1, 1, 1, kTarget, VK_SAMPLE_COUNT_1_BIT,
                     "rgba8 target"});
  testkit::SolidPipeline solid(ctx, VK_FORMAT_R8G8B8A8_UNORM);
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    testkit::beginColor(ctx, cmd, target, Color{0, 0, 0, 0});
    solid.draw(cmd, {1.0f, 0.2f, 0.0f, 1.0f});
    ctx.cmdEndRendering(cmd);
  });
  auto px = readback(ctx, target);
  ASSERT_EQ(px.size(), 32u * 24 * 4);
  for (std::size_t i = 0; i < px.size(); i += 4) {
    ASSERT_EQ(px[i], 255);
    ASSERT_NEAR(px[i + 1], 51, kUnormTolerance);  // 0.2 · 255
    ASSERT_EQ(px[i + 2], 0);
    ASSERT_EQ(px[i + 3], 255);
  }
}

TEST(Graphics, FullScreenTriangleFillsRgba16fWithHdrValues) {
  Context& ctx = testkit::sharedContext();
  Image target(ctx, {ImageType::Tex2D, VK_FORMAT_R16G16B16A16_SFLOAT, 16, 16, 1, 1, 1, kTarget, VK_SAMPLE_COUNT_1_BIT,
                     "rgba16f target"});
  testkit::SolidPipeline solid(ctx, VK_FORMAT_R16G16B16A16_SFLOAT);
  const Color color{4.5f, 0.125f, -1.0f, 1.0f};  // HDR and negative values, exact in half
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    testkit::beginColor(ctx, cmd, target, Color{0, 0, 0, 0});
    solid.draw(cmd, color);
    ctx.cmdEndRendering(cmd);
  });
  auto px = readback(ctx, target);
  for (std::uint32_t y = 0; y < 16; ++y)
    for (std::uint32_t x = 0; x < 16; ++x) ASSERT_EQ(halfPixel(px, 16, x, y), color) << x << "," << y;
}

TEST(Graphics, KnownTriangleCoversInsidePixelsAndBlendsAdditively) {
  Context& ctx = testkit::sharedContext();
  const std::uint32_t n = 64;
  Image target(ctx, {ImageType::Tex2D, VK_FORMAT_R16G16B16A16_SFLOAT, n, n, 1, 1, 1, kTarget, VK_SAMPLE_COUNT_1_BIT,
                     "triangle target"});
  // Clip-space triangle: Vulkan's y points down, so (0,0.5) is the bottom apex at row 48.
  const std::vector<float> vertices = {-0.5f, -0.5f, 0.5f, -0.5f, 0.0f, 0.5f};
  Buffer vb(ctx, {vertices.size() * 4, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, MemoryUsage::Upload, "triangle vertices"});
  upload(ctx, vb, bytesOf(vertices));

  ShaderModule vs(ctx, "test/triangle.vert.spv"), fs(ctx, "test/solid.frag.spv");
  PipelineLayout layout(ctx, {}, {{VK_SHADER_STAGE_ALL, 0, sizeof(Color)}}, "triangle");
  GraphicsPipelineDesc d;
  d.vertex = &vs;
  d.fragment = &fs;
  d.bindings = {{0, 2 * sizeof(float), false}};
  d.attributes = {{0, 0, VK_FORMAT_R32G32_SFLOAT, 0}};
  d.colorFormats = {VK_FORMAT_R16G16B16A16_SFLOAT};
  d.cull = VK_CULL_MODE_BACK_BIT;
  d.frontFace = VK_FRONT_FACE_CLOCKWISE;  // clockwise on screen with y down
  d.blend = Blend::Additive;
  d.name = "triangle additive";
  Pipeline pipeline = createGraphicsPipeline(ctx, layout, d);

  const Color clear{0.25f, 0.0f, 0.0f, 0.0f}, draw{0.5f, 0.25f, 1.0f, 1.0f};
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    testkit::beginColor(ctx, cmd, target, clear);
    pipeline.bind(cmd);
    VkDeviceSize offset = 0;
    VkBuffer handle = vb.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &handle, &offset);
    for (int i = 0; i < 2; ++i) {  // twice: additive blending must sum both
      pipeline.push(cmd, draw);
      vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    ctx.cmdEndRendering(cmd);
  });
  auto px = readback(ctx, target);
  const Color inside{0.25f + 2 * 0.5f, 2 * 0.25f, 2 * 1.0f, 2 * 1.0f};  // all exact in half
  // Pixel centres clearly inside: around the centroid (32, 26.7) and near the base.
  for (auto [x, y] : {std::pair{32u, 32u}, {32u, 20u}, {20u, 18u}, {44u, 18u}, {32u, 45u}})
    EXPECT_EQ(halfPixel(px, n, x, y), inside) << x << "," << y;
  // Clearly outside: corners, beside the apex, above the base.
  for (auto [x, y] : {std::pair{2u, 2u}, {61u, 61u}, {20u, 45u}, {44u, 45u}, {32u, 12u}, {10u, 30u}})
    EXPECT_EQ(halfPixel(px, n, x, y), clear) << x << "," << y;
  // The base spans rows 16.. (y = −0.5 → row 16): pixels of row 16 with centre y 16.5 are in.
  EXPECT_EQ(halfPixel(px, n, 32, 16), inside);
  EXPECT_EQ(halfPixel(px, n, 32, 15), clear);
}
