// PFM: exact bytes written, bit-exact round trips, row order, endianness, and hostile input.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/image.hpp"
#include "test_util.hpp"

namespace bounce::ref {
namespace {

std::vector<std::uint8_t> bytesOf(const std::string& s) { return {s.begin(), s.end()}; }

void appendFloat(std::vector<std::uint8_t>& out, float f, bool bigEndian = false) {
  std::uint32_t u = std::bit_cast<std::uint32_t>(f);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(u >> (bigEndian ? 24 - 8 * i : 8 * i)));
}

// The message of the InputError that parsing `bytes` throws ("" if none was thrown).
std::string parseError(const std::vector<std::uint8_t>& bytes, const PfmReadOptions& opt = {}) {
  try {
    parsePfm(bytes, "t.pfm", opt);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool bitEqual(const ImageRGB& a, const ImageRGB& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec3)) == 0;
}

TEST(Pfm, WritesHeaderAndBottomRowFirst) {
  ImageRGB img(1, 2);
  img.at(0, 0) = {1, 2, 3};  // top
  img.at(0, 1) = {4, 5, 6};  // bottom
  std::vector<std::uint8_t> expected = bytesOf("PF\n1 2\n-1.0\n");
  for (float f : {4.0f, 5.0f, 6.0f, 1.0f, 2.0f, 3.0f}) appendFloat(expected, f);
  EXPECT_EQ(encodePfm(img), expected);
  EXPECT_THROW(encodePfm(ImageRGB()), InternalError);
}

TEST(Pfm, RoundTripIsBitExact) {
  const auto dir = test::testDir();
  ImageRGB img = test::randomImage(7, 5, 1234, -3.0f, 100.0f);
  // Edge values a naive text or clamping path would change.
  img.pixels[0] = {0.0f, -0.0f, std::numeric_limits<float>::denorm_min()};
  img.pixels[1] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(),
                   std::numeric_limits<float>::min()};
  img.pixels[2] = {1.0f / 3.0f, 1e-30f, -7.25e12f};
  writePfm(dir / "x.pfm", img);
  EXPECT_TRUE(bitEqual(readPfm(dir / "x.pfm"), img));

  // Non-finite values survive too when the reader allows them.
  img.pixels[3] = {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                   std::numeric_limits<float>::quiet_NaN()};
  writePfm(dir / "y.pfm", img);
  EXPECT_TRUE(bitEqual(readPfm(dir / "y.pfm", PfmReadOptions{.requireFinite = false}), img));
  EXPECT_EQ(parseError(readFileBytes(dir / "y.pfm")),
            "t.pfm: pixel (3, 0) channel R: value is infinite (expected finite floats)");
}

TEST(Pfm, ReadsBigEndianAndGrey) {
  std::vector<std::uint8_t> be = bytesOf("PF\n2 1\n1.0\n");
  for (float f : {1.5f, -2.0f, 3.0f, 4.0f, 5.0f, 6.0f}) appendFloat(be, f, /*bigEndian=*/true);
  const ImageRGB a = parsePfm(be, "be.pfm");
  ASSERT_EQ(a.width, 2);
  EXPECT_EQ(a.pixels[0], glm::vec3(1.5f, -2.0f, 3.0f));
  EXPECT_EQ(a.pixels[1], glm::vec3(4.0f, 5.0f, 6.0f));

  // "Pf", 1x2, extra header whitespace allowed between tokens; grey goes to all three channels.
  std::vector<std::uint8_t> grey = bytesOf("Pf  1\t2\r\n-2.5\n");
  for (float f : {0.25f, 0.75f}) appendFloat(grey, f);
  const ImageRGB g = parsePfm(grey, "g.pfm");
  ASSERT_EQ(g.height, 2);
  EXPECT_EQ(g.at(0, 0), glm::vec3(0.75f));  // first stored row is the bottom one
  EXPECT_EQ(g.at(0, 1), glm::vec3(0.25f));
}

std::vector<std::uint8_t> header(const std::string& h, std::size_t payloadBytes) {
  auto b = bytesOf(h);
  b.resize(b.size() + payloadBytes, 0);
  return b;
}

TEST(Pfm, HostileHeadersGiveOneLineErrors) {
  const std::string magicExp = " (expected 'PF' (RGB) or 'Pf' (grey))";
  const std::string dimExp = " (expected width as an integer in 1..16384)";
  const std::string scaleExp = " (expected a non-zero number, negative for little-endian)";
  struct Case {
    std::vector<std::uint8_t> bytes;
    std::string error;
  };
  const Case cases[] = {
      {{}, "t.pfm: byte 0: file ends before the magic" + magicExp},
      {header("P6\n1 1\n255\n", 3), "t.pfm: byte 0: not a PFM file (magic 'P6')" + magicExp},
      {header("PF\n16385 1\n-1.0\n", 0), "t.pfm: byte 3: width 16385 is too large" + dimExp},
      {header("PF\n1 99999999999999999999999999\n-1.0\n", 0),
       "t.pfm: byte 5: height 99999999999999999999999999 is too large (expected height as an integer in 1..16384)"},
      {header("PF\n-4 4\n-1.0\n", 192), "t.pfm: byte 3: width '-4' is not a positive integer" + dimExp},
      {header("PF\n0 4\n-1.0\n", 0), "t.pfm: byte 3: width is 0" + dimExp},
      {header("PF\n2 2\nabc\n", 48), "t.pfm: byte 7: scale 'abc' is not a number" + scaleExp},
      {header("PF\n2 2\n-1.0x\n", 48), "t.pfm: byte 7: scale '-1.0x' is not a number" + scaleExp},
      {header("PF\n2 2\n0.0\n", 48), "t.pfm: byte 7: scale '0.0' is zero or not finite" + scaleExp},
      {header("PF\n2 2\nnan\n", 48), "t.pfm: byte 7: scale 'nan' is zero or not finite" + scaleExp},
      {header("PF\n2 2\n-1.0", 0),
       "t.pfm: byte 7: no whitespace after the scale (expected one newline, then the float payload)"},
      {header("PF\n2", 0), "t.pfm: byte 4: file ends before the height (expected height as an integer in 1..16384)"},
      {header(std::string(100, 'Z'), 0), "t.pfm: byte 0: magic is not a short text token" + magicExp},
  };
  for (const Case& c : cases) {
    const std::string msg = parseError(c.bytes);
    EXPECT_EQ(msg, c.error);
    EXPECT_EQ(msg.find('\n'), std::string::npos);
  }
}

TEST(Pfm, PayloadMustBeExact) {
  // 2x2 RGB needs 48 bytes after the 10-byte header.
  EXPECT_EQ(parseError(header("PF\n2 2\n-1\n", 47)),
            "t.pfm: byte 10: payload truncated: 47 bytes (expected 48 bytes for 2x2x3 floats)");
  EXPECT_EQ(parseError(header("PF\n2 2\n-1\n", 49)),
            "t.pfm: byte 10: extra bytes after payload: 49 bytes (expected 48 bytes for 2x2x3 floats)");
  // The largest legal header with a tiny payload is rejected before anything is allocated.
  EXPECT_EQ(parseError(header("PF\n16384 16384\n-1\n", 12)),
            "t.pfm: byte 18: payload truncated: 12 bytes (expected 3221225472 bytes for 16384x16384x3 floats)");
  EXPECT_EQ(parseError(header("PF\n2 2\n-1\n", 48)), "");
}

TEST(Pfm, NonFiniteValuesRejectedByDefault) {
  std::vector<std::uint8_t> b = bytesOf("PF\n1 2\n-1\n");
  for (float f : {0.0f, 0.0f, 0.0f, 1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f}) appendFloat(b, f);
  // The first stored row is the bottom one, so the second stored pixel is the top one, (0, 0).
  EXPECT_EQ(parseError(b), "t.pfm: pixel (0, 0) channel G: value is NaN (expected finite floats)");
  b = bytesOf("PF\n1 2\n-1\n");
  for (float f : {0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f, 1.0f, 1.0f, 1.0f}) appendFloat(b, f);
  EXPECT_EQ(parseError(b), "t.pfm: pixel (0, 1) channel G: value is NaN (expected finite floats)");
  EXPECT_EQ(parseError(b, PfmReadOptions{.requireFinite = false}), "");
}

TEST(Pfm, MissingFileIsInputError) {
  const auto dir = test::testDir();
  EXPECT_THROW(readPfm(dir / "nope.pfm"), InputError);
}

// Random byte corruptions of a valid file: each must give either a well-formed image or an
// InputError, never another exception or an inconsistent image.
TEST(Pfm, CorruptedFilesNeverYieldInconsistentImages) {
  const std::vector<std::uint8_t> valid = encodePfm(test::randomImage(3, 2, 7));
  std::mt19937 rng(99);
  int parsed = 0, rejected = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<std::uint8_t> b = valid;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits; ++e) {
      switch (rng() % 3) {
        case 0: b[rng() % b.size()] = static_cast<std::uint8_t>(rng()); break;   // overwrite
        case 1: b.resize(rng() % (b.size() + 1)); break;                          // truncate
        default: b.insert(b.begin() + rng() % (b.size() + 1), static_cast<std::uint8_t>(rng())); break;
      }
      if (b.empty()) break;
    }
    try {
      const ImageRGB img = parsePfm(b, "f.pfm", PfmReadOptions{.requireFinite = false});
      ASSERT_GE(img.width, 1);
      ASSERT_GE(img.height, 1);
      ASSERT_EQ(img.pixels.size(), std::size_t(img.width) * img.height);
      ++parsed;
    } catch (const InputError&) {
      ++rejected;
    }
  }
  // Both outcomes occur (payload overwrites keep the file valid; header damage does not).
  EXPECT_GT(parsed, 0);
  EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace bounce::ref
