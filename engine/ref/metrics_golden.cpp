#include "engine/ref/metrics_golden.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "engine/ref/image_heatmap.hpp"

namespace bounce::ref {

namespace {

std::string sizeText(const ImageRGB& img) { return std::to_string(img.width) + "x" + std::to_string(img.height); }

// %.3g keeps the summary short while still telling 1.2e-03 from 1.0e-03.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void writeArtifacts(const ImageRGB& image, const ImageRGB* golden, const std::filesystem::path& goldenPath,
                    const std::filesystem::path& dir) {
  const std::string stem = goldenPath.stem().string();
  writePfm(dir / (stem + ".actual.pfm"), image);
  if (golden && golden->sameSize(image)) writePng(dir / (stem + ".compare.png"), comparisonImage(*golden, image).image);
}

}  // namespace

bool updateGoldensRequested() {
  const char* v = std::getenv("BOUNCE_UPDATE_GOLDENS");
  return v && std::strcmp(v, "1") == 0;
}

GoldenResult compareToGolden(const ImageRGB& image, const std::filesystem::path& goldenPath,
                             const GoldenTolerance& tolerance, const GoldenOptions& options) {
  GoldenResult res;
  const std::string name = goldenPath.string();
  const bool update = options.update == GoldenUpdate::Always ||
                      (options.update == GoldenUpdate::FromEnvironment && updateGoldensRequested());
  if (update) {
    writePfm(goldenPath, image);
    res.passed = true;
    res.updated = true;
    res.summary = "UPDATED " + name + " " + sizeText(image) + " (BOUNCE_UPDATE_GOLDENS=1: written, not compared)";
    return res;
  }

  std::error_code ec;
  if (!std::filesystem::exists(goldenPath, ec)) {
    res.goldenMissing = true;
    res.summary = "FAIL " + name + ": golden missing (run with BOUNCE_UPDATE_GOLDENS=1 to create it)";
    if (!options.artifactDir.empty()) {
      writeArtifacts(image, nullptr, goldenPath, options.artifactDir);
      res.summary += "; artifacts in " + options.artifactDir.string();
    }
    return res;
  }

  const ImageRGB golden = readPfm(goldenPath);
  if (!golden.sameSize(image)) {
    res.sizeMismatch = true;
    res.summary = "FAIL " + name + ": image is " + sizeText(image) + ", golden is " + sizeText(golden);
    if (!options.artifactDir.empty()) {
      writeArtifacts(image, &golden, goldenPath, options.artifactDir);
      res.summary += "; artifacts in " + options.artifactDir.string();
    }
    return res;
  }

  res.stats = computeErrorStats(image, golden);
  // Written as "not greater" so that NaN metrics (a NaN in the image) fail.
  const bool relOk = res.stats.relativeRmse <= tolerance.relativeRmse;
  const bool maxOk = res.stats.maxAbs <= tolerance.maxAbs;
  res.passed = relOk && maxOk;
  res.summary = std::string(res.passed ? "PASS " : "FAIL ") + name + " " + sizeText(image) + ": relRMSE " +
                num(res.stats.relativeRmse) + (relOk ? " <= " : " > ") + num(tolerance.relativeRmse) + ", maxAbs " +
                num(res.stats.maxAbs) + (maxOk ? " <= " : " > ") + num(tolerance.maxAbs) + " (RMSE " +
                num(res.stats.rmse) + ", MAE " + num(res.stats.mae) + ", golden mean " +
                num(res.stats.referenceMean) + ")";
  if (!res.passed && !options.artifactDir.empty()) {
    writeArtifacts(image, &golden, goldenPath, options.artifactDir);
    res.summary += "; artifacts in " + options.artifactDir.string();
  }
  return res;
}

GoldenResult compareToGolden(const ImageRGB& image, const std::filesystem::path& goldenPath,
                             double relativeRmseTolerance, const GoldenOptions& options) {
  GoldenTolerance t;
  t.relativeRmse = relativeRmseTolerance;
  return compareToGolden(image, goldenPath, t, options);
}

}  // namespace bounce::ref
