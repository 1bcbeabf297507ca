#pragma once
// `bounce bench dnrt`: the DNRT paper's performance tables from one command, measured with the
// GPU timestamps of `bounce profile` (median over --frames frames of the levels' scripted motion,
// after kWarmupFrames):
//
//  - Table 8 analogue, per level (default cornell-1, -5, -10): ONE session with DNRT, SSAO and HBAO
//    all on (the level's effects plus ssao, hbao), so the three methods' costs are measured side
//    by side over the same frames: frame ms, DNRT ms (the "dnrt" pass), mean per-object DNRT ms,
//    SSAO ms, HBAO ms. Each level twice: in its own modes ("all") and with every object in the
//    clustered draw ("clustered", issue 15), which has no per-object scopes (objects = the level's);
//    and both again with the draw at half resolution ("half", "clustered half": the level's "dnrt":
//    {"resolution": "half"}, issue 15 part 3); with every object fused ("fused": the probes pass adds
//    every visible object's term, up to 32) and, on a level with one DNRT object, at half and quarter
//    resolution ("fused half", "fused quarter": pass dnrt.fused.reduced and its bilinear blend, README
//    "DNRT's fused term at reduced resolution, session 17"; with several objects in the probes pass the
//    terms are shaded at full resolution, so those rows would be "fused" again: table8Settings). A fused
//    row's DNRT is a marginal: its own passes plus its probes pass less the same pass without the term,
//    drawn in the same frames ("probes.baseline", gi::probes::ProbeNode::setTermBaseline) and paired
//    frame by frame (TimingCollector::pairedPercentileMs); the row's frame time leaves that pass out.
//  - Tables 6 and 7 and the grid and mode comparisons, per variant level (default cornell-1,
//    cornell-10): DNRT alone (the level's effects), once with the paper's standard configuration
//    (sh=4, grid=32, intrusion off; the outer-cube raster) and once per changed setting: sh=9
//    (Table 7), grid=16 and grid=64, intrusion=on (Table 6: its cube maps are the "dnrt.cube"
//    passes, reported apart from the shader), mode=fullscreen (the paper's full-screen pass),
//    mode=clustered (one draw for all objects, issue 15), resolution=half (the draw at half
//    resolution and its upsample).
//    Settings reach every `dnrt` entity as in `bounce accuracy` (accuracy_rows.cpp).
//  - The goal ratios of issue #4: DNRT(1 object)/SSAO ≤ 0.1, DNRT(10)/DNRT(1) ≤ 5, 9 SH/4 SH ≤ 1.5;
//    of issue 15 for the clustered rows: DNRT(1)/SSAO ≤ 0.05, DNRT(10)/DNRT(1) ≤ 4; DNRT(1)/SSAO at
//    half resolution (box and clustered, the same goals); and for reference intrusion/basic,
//    fullscreen/box, clustered/box, grid 16, 64 against 32 and half / full resolution.
//
// Fields are baked through the DNRT cache (<build>/dnrt) before each session; the seconds spent
// baking are reported per row, apart from the timings. Timings are not tested (DESIGN.md): the
// structure of the report is (tests/unit/dnrt/bench_gpu_test.cpp).
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace bounce::game {

struct DnrtBenchOptions {
  std::vector<std::filesystem::path> levels;         // Table 8 rows
  std::vector<std::filesystem::path> variantLevels;  // Table 6/7, grid and mode rows
  std::uint32_t width = 1280, height = 720;
  int frames = 30;                  // measured frames per session
  std::optional<int> raysPerVertex;  // a square; empty: each entity's own "rays"
  std::string device;
  // Settings (DnrtBenchRow::setting) whose sessions are left out, with their ratios: the test's way
  // to keep the report's structure checked at fewer sessions (CI time). Empty for the command.
  std::vector<std::string> skipSettings;
};

// One measured session. Times are medians in ms; NaN where the pass did not run.
struct DnrtBenchRow {
  std::string table;    // "8" (all methods) or "variant"
  std::string level;    // the level file's stem
  std::string setting;  // Table 8: "all", "clustered", "half", "clustered half", "fused", "fused half" or "fused quarter"; variants: "basic" or the changed setting ("sh=9", …)
  int objects = 0;      // DNRT objects timed (per-object scopes seen; clustered: the level's dnrt entities)
  double frameMs = 0.0;
  double dnrtMs = 0.0;       // the "dnrt" pass (every object's draw inside it) + "dnrt.combine" (+ "dnrt.upsample");
                             // "fused…": "dnrt.combine" (+ "dnrt.fused.reduced") + "dnrt" (objects left to it) + this row's
                             // "probes" − "probes.baseline", the median of their per-frame differences (the term's
                             // marginal cost in the probes pass)
  double perObjectMs = 0.0;  // mean of the per-object "dnrt/<object>" medians (NaN when clustered)
  double cubeMs = 0.0;       // the intrusion maps: sum of the "dnrt.cube/<object>" passes (0 when off)
  double ssaoMs = 0.0, hbaoMs = 0.0;
  double probesMs = 0.0;     // the "probes" pass (NaN when the level has no probes; "fused": with the object's term)
  double baseProbesMs = std::numeric_limits<double>::quiet_NaN();  // "fused…": "probes.baseline", the probes pass without the term in the same frames; NaN elsewhere
  // "fused…": the term's marginal in the probes pass, "probes" − "probes.baseline" over frames: its median
  // (part of dnrtMs) and quartiles, how well one run resolves it. NaN elsewhere.
  double termMs = std::numeric_limits<double>::quiet_NaN();
  double termQ1Ms = std::numeric_limits<double>::quiet_NaN(), termQ3Ms = std::numeric_limits<double>::quiet_NaN();
  int fieldsBaked = 0;       // fields missing from the cache before this session
  double bakeSeconds = 0.0;  // time spent baking them
};

struct DnrtBenchRatio {
  std::string name;
  double value = 0.0;  // NaN when a row it needs is missing
  double goal = 0.0;   // the bound, 0 when the ratio is only reported
};

struct DnrtBenchReport {
  std::string device;
  std::vector<DnrtBenchRow> rows;
  std::vector<DnrtBenchRatio> ratios;
};

// Validates every level and option first (InputError), then runs the sessions.
DnrtBenchReport runDnrtBench(const DnrtBenchOptions& options);
// The tables and ratios for the terminal.
std::string formatDnrtBench(const DnrtBenchReport& report, const DnrtBenchOptions& options);
// CSV, header exactly
// "table,level,setting,objects,frame_ms,dnrt_ms,per_object_ms,cube_ms,ssao_ms,hbao_ms,fields_baked,bake_s,probes_ms,base_probes_ms,term_ms,term_q1_ms,term_q3_ms".
std::string formatDnrtBenchCsv(const DnrtBenchReport& report);

// The Table 8 settings, in the order measured, of a level with `dnrtEntities` DNRT objects: "all",
// "fused", "fused half" and "fused quarter" (one object only), "clustered", "half", "clustered half".
std::vector<std::string> table8Settings(int dnrtEntities);

// "cornell-1" → <source>/content/levels/cornell-1.json; a path ending in .json is taken as is.
std::filesystem::path benchLevelPath(const std::string& name);

}  // namespace bounce::game
