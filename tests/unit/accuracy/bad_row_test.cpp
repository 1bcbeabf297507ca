// `bounce accuracy` with a row whose settings make a level its technique refuses (bad input, one
// line): the row is skipped with a note holding that line and the run goes on to the next row,
// instead of the whole run stopping at the first such row.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/gpu/testing.hpp"
#include "game/accuracy.hpp"
#include "game/accuracy_rows.hpp"

namespace bounce::game {
namespace {

// cornell-1's SL prop twice at 64 spheres with the hierarchy: 128 spheres + 2 parents, beyond pass
// 2's 128 (engine/gi/sl/technique.cpp create()), then the direct row, which runs.
TEST(AccuracyBadRow, IsSkippedWithItsLineAndTheRunGoesOn) {
  AccuracyRow bad;
  bad.technique = "sl";
  bad.setting = "spheres=64x2;hierarchy=on;ref=all";
  bad.effects = {"direct", "shadows", "sl"};
  bad.passes = {"shadow", "lighting", "sl.intensity", "sl"};
  bad.configure = [](scene::Level& level) {
    std::vector<scene::EntityDesc> copies;
    for (scene::EntityDesc& e : level.entities)
      if (e.sl) {
        e.sl->spheres = 64;
        e.sl->hierarchy = true;
        e.sl->blockedMap = false;  // the SH: the maps' 64-SL cap would refuse the row first (cornell-1 reads them)
        copies.push_back(e);
        copies.back().id += "-copy";
      }
    for (const scene::EntityDesc& c : copies) level.entities.push_back(c);
  };
  std::vector<AccuracyRow> rows{bad};
  const std::vector<AccuracyRow> direct = accuracyRows({"direct"});
  ASSERT_FALSE(direct.empty());
  rows.push_back(direct.front());

  AccuracyOptions o;
  o.level = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
  o.out = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "bad-row";
  o.spp = 4;
  o.width = o.height = 16;
  o.measuredFrames = 1;
  o.referenceCache = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "reference";
  o.cookCache = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "cooked";
  o.progress = false;
  o.chart = false;
  o.rows = rows;
  const AccuracyReport report = runAccuracy(o);

  ASSERT_EQ(report.rows.size(), 1u);
  EXPECT_EQ(report.rows[0].row.technique, direct.front().technique);
  EXPECT_EQ(report.rows[0].row.setting, direct.front().setting);
  const std::string expected = "skipped sl spheres=64x2;hierarchy=on;ref=all: bad input: " +
                               std::filesystem::absolute(o.level).lexically_normal().string() +
                               ": /entities/";
  const auto note = std::find_if(report.notes.begin(), report.notes.end(),
                                 [](const std::string& n) { return n.starts_with("skipped sl "); });
  ASSERT_NE(note, report.notes.end());
  EXPECT_TRUE(note->starts_with(expected)) << *note;
  EXPECT_TRUE(note->ends_with("/sl/hierarchy: true with 128 sl spheres + 2 parents (expected at most 128 in all "
                              "with the hierarchy: one parent per entity)"))
      << *note;
}

}  // namespace
}  // namespace bounce::game
