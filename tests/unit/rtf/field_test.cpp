// RTF field files: round trip, and every malformed or corrupt file rejected with one InputError
// line naming the file (never a crash, never a silently wrong field).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/gi/rtf/field.hpp"
#include "tests/unit/rtf/small_field.hpp"

namespace bounce::gi::rtf {
namespace {

const Field& baked() {
  static const Field f = bake(testing::unitSphere(glm::vec3(0.6f, 0.5f, 0.4f), 8), testing::smallSettings()).field;
  return f;
}

void resign(std::vector<std::uint8_t>& b) {  // recompute the trailing checksum after an edit
  const std::uint64_t h = hashBytes(std::span<const std::uint8_t>(b.data(), b.size() - 8));
  std::memcpy(b.data() + b.size() - 8, &h, 8);
}

std::string errorOf(const std::vector<std::uint8_t>& b) {
  try {
    deserialize(b, "obj.field");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RtfField, RoundTripIsExact) {
  const auto bytes = serialize(baked());
  const Field g = deserialize(bytes, "obj.field");
  EXPECT_EQ(serialize(g), bytes);
  EXPECT_EQ(g.proxies.size(), 2u);
  EXPECT_EQ(g.oof.size(), sampleCount(g.settings) * kShCount);
}

TEST(RtfField, EveryTruncationIsRejected) {
  const auto bytes = serialize(baked());
  for (std::size_t n : {std::size_t(0), std::size_t(5), std::size_t(12), std::size_t(40), bytes.size() / 2, bytes.size() - 9,
                        bytes.size() - 1}) {
    const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(n));
    const std::string e = errorOf(cut);
    EXPECT_NE(e.find("obj.field"), std::string::npos) << n;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
  }
}

TEST(RtfField, BadMagicVersionSettingsChecksumAndIndicesAreRejected) {
  const auto bytes = serialize(baked());
  auto b = bytes;
  b[0] = 'X';
  EXPECT_NE(errorOf(b).find("magic"), std::string::npos);
  b = bytes;
  b[8] = 99;  // version
  EXPECT_NE(errorOf(b).find("version"), std::string::npos);
  b = bytes;
  const std::int32_t zeroProxies = 0;
  std::memcpy(b.data() + 12, &zeroProxies, 4);
  resign(b);
  EXPECT_NE(errorOf(b).find("settings"), std::string::npos);
  b = bytes;
  b[b.size() / 2] ^= 0x10;  // a flipped bit in the data
  EXPECT_NE(errorOf(b).find("checksum"), std::string::npos);
  // A cluster index past the cluster count, correctly checksummed.
  const Field& f = baked();
  const std::size_t N = sampleCount(f.settings);
  const std::size_t clusterIds = bytes.size() - 8 - 8 - N * kShCount * 4 - N * std::size_t(f.settings.components) * 4 - N * 4;
  b = bytes;
  const std::uint32_t bad = 1000;
  std::memcpy(b.data() + clusterIds, &bad, 4);
  resign(b);
  EXPECT_NE(errorOf(b).find("cluster index"), std::string::npos);
  // A NaN in the OOF.
  b = bytes;
  const float nan = std::nanf("");
  std::memcpy(b.data() + bytes.size() - 8 - 8 - 4, &nan, 4);
  resign(b);
  EXPECT_NE(errorOf(b).find("non-finite"), std::string::npos);
}

}  // namespace
}  // namespace bounce::gi::rtf
