#pragma once
// Golden-image comparison for tests: compare a linear capture with a stored PFM golden, report
// metric values and a one-line summary for the assertion message.
//
//   auto g = ref::compareToGolden(img, BOUNCE_SOURCE_DIR "/tests/capture/goldens/cornell.pfm", 2e-3);
//   EXPECT_TRUE(g.passed) << g.summary;
//
// Regenerating goldens is deliberate: run the tests with BOUNCE_UPDATE_GOLDENS=1 and the helper
// WRITES the image as the golden (reporting passed + updated) instead of comparing; then review
// the changed goldens in the diff like any other change.
#include <filesystem>
#include <limits>
#include <string>

#include "engine/core/image.hpp"
#include "engine/ref/metrics.hpp"

namespace bounce::ref {

// A test passes when BOTH bounds hold.
struct GoldenTolerance {
  double relativeRmse = 0.0;                                    // bound on ErrorStats::relativeRmse
  double maxAbs = std::numeric_limits<double>::infinity();      // bound on ErrorStats::maxAbs
};

enum class GoldenUpdate {
  FromEnvironment,  // write the golden iff BOUNCE_UPDATE_GOLDENS=1 (what tests use)
  Never,
  Always,
};

struct GoldenOptions {
  GoldenUpdate update = GoldenUpdate::FromEnvironment;
  // When non-empty and the comparison fails, "<stem>.actual.pfm" and "<stem>.compare.png"
  // (golden | image | heat map) are written here so a CI failure can be looked at.
  std::filesystem::path artifactDir;
};

struct GoldenResult {
  bool passed = false;
  bool updated = false;        // the golden was (re)written instead of compared
  bool goldenMissing = false;  // no golden file (and no update requested)
  bool sizeMismatch = false;
  ErrorStats stats;            // valid when compared (not updated, not missing, same size)
  std::string summary;         // one line: verdict, file, metric values against tolerances
};

// True when the environment variable BOUNCE_UPDATE_GOLDENS is exactly "1".
bool updateGoldensRequested();

// A golden that exists but is not a valid PFM throws InputError (from readPfm): a corrupted
// golden is a broken checkout, not a failed comparison.
GoldenResult compareToGolden(const ImageRGB& image, const std::filesystem::path& goldenPath,
                             const GoldenTolerance& tolerance, const GoldenOptions& options = {});
// Shorthand: tolerance on relative RMSE only.
GoldenResult compareToGolden(const ImageRGB& image, const std::filesystem::path& goldenPath,
                             double relativeRmseTolerance, const GoldenOptions& options = {});

}  // namespace bounce::ref
