// Field storage: Table 2 layout, 8-bit quantisation within its bound, file round trip and
// rejection of malformed files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "engine/core/error.hpp"
#include "engine/gi/dnrt/field.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::gi::dnrt {
namespace {

std::vector<glm::vec3> randomValues(const FieldSettings& s, std::uint64_t seed) {
  math::Pcg32 rng(seed);
  std::vector<glm::vec3> v(std::size_t(s.grid) * s.grid * s.grid * s.shCount);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const float scale = float(1 + i % std::size_t(s.shCount));  // different ranges per coefficient
    v[i] = scale * (rng.nextFloat3() * 2.0f - 1.0f);
  }
  return v;
}

TEST(DnrtField, Table2Layout) {
  EXPECT_EQ(textureCount(4), 3);
  EXPECT_EQ(textureCount(9), 7);
  // Image 0..2: m_0..3 of red, green, blue; 3..5: m_4..7; 6: m_8 r, g, b.
  EXPECT_EQ(slotOf(0, 0).texture, 0);
  EXPECT_EQ(slotOf(3, 0).component, 3);
  EXPECT_EQ(slotOf(2, 1).texture, 1);
  EXPECT_EQ(slotOf(2, 1).component, 2);
  EXPECT_EQ(slotOf(5, 2).texture, 5);
  EXPECT_EQ(slotOf(5, 2).component, 1);
  EXPECT_EQ(slotOf(8, 0).texture, 6);
  EXPECT_EQ(slotOf(8, 2).component, 2);
}

TEST(DnrtField, QuantisationRoundTripIsWithinHalfAStep) {
  for (int sh : {4, 9}) {
    FieldSettings s;
    s.shCount = sh;
    s.grid = 5;
    const auto values = randomValues(s, 7);
    const Field f = quantize(s, glm::vec3(0.0f), 1.0f, values);
    ASSERT_EQ(f.textures.size(), std::size_t(textureCount(sh)));
    ASSERT_EQ(f.textures[0].size(), f.vertexCount() * 4);
    const QuantizationError e = quantizationError(f, values);
    // Half a step of the widest range, plus float rounding of the decode (1e-6 of the range).
    EXPECT_LE(e.maxAbs, e.bound * (1.0f + 1e-4f));
    EXPECT_GT(e.maxAbs, 0.0f);
    // The extremes of each range are exactly representable (bytes 0 and 255).
    for (const Range& r : f.ranges) EXPECT_LE(r.lo, r.hi);
  }
}

TEST(DnrtField, ConstantSlotsDecodeExactly) {
  FieldSettings s;
  s.grid = 3;
  std::vector<glm::vec3> v(27 * 4, glm::vec3(0.25f, -0.5f, 0.0f));
  const Field f = quantize(s, glm::vec3(0.0f), 1.0f, v);
  EXPECT_EQ(quantizationError(f, v).maxAbs, 0.0f);
}

TEST(DnrtField, FileRoundTripAndMalformedFiles) {
  FieldSettings s;
  s.shCount = 9;
  s.grid = 4;
  s.antiRadiance = AntiRadiance::Improved;
  const Field f = quantize(s, glm::vec3(1.0f, 2.0f, 3.0f), 0.5f, randomValues(s, 3));
  const auto path = std::filesystem::path(BOUNCE_TEST_OUT) / "dnrt-roundtrip.field";
  save(f, path);
  const Field g = load(path);
  EXPECT_EQ(g.settings.shCount, 9);
  EXPECT_EQ(g.settings.grid, 4);
  EXPECT_EQ(g.settings.antiRadiance, AntiRadiance::Improved);
  EXPECT_EQ(g.centre, f.centre);
  EXPECT_EQ(g.radius, f.radius);
  EXPECT_EQ(g.textures, f.textures);
  ASSERT_EQ(g.ranges.size(), f.ranges.size());
  for (std::size_t i = 0; i < f.ranges.size(); ++i) EXPECT_EQ(g.ranges[i].lo, f.ranges[i].lo);

  auto bytes = serialize(f);
  EXPECT_THROW(deserialize(std::span(bytes).first(bytes.size() - 1), "x.field"), InputError);  // truncated
  auto extra = bytes;
  extra.push_back(0);
  EXPECT_THROW(deserialize(extra, "x.field"), InputError);  // trailing bytes
  auto magic = bytes;
  magic[0] = 'X';
  EXPECT_THROW(deserialize(magic, "x.field"), InputError);
  auto grid = bytes;
  grid[8 + 4 + 4] = 0xff;  // grid (after magic, version, shCount) becomes huge
  EXPECT_THROW(deserialize(grid, "x.field"), InputError);
  try {
    deserialize(magic, "x.field");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.field"), std::string::npos);
  }
}

}  // namespace
}  // namespace bounce::gi::dnrt
