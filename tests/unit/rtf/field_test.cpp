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

// The same object with its last 2 of 4 components in 8 bits (cpca.hpp quantize).
const Field& bakedBytes() {
  static const Field f = [] {
    FieldSettings s = testing::smallSettings();
    s.byteComponents = 2;
    return bake(testing::unitSphere(glm::vec3(0.6f, 0.5f, 0.4f), 8), s).field;
  }();
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

// The bake rounds the CPCA to fp16 (cpca.hpp quantize), so the file's halves reload as exactly
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
  // Version 3's layout with n₈ = 0, byte for byte: header 12, settings 11·4, centre + radius 16,
  // proxies 12·m, cluster count 4, basis 2·n_c·(n_e+1)·D, ids 4·N, α 2·N·n_e, OOF 4·16·N, error 8,
  // checksum 8.
  const std::size_t N = sampleCount(f.settings), D = itfDimension(f.settings), ne = std::size_t(f.itf.components);
  EXPECT_EQ(bytes.size(), 12 + 44 + 16 + 12 * f.proxies.size() + 4 + 2 * std::size_t(f.itf.clusters) * (ne + 1) * D + 4 * N +
                              2 * N * ne + 4 * kShCount * N + 8 + 8);
}

// With n₈ = 2 of n_e = 4 components in 8 bits: the decoded values reload exactly, and the layout is
// header 12, settings 44, centre + radius 16, proxies 12·m, count 4, half rows 2·n_c·(n_e−n₈+1)·D,
// code rows n_c·n₈·D, row scales 4·n_c·n₈, ids 4·N, half α 2·N·(n_e−n₈), α codes N·n₈, sample
// scales 4·N, OOF 4·16·N, error 8, checksum 8.
TEST(RtfField, ByteTailRoundTripIsExact) {
  const Field& f = bakedBytes();
  ASSERT_EQ(f.itf.byteComponents, 2);
  const auto bytes = serialize(f);
  const Field g = deserialize(bytes, "obj.field");
  EXPECT_EQ(serialize(g), bytes);
  EXPECT_EQ(g.itf.basis, f.itf.basis);
  EXPECT_EQ(g.itf.alpha, f.itf.alpha);
  EXPECT_EQ(g.itf.basisScale, f.itf.basisScale);
  EXPECT_EQ(g.itf.alphaScale, f.itf.alphaScale);
  EXPECT_EQ(g.settings.byteComponents, 2);
  const std::size_t N = sampleCount(f.settings), D = itfDimension(f.settings), nc = std::size_t(f.itf.clusters);
  EXPECT_EQ(bytes.size(), 12 + 44 + 16 + 12 * f.proxies.size() + 4 + 2 * nc * 3 * D + nc * 2 * D + 4 * nc * 2 + 4 * N + 2 * N * 2 +
                              N * 2 + 4 * N + 4 * kShCount * N + 8 + 8);
  Field h = f;
  h.settings.byteComponents = 1;  // the Cpca's storage must be the settings'
  EXPECT_THROW(serialize(h), InternalError);
}

// The 8-bit tail's bad input, correctly checksummed: n₈ past n_e, a negative sample scale, a code −128.
TEST(RtfField, ByteTailBadSettingsScalesAndCodesAreRejected) {
  const Field& f = bakedBytes();
  const auto bytes = serialize(f);
  const std::size_t N = sampleCount(f.settings);
  auto b = bytes;
  const std::int32_t tooMany = f.settings.components + 1;
  std::memcpy(b.data() + 12 + 40, &tooMany, 4);  // byteComponents, the 11th setting
  resign(b);
  EXPECT_NE(errorOf(b).find("settings"), std::string::npos);
  const std::size_t alphaScales = bytes.size() - 8 - 8 - N * kShCount * 4 - N * 4;
  b = bytes;
  const float negative = -1.0f;
  std::memcpy(b.data() + alphaScales, &negative, 4);
  resign(b);
  EXPECT_NE(errorOf(b).find("cpca scales"), std::string::npos);
  b = bytes;
  b[alphaScales - 1] = 0x80;  // the last α code: −128
  resign(b);
  EXPECT_NE(errorOf(b).find("cpca codes"), std::string::npos);
  EXPECT_EQ(errorOf(b).find('\n'), std::string::npos) << "one line";
}

// More of the 8-bit tail's hostile input (review 15, item 6), each one line naming the file: a NaN and
// an +inf basis-row scale, a finite row scale whose decoded entries overflow (3e38 · a code of ±127),
// and a file cut inside the basis codes.
TEST(RtfField, ByteTailNonFiniteScalesOverflowAndCutCodesAreRejected) {
  const Field& f = bakedBytes();
  const auto bytes = serialize(f);
  const std::size_t D = itfDimension(f.settings), nc = std::size_t(f.itf.clusters);
  const std::size_t ne = std::size_t(f.settings.components), n8 = std::size_t(f.settings.byteComponents);
  ASSERT_GT(n8, 0u);
  // Header 12, settings 44, centre + radius 16, proxies, the cluster count; then the halves and codes.
  const std::size_t codes = 12 + 44 + 16 + 12 * f.proxies.size() + 4 + 2 * nc * (ne - n8 + 1) * D;
  const std::size_t rowScales = codes + nc * n8 * D;
  float stored = 0.0f;
  std::memcpy(&stored, bytes.data() + rowScales, 4);
  ASSERT_EQ(stored, f.itf.basisScale[0]) << "the first basis-row scale is where this test thinks";
  for (const float bad : {std::nanf(""), INFINITY}) {
    auto b = bytes;
    std::memcpy(b.data() + rowScales, &bad, 4);
    resign(b);
    const std::string e = errorOf(b);
    EXPECT_NE(e.find("obj.field: cpca scales: negative or non-finite scale"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
  }
  {
    auto b = bytes;
    const float huge = 3e38f;  // finite, but 3e38 · 127 is not
    std::memcpy(b.data() + rowScales, &huge, 4);
    resign(b);
    const std::string e = errorOf(b);
    EXPECT_NE(e.find("obj.field: data: non-finite value"), std::string::npos) << e;
  }
  for (const std::size_t n : {codes + 1, codes + nc * n8 * D / 2, rowScales - 1}) {
    const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(n));
    const std::string e = errorOf(cut);
    EXPECT_NE(e.find("obj.field"), std::string::npos) << n;
    EXPECT_NE(e.find("cpca basis codes"), std::string::npos) << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
  }
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
  const std::size_t basisStart = 12 + 44 + 16 + 12 * f.proxies.size() + 4;
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
