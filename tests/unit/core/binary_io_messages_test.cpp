// The error messages of the engine's four binary formats (cooked assets, DNRT fields, RTF fields,
// SL sphere sets), pinned byte for byte: they share one reader (engine/core/binary_io.hpp) whose
// two parameters (the "a complete X file" wording, and whether `where` carries the byte offset)
// must reproduce each format's messages exactly. Each case is a real file cut or corrupted at a
// known byte, so the `where` and the offset are known in advance.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "engine/asset/cooked_format.hpp"
#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/gi/dnrt/field.hpp"
#include "engine/gi/rtf/field.hpp"
#include "engine/gi/sl/sphere_set.hpp"

namespace bounce {
namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

std::vector<std::uint8_t> header(const char (&magic)[9], std::uint32_t version) {
  std::vector<std::uint8_t> b(magic, magic + 8);
  b.resize(12);
  std::memcpy(b.data() + 8, &version, 4);
  return b;
}

template <class F>
void expectMessages(F deserialize, const char (&magic)[9], std::uint32_t version, const std::vector<std::string>& expected) {
  const auto good = header(magic, version);
  auto badMagic = good;
  badMagic[2] ^= 0x20;
  const std::vector<std::vector<std::uint8_t>> cases = {
      std::vector<std::uint8_t>(good.begin(), good.begin() + 3),  // cut inside the magic
      badMagic,                                                   // third magic byte wrong
      header(magic, version + 7),                                 // another version
      good,                                                       // cut right after the header
  };
  ASSERT_EQ(cases.size(), expected.size());
  for (std::size_t i = 0; i < cases.size(); ++i)
    EXPECT_EQ(messageOf([&] { (void)deserialize(std::span<const std::uint8_t>(cases[i]), std::string("f.bin")); }), expected[i])
        << "case " << i;
}

TEST(BinaryIoMessages, DnrtField) {
  expectMessages(gi::dnrt::deserialize, "BDNRTFLD", 2,
                 {"f.bin: header: truncated (expected a complete DNRT field file)",
                  "f.bin: header: not a DNRT field (expected magic BDNRTFLD)",
                  "f.bin: version: version 9 (expected version 2)",
                  "f.bin: shCount: truncated (expected a complete DNRT field file)"});
}

TEST(BinaryIoMessages, RtfField) {
  expectMessages(gi::rtf::deserialize, "BRTFFLD\0", 3,
                 {"f.bin: header: truncated (expected a complete RTF field file)",
                  "f.bin: header: not an RTF field (expected magic BRTFFLD)",
                  "f.bin: version: version 10 (expected version 3)",
                  "f.bin: proxies: truncated (expected a complete RTF field file)"});
}

TEST(BinaryIoMessages, SlSphereSetCarriesTheByteOffset) {
  // `where (byte N)`: N is the read position when the check failed (after the byte or word read).
  expectMessages(gi::sl::deserialize, "BSLSPSET", 2,
                 {"f.bin: header (byte 3): truncated (expected a complete SL sphere-set file)",
                  "f.bin: header (byte 3): not an SL sphere set (expected magic BSLSPSET)",
                  "f.bin: version (byte 12): version 9 (expected version 2)",
                  "f.bin: settings (byte 12): truncated (expected a complete SL sphere-set file)"});
}

TEST(BinaryIoMessages, CookedAssetSections) {
  asset::CookedAsset a;
  a.sourceName = "abc";
  const auto bytes = asset::serializeCooked(a);
  const auto parse = [](const std::vector<std::uint8_t>& b) {
    return messageOf([&] { (void)asset::parseCooked(b, "a.bcook"); });
  };
  EXPECT_EQ(parse({bytes.begin(), bytes.begin() + 3}), "a.bcook: header: file has 3 bytes (expected a cooked asset)");
  auto badMagic = bytes;
  badMagic[2] ^= 0x20;
  EXPECT_EQ(parse(badMagic), "a.bcook: byte 0: bad magic (expected \"BCOOKED\")");
  // Section 1 (Info) starts after the 24-byte header and 9 table entries of 24 bytes: sourceName's
  // u64 length, its 3 bytes, rootNodes' u64 count. A length of 1000 overruns the 19-byte section
  // (checksum fixed, so the section reader is what refuses it).
  auto longName = bytes;
  const std::uint64_t n = 1000;
  std::memcpy(longName.data() + 240, &n, 8);
  const std::uint64_t sum = hashBytes(std::span(longName.data(), longName.size() - 8));
  std::memcpy(longName.data() + longName.size() - 8, &sum, 8);
  EXPECT_EQ(parse(longName), "a.bcook: section 1 byte 8: count 1000 exceeds the section (expected at most 11 bytes of data)");
}

}  // namespace
}  // namespace bounce
