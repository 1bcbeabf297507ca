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

// The baked irradiance volume (engine/gi/probes, issue 3 §3): two probe spacings × two SH orders,
// on top of direct light, against the full reference. Spacing and order reach the bake through
// the level's "probes" settings (`configure`).
void addProbes(std::vector<AccuracyRow>& rows) {
  for (const double spacing : {0.25, 0.125})  // metres; the Cornell box is 0.55 m wide
    for (const int order : {2, 3}) {          // SH order as bands: 2 = L1 (4 coefficients), 3 = L2 (9)
      AccuracyRow r;
      r.technique = "probes";
      char setting[96];
      std::snprintf(setting, sizeof setting, "spacing=%gm;sh_order=%d;ref=all", spacing, order);
      r.setting = setting;
      r.effects = {"direct", "shadows", "probes"};
      r.passes = {"shadow", "lighting", "probes"};
      r.configure = [spacing, order](scene::Level& level) {
        level.probes.spacing = float(spacing);
        level.probes.order = order;
      };
      rows.push_back(std::move(r));
    }
}

// The DNRT paper's baselines (§6.4): screen-space AO darkening the probes' indirect light around
// every object, dynamic ones included. Same probes as the DNRT rows (level defaults).
void addAo(std::vector<AccuracyRow>& rows) {
  for (const char* kind : {"ssao", "hbao"}) {
    AccuracyRow r;
    r.technique = kind;
    r.setting = "radius=0.1m;ref=all";
    r.effects = {"direct", "shadows", "probes", kind};
    r.passes = {"shadow", "lighting", kind, "probes"};
    rows.push_back(std::move(r));
  }
}

// DNRT (engine/gi/dnrt, issue 4) on top of probes: what the dynamic objects add and take away,
// for every field setting the paper's tables vary: SH count (Table 7), grid resolution, intrusion
// (Table 6) and the anti-radiance of Eq. 12 vs App. B.2. Applied to every `dnrt` entity. Its
// effect_rel_rmse is the number that matters (the static part is the probes').
void addDnrt(std::vector<AccuracyRow>& rows) {
  for (const int shCount : {4, 9})
    for (const int grid : {16, 32, 64})
      for (const bool intrusion : {false, true})
        for (const bool improved : {false, true}) {
          AccuracyRow r;
          r.technique = "dnrt";
          r.setting = "sh=" + std::to_string(shCount) + ";grid=" + std::to_string(grid) +
                      ";intrusion=" + (intrusion ? "on" : "off") + ";anti_radiance=" + (improved ? "improved" : "paper") +
                      ";ref=all";
          r.effects = {"direct", "shadows", "probes", "dnrt"};
          r.passes = {"shadow", "lighting", "probes", "dnrt"};
          r.optionalPasses = {"dnrt.cube"};  // the intrusion maps (one outermost pass per object)
          r.configure = [=](scene::Level& level) {
            for (auto& e : level.entities)
              if (e.dnrt) {
                e.dnrt->shCount = shCount;
                e.dnrt->grid = grid;
                e.dnrt->intrusion = intrusion;
                e.dnrt->improvedAntiRadiance = improved;
              }
          };
          rows.push_back(std::move(r));
        }
}

// Virtual Light Meshes (engine/gi/vlm, issue 5 §7): the thesis's range parameter (Fig. 5.6: too
// small a range leaves blocky cut-offs) × candidates per cell K (Table 5.3), on top of direct
// light. A VLM simulates exactly one diffuse bounce (§3.6), so it is compared with the one-bounce
// reference. Range and K reach the grid through the level's "vlm" settings.
void addVlm(std::vector<AccuracyRow>& rows) {
  for (const double range : {1.5, 2.5, 3.5, 4.5})
    for (const int k : {10, 20, 30, 60}) {
      AccuracyRow r;
      r.technique = "vlm";
      char setting[96];
      std::snprintf(setting, sizeof setting, "range=%g;k=%d;ref=1bounce", range, k);
      r.setting = setting;
      r.effects = {"direct", "shadows", "vlm"};
      r.referenceBounces = 1;
      r.passes = {"shadow", "lighting", "vlm.lights", "vlm"};
      r.configure = [range, k](scene::Level& level) {
        level.vlm.range = float(range);
        level.vlm.k = k;
      };
      rows.push_back(std::move(r));
    }
}

}  // namespace

std::vector<AccuracyRow> accuracyRows() {
  std::vector<AccuracyRow> rows;
  addDirect(rows);
  addProbes(rows);
  addAo(rows);
  addDnrt(rows);
  addVlm(rows);
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
