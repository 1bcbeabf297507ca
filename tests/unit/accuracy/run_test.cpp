// `bounce accuracy` end to end on the Cornell level at a small size: the CSV rows, the direct
// technique against both references, heat maps and the chart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "engine/core/image.hpp"
#include "engine/ref/effect_noise.hpp"
#include "engine/ref/metrics.hpp"
#include "engine/gpu/testing.hpp"
#include "game/accuracy.hpp"

namespace bounce::game {
namespace {

constexpr std::uint32_t kSize = 48;
constexpr std::uint32_t kSpp = 16;  // the full reference's noise stays well below the indirect light it shows
// cornell-vlm's VLMs cover the two coloured walls only (the white surfaces' bounce is left out):
// at 256², 64 spp they take direct light's error against the one-bounce reference from 0.637 to
// 0.601 (0.94×); 0.98 leaves room for this test's 48², 16 spp reference.
constexpr double kMaxVlmVsDirectRatio = 0.98;
// Direct light vs the bounces-0 reference: they agree everywhere but shadow-map edges and
// contact corners (raster_match_test: 0.4 % of a 64×64 view beyond 2 %). Measured here on
// lavapipe: 0.011. The prop hangs 8 cm under the lamp, so its lit top is far brighter than the
// mean: one silhouette pixel of it that the two rasterise differently adds up to ~0.08 (seen at
// 128×128), and the bound allows for that on another driver.
constexpr double kMaxDirectVsDirectRef = 0.15;
// The same for the prop's effect alone (its own pixels and its shadow). Measured here: 0.005;
// the same silhouette pixel gives ~0.07 at 128×128.
constexpr double kMaxDirectEffectVsDirectRef = 0.15;
// The closed Cornell box gets a large share of its light by bouncing; direct light alone
// misses it. Measured here: 0.89 (part of it the reference's 16-spp noise); the bound is far
// above anything shadow-map differences could explain.
constexpr double kMinDirectVsFullRef = 0.3;
// Probes at 0.125 m (4×4×4 in the 0.55 m box) restore most of the bounced light: measured here
// 0.42 against direct's 0.89 (both mostly the 16-spp reference's noise and the probes' low
// frequency). The bound asks for a clear improvement, not the measured value.
constexpr double kMaxProbesVsDirectRatio = 0.75;

// Every row but DNRT's 64³ fields: 4 of those bakes would add about a minute of CI time and test
// nothing the 16³ and 32³ rows do not (the bake and the node do not depend on N).
std::vector<AccuracyRow> testRows() {
  std::vector<AccuracyRow> rows = accuracyRows();
  std::erase_if(rows, [](const AccuracyRow& r) { return r.setting.find("grid=64") != std::string::npos; });
  // DNRT at reduced resolution: half runs (the draw, dnrt.upsample and the row's pass list end to
  // end); quarter is the same code path with another step, left out to keep the run short.
  std::erase_if(rows, [](const AccuracyRow& r) { return r.setting.starts_with("resolution=quarter;"); });
  // SL uncut with and without sl_bounce, and its uncut parts (terms=…;sl_bounce=…): pass 2 over every
  // receiver costs 1.4–2.3× the cut one; the bounce pass itself is covered by SlRelightBounceGpu.*, so
  // the run leaves those six rows out (CI time).
  std::erase_if(rows, [](const AccuracyRow& r) { return r.setting.find("sl_bounce=") != std::string::npos; });
  return rows;
}

class AccuracyRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    AccuracyOptions o;
    // cornell-1's box (split into one entity per wall), lamp and DNRT/SL prop, plus Virtual Light
    // Meshes: the one shipped level in which every technique's rows run.
    o.level = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-vlm.json";
    // One folder per process: ctest runs the suite as one process (entry `AccuracyRun`, so this
    // setup runs once), but single TESTs may still be run side by side with --gtest_filter, each
    // rerunning it; with one folder a process could read back the other's images. No test is
    // current here, so the folder is named after the filter.
    std::string filter = GTEST_FLAG_GET(filter);
    for (char& c : filter)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.') c = '_';
    o.out = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "run" / filter;
    o.spp = kSpp;
    o.width = o.height = kSize;
    o.measuredFrames = 2;
    o.referenceCache = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "reference";
    o.cookCache = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "cooked";
    o.progress = false;
    o.rows = testRows();
    o.effectImages = true;
    report_ = new AccuracyReport(runAccuracy(o));
  }
  static void TearDownTestSuite() {
    delete report_;
    report_ = nullptr;
  }
  static const AccuracyResult& row(const std::string& technique, const std::string& setting) {
    for (const auto& r : report_->rows)
      if (r.row.technique == technique && r.row.setting == setting) return r;
    throw std::runtime_error("no row " + technique + " " + setting);
  }
  static AccuracyReport* report_;
};
AccuracyReport* AccuracyRun::report_ = nullptr;

TEST_F(AccuracyRun, CsvHasTheExactHeaderAndOneLinePerConfigurationRun) {
  std::ifstream in(report_->csv);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0],
            "technique,setting,gpu_ms,rel_rmse,effect_rel_rmse,indirect_effect_rel_rmse,"
            "effect_noise_floor,effect_rel_rmse_corrected,indirect_noise_floor,indirect_effect_rel_rmse_corrected");
  EXPECT_EQ(lines.size(), 1 + report_->rows.size());
  // Every configuration either ran or was skipped with a note; both direct rows run today.
  std::size_t skipped = 0;
  for (const auto& n : report_->notes) skipped += n.rfind("skipped ", 0) == 0;
  EXPECT_EQ(report_->rows.size() + skipped, testRows().size());
  EXPECT_NO_THROW(row("direct", "ref=direct"));
  EXPECT_NO_THROW(row("direct", "ref=all"));
  for (const auto& r : report_->rows) {
    EXPECT_GT(r.gpuMs, 0.0) << r.row.setting << ": the shadow and lighting passes were timed";
    const ImageSrgb8 heat = readPng(r.heatMap);
    EXPECT_GE(heat.width, int(3 * kSize)) << "reference | technique | heat map";
  }
}

TEST_F(AccuracyRun, DirectAgreesWithTheDirectReferenceAndMissesIndirectLight) {
  const AccuracyResult& direct = row("direct", "ref=direct");
  const AccuracyResult& full = row("direct", "ref=all");
  std::printf("direct: rel_rmse %.4f vs bounces 0, %.4f vs full; effect %.4f / %.4f\n", direct.relRmse, full.relRmse,
              direct.effectRelRmse, full.effectRelRmse);
  EXPECT_LT(direct.relRmse, kMaxDirectVsDirectRef);
  EXPECT_LT(direct.effectRelRmse, kMaxDirectEffectVsDirectRef);
  EXPECT_GT(full.relRmse, kMinDirectVsFullRef);
  EXPECT_GT(full.relRmse, direct.relRmse);
  EXPECT_EQ(direct.gpuMs, full.gpuMs) << "one configuration, rendered and timed once for both references";
  // The prop's effect is visible in both references (it casts a shadow and is seen).
  EXPECT_FALSE(direct.referenceEffectIsZero);
  EXPECT_FALSE(full.referenceEffectIsZero);
}

// Every row of every technique whose node exists runs (none skipped), and indirect light from the
// probes is closer to the full reference than direct light alone.
TEST_F(AccuracyRun, EveryTechniqueRunsAndProbesAddTheMissingBounce) {
  EXPECT_EQ(report_->rows.size(), testRows().size());
  const double direct = row("direct", "ref=all").relRmse;
  const double probes = row("probes", "spacing=0.125m;sh_order=3;ref=all").relRmse;
  EXPECT_LT(probes, kMaxProbesVsDirectRatio * direct);
  for (const auto& r : report_->rows) {
    EXPECT_TRUE(std::isfinite(r.relRmse) && std::isfinite(r.effectRelRmse)) << r.row.technique << " " << r.row.setting;
    EXPECT_GT(r.gpuMs, 0.0) << r.row.technique << " " << r.row.setting;
  }
}

// The Virtual Light Meshes (one bounce off the two coloured walls and the prop) bring the image
// closer to the one-bounce reference than direct light alone, and a range of 1.5 (the thesis's
// Fig. 5.6 cut-offs) is no better than 4.5 with the same K.
TEST_F(AccuracyRun, VlmClosesPartOfTheOneBounceGap) {
  const double direct = row("direct", "ref=1bounce").relRmse;
  const double vlm = row("vlm", "range=2.5;k=30;ref=1bounce").relRmse;
  const double shortRange = row("vlm", "range=1.5;k=30;ref=1bounce").relRmse;
  const double longRange = row("vlm", "range=4.5;k=30;ref=1bounce").relRmse;
  std::printf("one-bounce reference: direct %.4f, vlm range 1.5 / 2.5 / 4.5: %.4f / %.4f / %.4f\n", direct, shortRange, vlm,
              longRange);
  EXPECT_LT(vlm, kMaxVlmVsDirectRatio * direct);
  EXPECT_LE(longRange, shortRange);
}

TEST_F(AccuracyRun, ChartIsAValidPng) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "/usr/bin/python3 has no matplotlib (Debian python3-matplotlib)";
  ASSERT_TRUE(report_->chart.has_value());
  std::ifstream in(*report_->chart, std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  EXPECT_EQ(std::string(signature, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const ImageSrgb8 chart = readPng(*report_->chart);
  EXPECT_GT(chart.width, 100);
  EXPECT_GT(chart.height, 100);
}

}  // namespace
}  // namespace bounce::game

namespace bounce::game {
namespace {

// --effect-images: the written PFMs are exactly what the errors compared — the object-effect error
// and the indirect-only one recomputed from them equal every row's reported numbers (float images
// stored as float: the same sums, to rounding of the double accumulation order, 1e-9).
TEST_F(AccuracyRun, EffectImagesReproduceEveryRowsObjectEffectErrors) {
  const std::filesystem::path out = report_->csv.parent_path();
  const ImageRGB maskImage = readPfm(out / "mask-indirect-only.pfm");
  ref::PixelMask mask(maskImage.width, maskImage.height);
  for (int y = 0; y < maskImage.height; ++y)
    for (int x = 0; x < maskImage.width; ++x) mask.set(x, y, maskImage.pixels[std::size_t(y) * maskImage.width + x].x > 0.5f);
  ASSERT_GT(mask.count(), 0u);
  int checked = 0;
  for (const AccuracyResult& r : report_->rows) {
    const std::string stem = r.heatMap.stem().string();  // "heatmap-<row>"
    const std::string name = stem.substr(std::string("heatmap-").size());
    const std::string kind = referenceKind(r.row.setting);
    const ImageRGB with = readPfm(out / ("image-" + name + ".pfm")), without = readPfm(out / ("without-" + name + ".pfm"));
    const ImageRGB refWith = readPfm(out / ("reference-" + kind + "-with.pfm"));
    const ImageRGB refWithout = readPfm(out / ("reference-" + kind + "-without.pfm"));
    const ref::ObjectEffectError all = ref::objectEffectError(with, without, refWith, refWithout);
    const ref::ObjectEffectError indirect = ref::objectEffectError(with, without, refWith, refWithout, &mask);
    if (std::isfinite(r.effectRelRmse)) {
      EXPECT_NEAR(all.relativeError, r.effectRelRmse, 1e-9 * (1.0 + r.effectRelRmse)) << name;
    }
    if (std::isfinite(r.indirectEffectRelRmse)) {
      EXPECT_NEAR(indirect.relativeError, r.indirectEffectRelRmse, 1e-9 * (1.0 + r.indirectEffectRelRmse)) << name;
    }
    ++checked;
  }
  EXPECT_EQ(checked, int(report_->rows.size()));
  EXPECT_GT(checked, 10);
}

// The noise floors: recomputed from the written full and first-half references (effect_noise.hpp)
// they equal every row's columns; each traced reference kind has one, strictly between 0 and 1 at
// 16 spp (the prop's effect is visible, and not all noise); the exact bounces-0 reference has
// floor 0 and its errors are their own corrected form.
TEST_F(AccuracyRun, NoiseFloorsComeFromTheHalfReferencesAndCorrectEveryRow) {
  const std::filesystem::path out = report_->csv.parent_path();
  const ImageRGB maskImage = readPfm(out / "mask-indirect-only.pfm");
  ref::PixelMask mask(maskImage.width, maskImage.height);
  for (int y = 0; y < maskImage.height; ++y)
    for (int x = 0; x < maskImage.width; ++x) mask.set(x, y, maskImage.pixels[std::size_t(y) * maskImage.width + x].x > 0.5f);
  std::set<std::string> kinds;
  for (const auto& f : report_->effectFloors) {
    EXPECT_TRUE(kinds.insert(f.kind).second) << "one floor per reference kind: " << f.kind;
    EXPECT_EQ(f.spp, kSpp);
    EXPECT_GT(f.effect, 0.0) << f.kind;
    EXPECT_LT(f.effect, 1.0) << f.kind;
    EXPECT_GT(f.indirect, 0.0) << f.kind;
    EXPECT_LT(f.indirect, 1.0) << f.kind;
    std::printf("ref=%s %u spp: noise floor %.4f (object effect), %.4f (indirect-only)\n", f.kind.c_str(), f.spp, f.effect,
                f.indirect);
    const auto read = [&](const std::string& part) { return readPfm(out / ("reference-" + f.kind + "-" + part + ".pfm")); };
    const ImageRGB fullWith = read("with"), fullWithout = read("without"), halfWith = read("half-with"),
                   halfWithout = read("half-without");
    EXPECT_NEAR(ref::effectNoise(fullWith, fullWithout, halfWith, halfWithout).floor, f.effect, 1e-9) << f.kind;
    EXPECT_NEAR(ref::effectNoise(fullWith, fullWithout, halfWith, halfWithout, &mask).floor, f.indirect, 1e-9) << f.kind;
  }
  EXPECT_EQ(kinds, (std::set<std::string>{"all", "1bounce"}));
  for (const AccuracyResult& r : report_->rows) {
    const std::string kind = referenceKind(r.row.setting);
    const std::string name = r.row.technique + " " + r.row.setting;
    if (kind == "direct") {
      EXPECT_EQ(r.effectNoiseFloor, 0.0) << name;
      EXPECT_EQ(r.indirectNoiseFloor, 0.0) << name;
      if (std::isfinite(r.effectRelRmse)) { EXPECT_EQ(r.effectRelRmseCorrected, r.effectRelRmse) << name; }
      continue;
    }
    const auto f = std::find_if(report_->effectFloors.begin(), report_->effectFloors.end(),
                                [&](const auto& e) { return e.kind == kind; });
    ASSERT_NE(f, report_->effectFloors.end()) << name;
    EXPECT_EQ(r.effectNoiseFloor, f->effect) << name;
    EXPECT_EQ(r.indirectNoiseFloor, f->indirect) << name;
    EXPECT_EQ(r.effectRelRmseCorrected, ref::noiseCorrectedError(r.effectRelRmse, f->effect)) << name;
    if (std::isfinite(r.indirectEffectRelRmse)) {
      EXPECT_EQ(r.indirectEffectRelRmseCorrected, ref::noiseCorrectedError(r.indirectEffectRelRmse, f->indirect)) << name;
      // e*² − e² = f²(e² − 1)/(1 − f²): the correction lowers errors below 1 ("effect missing") and
      // raises those above it (the noise had diluted them), and leaves 1 where it is.
      const double e = r.indirectEffectRelRmse, corrected = r.indirectEffectRelRmseCorrected;
      if (e <= 1.0) {
        EXPECT_LE(corrected, e + 1e-12) << name;
      } else {
        EXPECT_GE(corrected, e - 1e-12) << name;
      }
    }
  }
}

}  // namespace
}  // namespace bounce::game
