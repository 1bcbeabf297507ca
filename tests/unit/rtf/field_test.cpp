// RTF field files: round trip, and every malformed or corrupt file rejected with one InputError
// line naming the file (never a crash, never a silently wrong field).
#include <gtest/gtest.h>

#include <cmath>
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

// The bake rounds the CPCA to fp16 (cpca.hpp roundToHalf), so the file's halves reload as exactly
// the field in memory; its error bound is tested in RtfCpca.Fp16Rounding* and RtfBake.
TEST(RtfField, RoundTripIsExact) {
  const Field& f = baked();
  const auto bytes = serialize(f);
  const Field g = deserialize(bytes, "obj.field");
  EXPECT_EQ(serialize(g), bytes);
  EXPECT_EQ(g.itf.basis, f.itf.basis);
  EXPECT_EQ(g.itf.alpha, f.itf.alpha);
  EXPECT_EQ(g.itf.cluster, f.itf.cluster);
  EXPECT_EQ(g.oof, f.oof);
  EXPECT_EQ(g.frobenius, f.frobenius);
  EXPECT_EQ(g.proxies.size(), 2u);
  EXPECT_EQ(g.oof.size(), sampleCount(g.settings) * kShCount);
  // Version 2's layout, byte for byte: header 12, settings 10·4, centre + radius 16, proxies 12·m,
  // cluster count 4, basis 2·n_c·(n_e+1)·D, ids 4·N, α 2·N·n_e, OOF 4·16·N, error 8, checksum 8.
  const std::size_t N = sampleCount(f.settings), D = itfDimension(f.settings), ne = std::size_t(f.itf.components);
  EXPECT_EQ(bytes.size(), 12 + 40 + 16 + 12 * f.proxies.size() + 4 + 2 * std::size_t(f.itf.clusters) * (ne + 1) * D + 4 * N +
                              2 * N * ne + 4 * kShCount * N + 8 + 8);
}

TEST(RtfField, ACpcaNotRoundedToFp16IsNotSaved) {
  Field f = baked();
  f.itf.basis[1] += 1e-4f * std::abs(f.itf.basis[1]) + 1e-7f;  // between two halves
  EXPECT_THROW(serialize(f), InternalError);
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
  const std::size_t clusterIds = bytes.size() - 8 - 8 - N * kShCount * 4 - N * std::size_t(f.settings.components) * 2 - N * 4;
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
  // An infinite half (0x7c00) as the first basis entry, and a NaN half (0x7e00) as the last α.
  const std::size_t basisStart = 12 + 40 + 16 + 12 * f.proxies.size() + 4;
  for (const std::size_t at : {basisStart, clusterIds + 4 * N + 2 * N * std::size_t(f.settings.components) - 2}) {
    b = bytes;
    const std::uint16_t h = at == basisStart ? 0x7c00 : 0x7e00;
    std::memcpy(b.data() + at, &h, 2);
    resign(b);
    EXPECT_NE(errorOf(b).find("non-finite"), std::string::npos) << at;
  }
}

}  // namespace
}  // namespace bounce::gi::rtf
