// `bounce bench dnrt` at a tiny size: the report's structure, never its speed (no timed tests):
// every row present in order, every timed pass measured (> 0 ms), the intrusion maps only where
// intrusion is on, and every ratio finite with the goals attached.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "engine/gpu/testing.hpp"
#include "game/bench_dnrt.hpp"
#include "game/timing_stats.hpp"

namespace bounce::game {
namespace {

TEST(DnrtBench, ReportHasEveryRowTimedAndFiniteRatios) {
  DnrtBenchOptions o;
  o.levels = {benchLevelPath("cornell-1")};
  o.variantLevels = {benchLevelPath("cornell-1")};
  o.width = 64, o.height = 36;
  o.frames = 2;
  o.raysPerVertex = 2;  // 4 rays per vertex: the 64³ field bakes in about a second
  // One reduced-resolution session only (CI time): "clustered half" and the variant "resolution=half"
  // run the same half-resolution path as Table 8's "half"; their ratios go with them.
  // Of the fused rows (the probes pass with DNRT's term) only "fused quarter", whose marginal is measured
  // against "probes.baseline" in the same frames; "fused" and "fused half" are left out (CI time):
  // DnrtGpu.FusedModeIsTheBoxImageInsideTheProbesPass covers the mode.
  o.skipSettings = {"clustered half", "resolution=half", "fused", "fused half"};
  const DnrtBenchReport r = runDnrtBench(o);

  const std::vector<std::string> settings = {"all",          "fused quarter",   "clustered",     "half",          "basic",
                                             "sh=9",         "grid=16",         "grid=64",       "intrusion=on",
                                             "mode=fullscreen", "mode=clustered"};
  ASSERT_EQ(r.rows.size(), settings.size());
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const DnrtBenchRow& row = r.rows[i];
    EXPECT_EQ(row.setting, settings[i]);
    EXPECT_EQ(row.table, i < 4 ? "8" : "variant");
    const bool fused = row.setting.starts_with("fused");
    const bool clustered = row.setting.starts_with("clustered") || row.setting == "mode=clustered";
    EXPECT_EQ(row.level, "cornell-1");
    EXPECT_EQ(row.objects, 1) << row.setting << ": the prop is drawn in every frame";
    EXPECT_GT(row.frameMs, 0.0) << row.setting;
    if (fused) {
      // A marginal (its passes + probes − probes.baseline, frame by frame): finite, but at 64×36 its sign is noise.
      EXPECT_TRUE(std::isfinite(row.dnrtMs)) << row.setting;
      EXPECT_GT(row.baseProbesMs, 0.0) << row.setting << ": the probes pass without the term, in the same frames";
      EXPECT_TRUE(std::isfinite(row.termQ1Ms) && std::isfinite(row.termQ3Ms)) << row.setting << ": measured";
      EXPECT_LE(row.termQ1Ms, row.termMs) << row.setting << ": the term's quartiles over frames";
      EXPECT_LE(row.termMs, row.termQ3Ms) << row.setting;
      EXPECT_TRUE(std::isnan(row.perObjectMs)) << row.setting << ": the term has no scope of its own";
      EXPECT_EQ(row.objects, 1);
      EXPECT_GT(row.ssaoMs, 0.0);
      EXPECT_GT(row.hbaoMs, 0.0);
      continue;
    }
    EXPECT_TRUE(std::isnan(row.baseProbesMs)) << row.setting << ": only fused rows have a baseline";
    EXPECT_TRUE(std::isnan(row.termMs) && std::isnan(row.termQ1Ms) && std::isnan(row.termQ3Ms)) << row.setting;
    EXPECT_GT(row.dnrtMs, 0.0) << row.setting;
    if (clustered) {
      EXPECT_TRUE(std::isnan(row.perObjectMs)) << row.setting << ": one draw for all objects, no scope per object";
    } else {
      EXPECT_GT(row.perObjectMs, 0.0) << row.setting;
      EXPECT_LE(row.perObjectMs, row.dnrtMs) << row.setting << ": the object's scope lies inside the pass";
    }
    EXPECT_GE(row.bakeSeconds, 0.0);
    if (row.setting == "intrusion=on")
      EXPECT_GT(row.cubeMs, 0.0);
    else
      EXPECT_EQ(row.cubeMs, 0.0) << row.setting;
    if (row.table == "8") {
      EXPECT_GT(row.ssaoMs, 0.0);
      EXPECT_GT(row.hbaoMs, 0.0);
    } else {
      EXPECT_TRUE(std::isnan(row.ssaoMs)) << row.setting << ": DNRT alone";
    }
  }
  const std::vector<std::pair<std::string, double>> goals = {
      {"DNRT(1 obj) / SSAO, cornell-1", 0.1},          {"DNRT(1 obj) clustered / SSAO, cornell-1", 0.05},
      {"9 SH / 4 SH, cornell-1", 1.5},                  {"fullscreen / box, cornell-1", 0.0},
      {"clustered / box, cornell-1", 0.0},
      {"DNRT(1 obj) half / SSAO, cornell-1", 0.1},     {"DNRT(1 obj) fused quarter / SSAO, cornell-1", 0.05},
      {"fused quarter / box (in SSAO units), cornell-1", 0.0}};
  for (const auto& [name, goal] : goals) {
    bool found = false;
    for (const DnrtBenchRatio& q : r.ratios)
      if (q.name == name) {
        found = true;
        EXPECT_EQ(q.goal, goal) << name;
      }
    EXPECT_TRUE(found) << name;
  }
  // DNRT/SSAO, DNRT/HBAO, clustered DNRT/SSAO, DNRT/SSAO at half, fused quarter DNRT/SSAO and / box (one
  // Table 8 level) + 8 per variant level (9 less the left-out "half / full resolution")
  for (const DnrtBenchRatio& q : r.ratios) EXPECT_EQ(q.name.find("clustered half"), std::string::npos) << q.name;
  EXPECT_EQ(r.ratios.size(), 6u + 8u);
  for (const DnrtBenchRatio& q : r.ratios)  // the fused ones are marginals: finite, their sign noise at 64×36
    EXPECT_TRUE(std::isfinite(q.value) && (q.value > 0.0 || q.name.find("fused") != std::string::npos)) << q.name;

  std::istringstream csv(formatDnrtBenchCsv(r));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line,
            "table,level,setting,objects,frame_ms,dnrt_ms,per_object_ms,cube_ms,ssao_ms,hbao_ms,fields_baked,bake_s,probes_ms,base_probes_ms,"
            "term_ms,term_q1_ms,term_q3_ms");
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, int(settings.size()));
  EXPECT_NE(formatDnrtBench(r, o).find("goal <= 0.1"), std::string::npos);
}

// A fused row's marginal is the median of the per-frame differences "probes" − "probes.baseline", not the
// difference of the two medians. Here the term costs exactly 4 ms in every frame; a slower host adds 15 ms
// to both passes in frames 1 and 2, and in frame 3 a burst of load catches the probes pass but not the
// baseline drawn beside it. The medians' difference reads 19 ms (49 − 30: the two medians come from different frames),
// the paired median 4.
TEST(DnrtBench, FusedMarginalIsThePairedMedianOverFrames) {
  TimingCollector t;
  const double baseline[] = {30.0, 45.0, 45.0, 30.0, 30.0};
  const double probes[] = {34.0, 49.0, 49.0, 49.0, 34.0};
  for (int i = 0; i < 5; ++i) t.addFrame({{"probes.baseline", 0, baseline[i]}, {"probes", 0, probes[i]}});
  double probesMedian = 0.0, baselineMedian = 0.0;
  for (const PassStats& s : t.stats()) {
    if (s.pass == "probes") probesMedian = s.medianMs;
    if (s.pass == "probes.baseline") baselineMedian = s.medianMs;
  }
  EXPECT_DOUBLE_EQ(probesMedian - baselineMedian, 19.0);
  EXPECT_DOUBLE_EQ(t.pairedPercentileMs("probes", "probes.baseline", 0.5), 4.0);
  // "frame" (the outermost scopes' sum) less the baseline, frame by frame: the frame as the level draws it.
  EXPECT_DOUBLE_EQ(t.pairedPercentileMs("frame", "probes.baseline", 0.5), probesMedian);
  // Frames without one of the two scopes are left out; none with both: NaN, never a number that looks measured.
  t.addFrame({{"probes", 0, 1000.0}});
  EXPECT_DOUBLE_EQ(t.pairedPercentileMs("probes", "probes.baseline", 0.5), 4.0);
  EXPECT_TRUE(std::isnan(t.pairedPercentileMs("probes", "ssao", 0.5)));
  // The frame less the baseline where it ran: the sixth frame (no baseline) counts whole. Frames 34, 49, 49,
  // 49, 34 and 1000: the nearest-rank median is the third of six, 49.
  EXPECT_DOUBLE_EQ(t.pairedPercentileMs("frame", "probes.baseline", 0.5, true), 49.0);
  EXPECT_DOUBLE_EQ(t.pairedPercentileMs("frame", "probes.baseline", 1.0, true), 1000.0);
  // Quartiles (nearest rank) of the differences 4, 4, 4, 19, 4: the burst lies past the upper one.
  EXPECT_DOUBLE_EQ(t.pairedPercentileMs("probes", "probes.baseline", 0.25), 4.0);
  EXPECT_DOUBLE_EQ(t.pairedPercentileMs("probes", "probes.baseline", 0.75), 4.0);
  EXPECT_DOUBLE_EQ(t.pairedPercentileMs("probes", "probes.baseline", 1.0), 19.0);
}

// The reduced fused rows only where they measure what they say: the reduced term serves one fused
// object, so a level with several (cornell-10) would run "fused half" / "fused quarter" at full
// resolution under those names (and give 10 : 1 ratios for them).
TEST(DnrtBench, ReducedFusedRowsOnlyForALevelWithOneObject) {
  const std::vector<std::string> one = {"all",       "fused", "fused half",    "fused quarter",
                                        "clustered", "half",  "clustered half"};
  const std::vector<std::string> several = {"all", "fused", "clustered", "half", "clustered half"};
  EXPECT_EQ(table8Settings(1), one);
  EXPECT_EQ(table8Settings(2), several);
  EXPECT_EQ(table8Settings(10), several);
}

}  // namespace
}  // namespace bounce::game
