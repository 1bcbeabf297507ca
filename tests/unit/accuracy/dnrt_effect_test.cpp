// DNRT's object effect against the path-traced reference (issue #4 §6: "object effect against the
// reference within a stated tolerance"): cornell-1 at a small size, the paper's standard field
// (4 SH, 32³, no intrusion) with both anti-radiance modes, and the same level without DNRT: the
// probes alone as baked (what the prop's neighbourhood looks like when nothing models its effect)
// and relit each frame, as cornell-1 ships them (session 10; README "DNRT with the relit probes").
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
// level's own probes without DNRT, relit as shipped and baked (relight off: a row's configure, same
// references): the same probe volume the DNRT rows use (level defaults), so they differ only by DNRT
// and by the relight.
std::vector<AccuracyRow> rows() {
  std::vector<AccuracyRow> out;
  for (const AccuracyRow& r : accuracyRows({"dnrt"}))
    if (r.setting.starts_with("sh=4;grid=32;intrusion=off;")) out.push_back(r);
  AccuracyRow probes;
  probes.technique = "probes";
  probes.setting = "level;ref=all";
  probes.effects = {"direct", "shadows", "probes"};
  probes.passes = {"shadow", "lighting", "probes.relight", "probes.tiles", "probes"};
  out.push_back(probes);
  probes.setting = "baked;ref=all";
  probes.passes = {"shadow", "lighting", "probes"};  // a baked volume's tiles are built once, no probes.tiles pass
  probes.configure = [](scene::Level& level) { level.probes.relight = false; };
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
  const AccuracyResult& relit = row("probes", "level");
  const AccuracyResult& baked = row("probes", "baked");
  std::printf("cornell-1 %ux%u, %u spp: effect_rel_rmse dnrt paper %.4f, improved %.4f, probes relit %.4f, baked %.4f; "
              "indirect-only: %.4f, %.4f, %.4f, %.4f\n",
              kSize, kSize, kSpp, paper.effectRelRmse, improved.effectRelRmse, relit.effectRelRmse, baked.effectRelRmse,
              paper.indirectEffectRelRmse, improved.indirectEffectRelRmse, relit.indirectEffectRelRmse,
              baked.indirectEffectRelRmse);
  std::printf("whole image rel_rmse: dnrt paper %.4f, improved %.4f, probes relit %.4f, baked %.4f\n", paper.relRmse,
              improved.relRmse, relit.relRmse, baked.relRmse);
  ASSERT_FALSE(paper.referenceEffectIsZero);
  for (const AccuracyResult* r : {&paper, &improved, &relit, &baked}) {
    ASSERT_TRUE(std::isfinite(r->effectRelRmse)) << r->row.setting;
    ASSERT_TRUE(std::isfinite(r->indirectEffectRelRmse)) << r->row.setting;
  }
  // Where the prop's effect is indirect only (not seen, no shadow), the baked probes leave it out
  // entirely: their technique effect is exactly zero there, so the error is exactly 1.
  EXPECT_NEAR(baked.indirectEffectRelRmse, 1.0, 1e-9);
  // The relit probes carry part of it: the room's loss of the light the prop's lamp shadow takes
  // from the floor (the darkening of the lower image, outside DNRT's local model). Measured 0.8894.
  EXPECT_LT(relit.indirectEffectRelRmse, 0.95);
  // DNRT on the relit probes models the rest: the prop's reflection of the lamp onto the ceiling
  // and its occlusion of the probes' light, the lamp left out of the anti-radiance (the shadow map
  // draws its occlusion, the relight its bounce; counted a second time the effect was twice the
  // reference's mean darkening: README "DNRT with the relit probes, session 10"). Measured 0.8225
  // (paper) and 0.8161 (improved; 0.8201 with the lights' SH windowed as before, update.cpp); before session 10 (baked probes, the lamp in k_j) 0.849 and
  // 0.848, and with relit probes but the lamp still in k_j 0.840 and 0.847 (improved worse).
  // Not near 0: the reference's effect there is small and carries the noise of two 256-spp traces.
  // 0.85 asks for the gain over the relit probes alone with margin for rasterisers that place the
  // prop's edge pixels differently.
  constexpr double kMaxIndirectEffectError = 0.85;
  EXPECT_LT(paper.indirectEffectRelRmse, kMaxIndirectEffectError);
  EXPECT_LT(improved.indirectEffectRelRmse, kMaxIndirectEffectError);
  EXPECT_LT(paper.indirectEffectRelRmse, relit.indirectEffectRelRmse);
  // App. B.2 / §7.2.6: the improved anti-radiance removes the paper's "lack of intensity" of
  // occlusions, so it is closer to the reference (same reference, so the comparison is paired).
  EXPECT_LT(improved.indirectEffectRelRmse, paper.indirectEffectRelRmse);
  // Over the whole image (the prop's own pixels dominate, lit the same way by both) DNRT still
  // does not make the effect worse than the probes alone, relit or baked (measured 0.0996 (paper), 0.0993 against
  // 0.1026 and 0.1068).
  EXPECT_LE(paper.effectRelRmse, relit.effectRelRmse);
  EXPECT_LE(paper.effectRelRmse, baked.effectRelRmse);
  // Issue 15: DNRT's whole-image error below the probes + direct light it adds to (the same relit
  // probes). Measured 0.1408 (paper), 0.1404 (improved) against 0.1432 (relit), 0.1469 (baked).
  EXPECT_LT(paper.relRmse, relit.relRmse);
  EXPECT_LT(improved.relRmse, relit.relRmse);
}

}  // namespace
}  // namespace bounce::game
