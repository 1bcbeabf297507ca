// DNRT's object effect against the path-traced reference (issue #4 §6: "object effect against the
// reference within a stated tolerance"): cornell-1 at a small size, the paper's standard field
// (4 SH, 32³, no intrusion) with both anti-radiance modes, and the same level without DNRT (the
// probes alone: what the prop's neighbourhood looks like when nothing models its effect).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/gpu/testing.hpp"
#include "game/accuracy.hpp"

namespace bounce::game {
namespace {

constexpr std::uint32_t kSize = 64;
// The prop's indirect effect is small next to path-tracing noise: 256 spp keeps the noise of
// "with − without" below it (two 64² traces of ≈ 4 s each, cached under test-out).
constexpr std::uint32_t kSpp = 256;

// The standard DNRT row (Table 4 configuration 2) and its improved-anti-radiance twin, plus the
// level's own probes without DNRT: the same probe volume the DNRT rows use (level defaults), so the
// two differ only by DNRT.
std::vector<AccuracyRow> rows() {
  std::vector<AccuracyRow> out;
  for (const AccuracyRow& r : accuracyRows({"dnrt"}))
    if (r.setting.starts_with("sh=4;grid=32;intrusion=off;")) out.push_back(r);
  AccuracyRow probes;
  probes.technique = "probes";
  probes.setting = "level;ref=all";
  probes.effects = {"direct", "shadows", "probes"};
  probes.passes = {"shadow", "lighting", "probes"};
  out.push_back(probes);
  return out;
}

const AccuracyReport& report() {
  static const AccuracyReport r = [] {
    AccuracyOptions o;
    o.level = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
    o.out = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "dnrt-effect";
    o.spp = kSpp;
    o.width = o.height = kSize;
    o.measuredFrames = 1;
    o.referenceCache = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "reference";
    o.cookCache = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "cooked";
    o.progress = false;
    o.chart = false;
    o.rows = rows();
    return runAccuracy(o);
  }();
  return r;
}

const AccuracyResult& row(const std::string& technique, const std::string& settingPrefix) {
  for (const auto& r : report().rows)
    if (r.row.technique == technique && r.row.setting.starts_with(settingPrefix)) return r;
  throw std::runtime_error("no row " + technique + " " + settingPrefix);
}

TEST(AccuracyDnrt, ObjectEffectWithinToleranceAndBetterThanLeavingItOut) {
  const AccuracyResult& paper = row("dnrt", "sh=4;grid=32;intrusion=off;anti_radiance=paper");
  const AccuracyResult& improved = row("dnrt", "sh=4;grid=32;intrusion=off;anti_radiance=improved");
  const AccuracyResult& probes = row("probes", "level");
  std::printf("cornell-1 %ux%u, %u spp: effect_rel_rmse dnrt paper %.4f, improved %.4f, probes alone %.4f; "
              "indirect-only: %.4f, %.4f, %.4f\n",
              kSize, kSize, kSpp, paper.effectRelRmse, improved.effectRelRmse, probes.effectRelRmse,
              paper.indirectEffectRelRmse, improved.indirectEffectRelRmse, probes.indirectEffectRelRmse);
  ASSERT_FALSE(paper.referenceEffectIsZero);
  for (const AccuracyResult* r : {&paper, &improved, &probes}) {
    ASSERT_TRUE(std::isfinite(r->effectRelRmse)) << r->row.setting;
    ASSERT_TRUE(std::isfinite(r->indirectEffectRelRmse)) << r->row.setting;
  }
  // Where the prop's effect is indirect only (not seen, no shadow), the probes alone leave it out
  // entirely: their technique effect is exactly zero there, so the error is exactly 1.
  EXPECT_NEAR(probes.indirectEffectRelRmse, 1.0, 1e-9);
  // DNRT models that part. Measured here: 0.849 (paper), 0.848 (improved); 0.916 and 0.902 before
  // c_j carried the level's lamp (issue 15: c_j from the incident-light service, the probes plus
  // the lamp as a cap over the prop's bounding sphere). Not near 0: the reference's effect there is
  // small and carries the noise of two 256-spp traces, and most of it is outside DNRT's local
  // model — the prop, 8 cm under the point lamp, hides ~20 % of its light from the floor, and the
  // darker floor then lights the whole room less. 0.90 asks for the lamp's gain over the probes-only
  // c_j (0.916), with margin for rasterisers that place the prop's edge pixels differently.
  constexpr double kMaxIndirectEffectError = 0.90;
  EXPECT_LT(paper.indirectEffectRelRmse, kMaxIndirectEffectError);
  EXPECT_LT(improved.indirectEffectRelRmse, kMaxIndirectEffectError);
  // App. B.2 / §7.2.6: the improved anti-radiance removes the paper's "lack of intensity" of
  // occlusions, so it is closer to the reference (same reference, so the comparison is paired).
  EXPECT_LT(improved.indirectEffectRelRmse, paper.indirectEffectRelRmse);
  // Over the whole image (the prop's own pixels dominate, lit the same way by both) DNRT still
  // does not make the effect worse than the probes alone.
  EXPECT_LE(paper.effectRelRmse, probes.effectRelRmse);
}

}  // namespace
}  // namespace bounce::game
