// A row's gpu_ms from synthetic timings (rowGpuMs): whole passes add up, per-object scopes nested in
// a pass are not counted twice, and per-object intrusion passes ("dnrt.cube/<object>") count
// without being required.
#include <gtest/gtest.h>

#include "game/accuracy_rows.hpp"

namespace bounce::game {
namespace {

// Timings as TimingCollector::stats() reports them for one DNRT frame with two objects, one of them
// with intrusion: pass, object, frames, median, p95, depth. Values are binary fractions, so the
// sums below are exact.
std::vector<PassStats> dnrtFrame(bool intrusion) {
  std::vector<PassStats> s = {
      {"shadow", "", 10, 1.0, 1.5, 0},
      {"gbuffer", "", 10, 8.0, 9.0, 0},
      {"lighting", "", 10, 2.0, 2.5, 0},
      {"probes", "", 10, 0.5, 0.75, 0},
      {"dnrt.combine", "", 10, 0.125, 0.25, 0},  // Σ_j c_j M_j per grid vertex, before the draws
      {"dnrt", "", 10, 4.0, 4.5, 0},
      {"dnrt", "prop-a", 10, 1.5, 2.0, 1},  // inside "dnrt": already counted
      {"dnrt", "prop-b", 10, 2.25, 2.5, 1},
      {"tonemap", "", 10, 0.25, 0.5, 0},
  };
  if (intrusion) s.insert(s.begin() + 3, PassStats{"dnrt.cube", "prop-a", 10, 16.0, 17.0, 0});
  s.push_back({"frame", "", 10, 99.0, 99.0, 0});
  return s;
}

AccuracyRow dnrtRow() {
  for (const AccuracyRow& r : accuracyRows({"dnrt"}))
    if (r.setting.find("intrusion=on") != std::string::npos) return r;
  throw std::runtime_error("no intrusion=on dnrt row");
}

TEST(AccuracyGpuMs, NestedPerObjectScopesAreNotCountedTwice) {
  const AccuracyRow row = dnrtRow();
  // shadow + lighting + probes + dnrt.combine + dnrt; not gbuffer/tonemap (shared), not the nested objects.
  EXPECT_EQ(rowGpuMs(row, dnrtFrame(false)), 1.0 + 2.0 + 0.5 + 0.125 + 4.0);
}

TEST(AccuracyGpuMs, IntrusionPassesCountWithoutBeingRequired) {
  const AccuracyRow row = dnrtRow();
  EXPECT_EQ(rowGpuMs(row, dnrtFrame(true)), 1.0 + 2.0 + 0.5 + 0.125 + 4.0 + 16.0);
  // Availability needs only the required passes: the frame without intrusion maps runs the row.
  EXPECT_TRUE(rowAvailable(row, {"shadow", "gbuffer", "lighting", "probes", "dnrt.combine", "dnrt", "tonemap"}));
  EXPECT_FALSE(rowAvailable(row, {"shadow", "gbuffer", "lighting", "probes", "dnrt", "tonemap"}));  // no combine
  EXPECT_FALSE(rowAvailable(row, {"shadow", "gbuffer", "lighting", "probes", "dnrt.cube/prop-a", "tonemap"}));
}

TEST(AccuracyGpuMs, EveryDnrtRowCountsTheIntrusionMaps) {
  for (const AccuracyRow& r : accuracyRows({"dnrt"})) {
    EXPECT_EQ(r.optionalPasses, std::vector<std::string>{"dnrt.cube"}) << r.setting;
    EXPECT_EQ(rowGpuMs(r, dnrtFrame(true)), 23.625) << r.setting;
  }
}

TEST(AccuracyGpuMs, OtherTechniquesSumTheirOwnWholePasses) {
  AccuracyRow row;
  row.passes = {"shadow", "lighting"};
  EXPECT_EQ(rowGpuMs(row, dnrtFrame(true)), 3.0);
  row.passes = {"frame"};  // the frame total is never a lighting pass
  EXPECT_EQ(rowGpuMs(row, dnrtFrame(true)), 0.0);
  EXPECT_EQ(rowGpuMs(row, {}), 0.0);
}

}  // namespace
}  // namespace bounce::game
