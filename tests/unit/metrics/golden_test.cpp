// compareToGolden: missing golden, deliberate update via BOUNCE_UPDATE_GOLDENS=1, match,
// mismatch with artifacts, size mismatch.
#include <gtest/gtest.h>

#include <cstdlib>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/ref/metrics_golden.hpp"
#include "test_util.hpp"

namespace bounce::ref {
namespace {

// Tolerance for the tests below: the perturbation they add is far above it.
constexpr double kGoldenTol = 1e-3;

// Sets BOUNCE_UPDATE_GOLDENS for one scope (each ctest entry is its own process, so this does
// not leak into other tests).
struct ScopedEnv {
  explicit ScopedEnv(const char* value) { ::setenv("BOUNCE_UPDATE_GOLDENS", value, 1); }
  ~ScopedEnv() { ::unsetenv("BOUNCE_UPDATE_GOLDENS"); }
};

TEST(Golden, MissingThenWrittenThenMatches) {
  ::unsetenv("BOUNCE_UPDATE_GOLDENS");
  const auto dir = test::testDir();
  const auto golden = dir / "scene.pfm";
  const ImageRGB img = test::randomImage(8, 6, 3);

  const GoldenResult missing = compareToGolden(img, golden, kGoldenTol);
  EXPECT_FALSE(missing.passed);
  EXPECT_TRUE(missing.goldenMissing);
  EXPECT_EQ(missing.summary,
            "FAIL " + golden.string() + ": golden missing (run with BOUNCE_UPDATE_GOLDENS=1 to create it)");

  {
    ScopedEnv env("1");
    EXPECT_TRUE(updateGoldensRequested());
    const GoldenResult w = compareToGolden(img, golden, kGoldenTol);
    EXPECT_TRUE(w.passed);
    EXPECT_TRUE(w.updated);
    EXPECT_EQ(w.summary.rfind("UPDATED ", 0), 0u) << w.summary;
  }
  EXPECT_FALSE(updateGoldensRequested());
  const ImageRGB stored = readPfm(golden);
  EXPECT_EQ(stored.pixels, img.pixels);

  const GoldenResult same = compareToGolden(img, golden, kGoldenTol);
  EXPECT_TRUE(same.passed) << same.summary;
  EXPECT_FALSE(same.updated);
  EXPECT_EQ(same.stats.relativeRmse, 0.0);
  EXPECT_EQ(same.summary.rfind("PASS " + golden.string() + " 8x6: relRMSE 0 <= 0.001, maxAbs 0 <= inf", 0), 0u)
      << same.summary;
}

TEST(Golden, OnlyExactlyOneRequestsAnUpdate) {
  for (const char* v : {"0", "true", "yes", "11", ""}) {
    ScopedEnv env(v);
    EXPECT_FALSE(updateGoldensRequested()) << "'" << v << "'";
  }
}

TEST(Golden, MismatchFailsAndWritesArtifacts) {
  ::unsetenv("BOUNCE_UPDATE_GOLDENS");
  const auto dir = test::testDir();
  const auto golden = dir / "g.pfm";
  ImageRGB img(4, 4, glm::vec3(1.0f));
  writePfm(golden, img);
  img.at(1, 1) = glm::vec3(2.0f);  // RMSE sqrt(3/48) = 0.25, mean 1 → relRMSE 0.25
  GoldenOptions opt;
  opt.artifactDir = dir / "artifacts";
  const GoldenResult r = compareToGolden(img, golden, kGoldenTol, opt);
  EXPECT_FALSE(r.passed);
  EXPECT_DOUBLE_EQ(r.stats.relativeRmse, 0.25);
  EXPECT_DOUBLE_EQ(r.stats.maxAbs, 1.0);
  EXPECT_EQ(r.summary, "FAIL " + golden.string() +
                           " 4x4: relRMSE 0.25 > 0.001, maxAbs 1 <= inf (RMSE 0.25, MAE 0.0625, golden mean 1); "
                           "artifacts in " + opt.artifactDir.string());
  EXPECT_EQ(readPfm(opt.artifactDir / "g.actual.pfm").pixels, img.pixels);
  const ImageSrgb8 cmp = readPng(opt.artifactDir / "g.compare.png");
  EXPECT_EQ(cmp.width, 3 * 4 + 2 * 4);

  // The max-abs bound alone can fail a comparison whose relative RMSE passes.
  GoldenTolerance t;
  t.relativeRmse = 1.0;
  t.maxAbs = 0.5;
  const GoldenResult r2 = compareToGolden(img, golden, t);
  EXPECT_FALSE(r2.passed);
  EXPECT_NE(r2.summary.find("maxAbs 1 > 0.5"), std::string::npos) << r2.summary;
}

TEST(Golden, SizeMismatchAndCorruptGolden) {
  ::unsetenv("BOUNCE_UPDATE_GOLDENS");
  const auto dir = test::testDir();
  writePfm(dir / "g.pfm", ImageRGB(4, 4, glm::vec3(1.0f)));
  const GoldenResult r = compareToGolden(ImageRGB(4, 3, glm::vec3(1.0f)), dir / "g.pfm", kGoldenTol);
  EXPECT_FALSE(r.passed);
  EXPECT_TRUE(r.sizeMismatch);
  EXPECT_EQ(r.summary, "FAIL " + (dir / "g.pfm").string() + ": image is 4x3, golden is 4x4");

  writeFileAtomic(dir / "bad.pfm", std::string("PF\n4 4\n-1\nshort"));
  EXPECT_THROW(compareToGolden(ImageRGB(4, 4), dir / "bad.pfm", kGoldenTol), InputError);
}

}  // namespace
}  // namespace bounce::ref
