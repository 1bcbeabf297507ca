// accuracy.csv's exact shape, the row table's invariants, and the effect metric's zero.
#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include "engine/ref/metrics.hpp"
#include "game/accuracy.hpp"

namespace bounce::game {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(AccuracyCsv, ExactHeaderThenOneLinePerResult) {
  std::vector<AccuracyResult> results(2);
  results[0].row.technique = "direct";
  results[0].row.setting = "ref=direct";
  results[0].gpuMs = 0.25;
  results[0].relRmse = 0.03125;
  results[0].effectRelRmse = 0.5;
  results[1].row.technique = "probes";
  results[1].row.setting = "a,b";  // a comma must be quoted, not split into a sixth column
  results[0].indirectEffectRelRmse = 0.75;
  results[1].effectRelRmse = std::numeric_limits<double>::quiet_NaN();
  results[1].indirectEffectRelRmse = std::numeric_limits<double>::quiet_NaN();  // none: an empty field
  results[0].effectNoiseFloor = 0.0;  // the noise columns: empty where NaN (row 1 has none)
  results[0].effectRelRmseCorrected = 0.5;
  results[0].indirectNoiseFloor = 0.6;
  results[0].indirectEffectRelRmseCorrected = 0.5625;
  const auto l = lines(formatAccuracyCsv(results));
  ASSERT_EQ(l.size(), 3u);
  // The first six columns keep their names and order (scripts read them); the noise columns follow.
  EXPECT_EQ(l[0],
            "technique,setting,gpu_ms,rel_rmse,effect_rel_rmse,indirect_effect_rel_rmse,"
            "effect_noise_floor,effect_rel_rmse_corrected,indirect_noise_floor,indirect_effect_rel_rmse_corrected");
  EXPECT_EQ(l[1], "direct,ref=direct,0.25,0.03125,0.5,0.75,0,0.5,0.6,0.5625");
  EXPECT_EQ(l[2], "probes,\"a,b\",0,0,nan,,,,,");
  EXPECT_EQ(lines(formatAccuracyCsv({})), std::vector<std::string>{kAccuracyCsvHeader});
}

TEST(AccuracyRows, EffectNamesValidSettingsUniqueAndCommaFree) {
  const auto rows = accuracyRows();
  std::set<std::pair<std::string, std::string>> seen;
  std::size_t direct = 0, probes = 0, ao = 0, dnrt = 0, vlm = 0, rtf = 0;
  for (const auto& r : rows) {
    EXPECT_TRUE(scene::effectFromName(r.technique).has_value()) << r.technique;
    EXPECT_EQ(r.setting.find(','), std::string::npos) << r.setting;
    EXPECT_TRUE(seen.insert({r.technique, r.setting}).second) << "duplicate row " << r.technique << " " << r.setting;
    EXPECT_NE(std::find(r.effects.begin(), r.effects.end(), r.technique), r.effects.end())
        << r.technique << " must be among its own effects";
    EXPECT_FALSE(r.passes.empty()) << r.technique;
    // The setting names the reference the row is compared with.
    const std::string ref = !r.referenceBounces        ? "ref=all"
                            : *r.referenceBounces == 0 ? "ref=direct"
                            : *r.referenceBounces == 1 ? "ref=1bounce"
                                                       : "ref=" + std::to_string(*r.referenceBounces) + "bounces";
    EXPECT_TRUE(r.setting.ends_with(ref)) << r.setting << " should end with " << ref;
    direct += r.technique == "direct";
    probes += r.technique == "probes";
    ao += r.technique == "ssao" || r.technique == "hbao";
    dnrt += r.technique == "dnrt";
    vlm += r.technique == "vlm";
    rtf += r.technique == "rtf";
  }
  EXPECT_EQ(direct, 3u);  // against the bounces-0, the full and the one-bounce reference
  EXPECT_EQ(probes, 4u);  // two spacings × two SH orders
  EXPECT_EQ(ao, 2u);      // SSAO and HBAO over probes (the DNRT paper's baselines)
  // {4, 9} SH × grid {16, 32, 64} × intrusion {off, on} × anti-radiance {paper, improved}, + the shipped
  // setting at half and quarter resolution
  EXPECT_EQ(dnrt, 26u);
  EXPECT_EQ(vlm, 16u);    // range {1.5, 2.5, 3.5, 4.5} × K {10, 20, 30, 60}, against one bounce
  // bounces {1, 2} with 9 SH, 2 bounces with 4 SH, 2 bounces with the tail τ = 0.01; then at half and quarter
  // resolution 2 bounces with 9 and 4 SH, and at quarter the tail with 1 and 2 bounces, 9 and 4 SH; full reference
  EXPECT_EQ(rtf, 12u);
}

TEST(AccuracyRows, AvailableOnlyWhenTheRendererRanEveryPass) {
  AccuracyRow row;
  row.passes = {"shadow", "lighting", "probes"};
  EXPECT_FALSE(rowAvailable(row, {"shadow", "gbuffer", "lighting", "tonemap"}));
  EXPECT_TRUE(rowAvailable(row, {"shadow", "gbuffer", "probes", "lighting", "tonemap"}));
}

TEST(EffectMetric, TechniqueEqualToTheReferenceScoresZero) {
  gpu::FloatImage with{4, 3, std::vector<float>(36)}, without{4, 3, std::vector<float>(36)};
  for (std::size_t i = 0; i < 36; ++i) {
    with.rgb[i] = 0.1f + 0.01f * float(i);
    without.rgb[i] = i % 5 == 0 ? 0.05f : with.rgb[i];  // the object changes every 5th value
  }
  const ImageRGB w = toImageRgb(with), wo = toImageRgb(without);
  ASSERT_EQ(w.width, 4);
  ASSERT_EQ(w.height, 3);
  EXPECT_EQ(w.at(1, 2), glm::vec3(with.rgb[27], with.rgb[28], with.rgb[29]));  // row-major, top row first
  const ref::ObjectEffectError e = ref::objectEffectError(w, wo, w, wo);
  EXPECT_FALSE(e.referenceEffectIsZero);
  EXPECT_EQ(e.relativeError, 0.0);
  EXPECT_EQ(e.effectRmse, 0.0);
  // …and leaving the effect out entirely scores 1 (the metric's scale, metrics.hpp).
  EXPECT_DOUBLE_EQ(ref::objectEffectError(wo, wo, w, wo).relativeError, 1.0);
}

}  // namespace
}  // namespace bounce::game
