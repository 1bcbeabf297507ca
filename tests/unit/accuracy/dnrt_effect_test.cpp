// DNRT's object effect against the path-traced reference (issue #4 §6: "object effect against the
// reference within a stated tolerance"): cornell-1 at a small size, the paper's standard field
// (4 SH, 32³, no intrusion) with both anti-radiance modes, and the same level without DNRT: the
// probes alone as baked (what the prop's neighbourhood looks like when nothing models its effect)
// and relit each frame, as cornell-1 ships them (session 10; README "DNRT with the relit probes").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/gpu/image_io.hpp"
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
    o.effectImages = true;  // the PFMs the paired comparisons below read
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

// A row's images as runAccuracy wrote them (effectImages): "image-<name>.pfm", "without-<name>.pfm",
// <name> as in its heat map's file name.
struct RowImages {
  gpu::FloatImage with, without;
};
RowImages imagesOf(const AccuracyResult& r) {
  const std::string stem = r.heatMap.stem().string();  // "heatmap-<name>"
  const std::string name = stem.substr(std::string("heatmap-").size());
  const std::filesystem::path dir = r.heatMap.parent_path();
  return {gpu::readPfm(dir / ("image-" + name + ".pfm")), gpu::readPfm(dir / ("without-" + name + ".pfm"))};
}

// Paired comparison of rows A and B against the same reference, pixel by pixel: d_i = Σ_c (e_A² − e_B²)
// with e the row's error at pixel i, channel c — of the effect (with − without, against the
// reference's) when `effect`, else of the image. Σ d_i > 0 is exactly "B's error below A's" (the
// metrics share their denominator: the reference effect's RMS, the reference image's mean). What a thin margin leaves open is whether that sum rests on a
// few pixels (a rasteriser that places the prop's edges differently would move those): so the mean
// of d in units of its standard error over the pixels (z, pixels taken as independent, which
// neighbouring pixels are not quite), and the sum again without the 2 % of pixels with the largest
// |d| (the edges, the lamp's and the prop's silhouettes).
struct Paired {
  double z = 0.0, trimmedSum = 0.0, sum = 0.0, relativeA = 0.0, relativeB = 0.0;
  std::size_t pixels = 0;
};
Paired paired(const RowImages& a, const RowImages& b, const gpu::FloatImage& refWith, const gpu::FloatImage& refWithout,
              const gpu::FloatImage* mask, bool effect) {
  std::vector<double> d;
  double sumA = 0.0, sumB = 0.0, sumRef = 0.0, sumRefSq = 0.0;
  for (std::size_t i = 0; i < refWith.rgb.size() / 3; ++i) {
    if (mask && mask->rgb[3 * i] < 0.5f) continue;
    double di = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t k = 3 * i + c;
      const double ref = effect ? double(refWith.rgb[k]) - double(refWithout.rgb[k]) : double(refWith.rgb[k]);
      const double ea = (effect ? double(a.with.rgb[k]) - double(a.without.rgb[k]) : double(a.with.rgb[k])) - ref;
      const double eb = (effect ? double(b.with.rgb[k]) - double(b.without.rgb[k]) : double(b.with.rgb[k])) - ref;
      di += ea * ea - eb * eb;
      sumA += ea * ea, sumB += eb * eb, sumRef += ref, sumRefSq += ref * ref;
    }
    d.push_back(di);
  }
  Paired p;
  p.pixels = d.size();
  if (d.size() < 2 || !(sumRefSq > 0.0)) return p;
  double mean = 0.0, var = 0.0;
  for (double v : d) mean += v;
  p.sum = mean;
  mean /= double(d.size());
  for (double v : d) var += (v - mean) * (v - mean);
  var /= double(d.size() - 1);
  p.z = var > 0.0 ? mean / std::sqrt(var / double(d.size())) : 0.0;
  std::sort(d.begin(), d.end(), [](double x, double y) { return std::abs(x) < std::abs(y); });
  const std::size_t keep = d.size() - d.size() / 50;
  for (std::size_t i = 0; i < keep; ++i) p.trimmedSum += d[i];
  // The report's metrics: effect RMS error over the reference effect's RMS (ref::objectEffectError),
  // image RMS error over the reference's mean (ref::relativeRmse).
  const double n = 3.0 * double(d.size());
  const double scale = effect ? std::sqrt(sumRefSq / n) : sumRef / n;
  p.relativeA = std::sqrt(sumA / n) / scale;
  p.relativeB = std::sqrt(sumB / n) / scale;
  return p;
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

  // The two thinnest margins above (improved vs paper, indirect-only: 0.0064; DNRT vs the relit
  // probes, whole image: 0.0024), paired pixel by pixel (Paired): each must rest on the image, not on
  // a few pixels — z ≥ 3 and the sign kept without the 2 % of pixels with the largest |d|. Measured
  // (lavapipe): z 6.50 over 3669 indirect-only pixels, 12.50 and 12.36 over the image; the trimmed
  // sums keep 62 %, 51 % and 51 % of the whole.
  const std::filesystem::path dir = paper.heatMap.parent_path();
  const gpu::FloatImage refWith = gpu::readPfm(dir / "reference-all-with.pfm");
  const gpu::FloatImage refWithout = gpu::readPfm(dir / "reference-all-without.pfm");
  const gpu::FloatImage mask = gpu::readPfm(dir / "mask-indirect-only.pfm");
  const RowImages paperImages = imagesOf(paper), improvedImages = imagesOf(improved), relitImages = imagesOf(relit);
  const Paired antiRadiance = paired(paperImages, improvedImages, refWith, refWithout, &mask, true);
  const Paired wholePaper = paired(relitImages, paperImages, refWith, refWithout, nullptr, false);
  const Paired wholeImproved = paired(relitImages, improvedImages, refWith, refWithout, nullptr, false);
  for (const auto& [what, p] : {std::pair{"improved vs paper, indirect-only effect", antiRadiance},
                                std::pair{"dnrt paper vs relit probes, whole image", wholePaper},
                                std::pair{"dnrt improved vs relit probes, whole image", wholeImproved}})
    std::printf("paired %s: %zu pixels, errors %.4f -> %.4f, z %.2f, sum of d %.4g, without the largest 2 %% %.4g\n",
                what, p.pixels, p.relativeA, p.relativeB, p.z, p.sum, p.trimmedSum);
  // The paired metrics are the report's own (same sums): a check that the images read are the rows'.
  EXPECT_NEAR(antiRadiance.relativeA, paper.indirectEffectRelRmse, 1e-6);
  EXPECT_NEAR(antiRadiance.relativeB, improved.indirectEffectRelRmse, 1e-6);
  EXPECT_NEAR(wholePaper.relativeA, relit.relRmse, 1e-6);
  EXPECT_NEAR(wholePaper.relativeB, paper.relRmse, 1e-6);
  for (const Paired* p : {&antiRadiance, &wholePaper, &wholeImproved}) {
    EXPECT_GE(p->z, 3.0);
    EXPECT_GT(p->trimmedSum, 0.0);
  }
}

}  // namespace
}  // namespace bounce::game
