#include "game/accuracy_rows.hpp"

#include <algorithm>
#include <cstdio>

namespace bounce::game {
namespace {

// Direct light with shadow maps. Its own passes are the shadow atlas and the lighting pass (the
// G-buffer is shared by every technique, the tonemap is display). Compared with three references:
// bounces 0 is what it simulates (the two agree up to shadow-map edges: tests/unit/ref
// raster_match_test), the full one shows what leaving out indirect light costs, and the one-bounce
// one is the baseline of the VLM rows (what a single diffuse bounce has to close).
void addDirect(std::vector<AccuracyRow>& rows) {
  for (const int bounces : {0, -1, 1}) {  // −1: the full reference
    AccuracyRow r;
    r.technique = "direct";
    r.setting = bounces == 0 ? "ref=direct" : bounces == 1 ? "ref=1bounce" : "ref=all";
    r.effects = {"direct", "shadows"};
    if (bounces >= 0) r.referenceBounces = bounces;
    r.passes = {"shadow", "lighting"};
    rows.push_back(std::move(r));
  }
}

}  // namespace

std::vector<AccuracyRow> accuracyRows() {
  std::vector<AccuracyRow> rows;
  addDirect(rows);
  for (const gi::Technique* t : gi::techniques()) t->accuracyRows(rows);
  return rows;
}

std::vector<AccuracyRow> accuracyRows(const std::vector<std::string>& techniques) {
  std::vector<AccuracyRow> rows = accuracyRows();
  if (techniques.empty()) return rows;
  std::erase_if(rows, [&](const AccuracyRow& r) {
    return std::find(techniques.begin(), techniques.end(), r.technique) == techniques.end();
  });
  return rows;
}

bool rowAvailable(const AccuracyRow& row, const std::vector<std::string>& executedPasses) {
  return std::all_of(row.passes.begin(), row.passes.end(), [&](const std::string& p) {
    return std::find(executedPasses.begin(), executedPasses.end(), p) != executedPasses.end();
  });
}

double rowGpuMs(const AccuracyRow& row, const std::vector<PassStats>& stats) {
  const auto named = [&](const std::string& pass) {
    return std::find(row.passes.begin(), row.passes.end(), pass) != row.passes.end() ||
           std::find(row.optionalPasses.begin(), row.optionalPasses.end(), pass) != row.optionalPasses.end();
  };
  double ms = 0.0;
  for (const PassStats& s : stats)
    if (s.depth == 0 && s.pass != "frame" && named(s.pass)) ms += s.medianMs;
  return ms;
}

}  // namespace bounce::game
