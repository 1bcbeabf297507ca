// Cooked format: exact round trip, every corruption detected, and the cache re-cooking corrupt
// and stale entries.
#include "engine/asset/cooked_format.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "tests/unit/asset/test_util.hpp"

namespace bounce::asset::test {
namespace {

TEST(CookedFormat, RoundTripIsExact) {
  const fs::path dir = scratch();
  for (const char* model : {"Duck/glTF-Binary/Duck.glb", "RiggedSimple/glTF/RiggedSimple.gltf", "BoxAnimated/glTF/BoxAnimated.gltf"}) {
    SCOPED_TRACE(model);
    const CookedAsset a = cook(assets() / model);
    writeCooked(a, dir / "a.bcook");
    const CookedAsset b = readCooked(dir / "a.bcook");
    EXPECT_TRUE(a == b);
    EXPECT_EQ(serializeCooked(b), readFileBytes(dir / "a.bcook"));  // deterministic bytes
  }
}

TEST(CookedFormat, EverySampledSingleByteFlipIsDetected) {
  // Geometry only keeps the file small (no pixels), so every byte can be tried.
  const CookedAsset a = cook(assets() / "BoxTextured/glTF/BoxTextured.gltf", geometryOnly());
  const auto bytes = serializeCooked(a);
  ASSERT_LT(bytes.size(), 20000u);
  std::size_t tried = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (std::uint8_t mask : {std::uint8_t(0x01), std::uint8_t(0x80)}) {
      auto b = bytes;
      b[i] ^= mask;
      EXPECT_THROW((void)parseCooked(b, "flip.bcook"), InputError) << "byte " << i;
      ++tried;
    }
  }
  EXPECT_GT(tried, 1000u);
}

TEST(CookedFormat, TruncationIsDetected) {
  const auto bytes = serializeCooked(cook(assets() / "Box/glTF/Box.gltf"));
  for (std::size_t n : {std::size_t(0), std::size_t(7), std::size_t(23), std::size_t(100), bytes.size() / 2, bytes.size() - 8,
                        bytes.size() - 1})
    expectInputError([&] { (void)parseCooked(std::span(bytes.data(), n), "cut.bcook"); }, {"cut.bcook: "});
  auto longer = bytes;
  longer.push_back(0);
  expectInputError([&] { (void)parseCooked(longer, "long.bcook"); }, {"long.bcook: checksum"});
}

// Rewrites the cooker version field and fixes the checksum: a well-formed entry from "another
// cooker", which the reader must refuse by version alone.
std::vector<std::uint8_t> withCookerVersion(std::vector<std::uint8_t> b, std::uint32_t version) {
  std::memcpy(b.data() + 12, &version, 4);
  const std::uint64_t sum = hashBytes(std::span(b.data(), b.size() - 8));
  std::memcpy(b.data() + b.size() - 8, &sum, 8);
  return b;
}

TEST(CookedFormat, StaleVersionIsRefused) {
  const auto bytes = serializeCooked(cook(assets() / "Box/glTF/Box.gltf"));
  expectInputError([&] { (void)parseCooked(withCookerVersion(bytes, kCookerVersion + 1), "old.bcook"); },
                   {"old.bcook: header: cooked by cooker version " + std::to_string(kCookerVersion + 1)});
}

TEST(Cache, HitsThenRecooksCorruptAndStaleEntries) {
  const fs::path dir = scratch();
  const fs::path source = assets() / "Duck/glTF/Duck.gltf";
  const CookOptions options = geometryOnly();
  const fs::path entry = dir / (cacheKey(source, options) + ".bcook");
  const CookedAsset first = loadOrCook(source, dir, options);
  ASSERT_TRUE(fs::exists(entry));
  const auto good = readFileBytes(entry);
  std::size_t warnings = log::warningCount();
  EXPECT_TRUE(loadOrCook(source, dir, options) == first);  // hit
  EXPECT_EQ(log::warningCount(), warnings);

  auto corrupt = good;
  corrupt[corrupt.size() / 2] ^= 0x10;
  writeFileAtomic(entry, corrupt);
  EXPECT_TRUE(loadOrCook(source, dir, options) == first);
  EXPECT_EQ(log::warningCount(), warnings + 1);  // "cooked cache entry rejected, re-cooking"
  EXPECT_EQ(readFileBytes(entry), good);         // rewritten

  writeFileAtomic(entry, withCookerVersion(good, kCookerVersion + 7));
  EXPECT_TRUE(loadOrCook(source, dir, options) == first);
  EXPECT_EQ(log::warningCount(), warnings + 2);
  EXPECT_EQ(readFileBytes(entry), good);
}

TEST(Cache, KeyCoversReferencedFilesAndOptions) {
  const fs::path dir = scratch();
  copyFolder(assets() / "BoxTextured/glTF", dir);
  const fs::path src = dir / "BoxTextured.gltf";
  const auto refs = referencedFiles(src);
  ASSERT_EQ(refs.size(), 2u);
  EXPECT_EQ(refs[0].filename(), "BoxTextured0.bin");
  EXPECT_EQ(refs[1].filename(), "CesiumLogoFlat.png");
  const std::string key = cacheKey(src, {});
  EXPECT_NE(cacheKey(src, geometryOnly()), key);
  CookOptions sub;
  sub.subdivision["1"] = {SubdivisionScheme::Loop, 1};
  EXPECT_NE(cacheKey(src, sub), key);
  auto png = readFileBytes(dir / "CesiumLogoFlat.png");
  png.back() ^= 1;  // an image byte changes the key even though the .gltf did not change
  writeFileAtomic(dir / "CesiumLogoFlat.png", png);
  EXPECT_NE(cacheKey(src, {}), key);
}

TEST(Cache, CookManyWithProgress) {
  const fs::path dir = scratch();
  const std::vector<fs::path> sources = {assets() / "Box/glTF/Box.gltf", assets() / "Box/glTF-Binary/Box.glb",
                                         assets() / "Box/glTF-Embedded/Box.gltf"};
  const auto all = loadOrCookAll(sources, dir, geometryOnly());
  ASSERT_EQ(all.size(), 3u);
  for (const auto& a : all) EXPECT_EQ(a.triangleCount(), 12u);
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 3u);
}

}  // namespace
}  // namespace bounce::asset::test
