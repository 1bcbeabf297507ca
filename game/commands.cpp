#include "game/commands.hpp"

#include <climits>

#include "game/play_controls.hpp"

namespace bounce::game {

const std::vector<cli::CommandSpec>& commandSpecs() {
  static const cli::OptionSpec device{"--device", "NAME", "Vulkan device (substring of its name; also BOUNCE_DEVICE)"};
  static const cli::OptionSpec effects{"--effects", "LIST", "replace the level's effects, e.g. direct,shadows"};
  static const std::vector<cli::CommandSpec> specs = {
      // The key map continues the summary, indented to the overview's column.
      {"play", "LEVEL [options]",
       "open a window on a level: fly camera (WASD + mouse), effect and debug-view keys, GPU overlay\n" +
           keyMapSummary(std::string(14, ' ')),
       {device, effects,
        {"--frames", "N", "quit after N frames"},
        {"--screenshot", "FILE", "save the last presented frame as PNG (with --frames)"},
        {"--resolution", "WxH", "window size (default 1280x720)"},
        {"--vsync", "on|off", "present with vsync (default on)"},
        {"--overlay", "on|off", "GPU-timing overlay (default on; off with --screenshot)"},
        {"--keys", "KEY@FRAME,...", "press keys at given frames (scripted demos and tests), e.g. 2@0,F3@30"}},
       1, 1},
      {"capture", "SCRIPT --out DIR [options]", "headless scripted capture: PNG + PFM per captured frame, timings.json",
       {device, effects, {"--out", "DIR", "output folder (created)"}, {"--resolution", "WxH", "override the script's resolution"}},
       1, 1},
      {"profile", "LEVEL [options]", "per-pass GPU time (median and p95 over many frames)",
       {device, effects,
        {"--frames", "N", "measured frames (default 60, after 5 warm-up frames)"},
        {"--resolution", "WxH", "render size (default 1280x720)"},
        {"--csv", "FILE", "also write pass,object,frames,median_ms,p95_ms"}},
       1, 1},
      {"graph", "LEVEL --dot FILE [options]", "write the level's compiled render graph as Graphviz DOT",
       {effects, {"--dot", "FILE", "output file"}, {"--no-cull", "", "keep passes whose outputs nothing reads"},
        {"--resolution", "WxH", "render size (default 1280x720)"}},
       1, 1},
      {"cook", "FILE... [--out DIR]", "cook glTF/glb files (or every asset of a level .json) into the content cache",
       {{"--out", "DIR", "cache folder (default: BOUNCE_COOK_CACHE or <build>/cooked)"}}, 1, SIZE_MAX},
      {"reference", "(LEVEL|SCRIPT) --out FILE.pfm [options]",
       "path-traced ground truth of one frame (linear PFM), cached under <build>/reference",
       {effects,
        {"--out", "FILE", "output PFM (linear radiance)"},
        {"--frame", "N", "simulation time N·dt (a script's dt, else 1/60 s); default 0"},
        {"--spp", "N", "samples per pixel (default 64)"},
        {"--bounces", "N", "indirect bounces: 0 = direct light only (default unlimited, Russian roulette)"},
        {"--resolution", "WxH", "image size (default: the script's, else 256x256)"}},
       1, 1},
      {"demo", "[options]", "the README's first command: play the default level with a display, else capture + profile it",
       {device, {"--out", "DIR", "capture folder when headless (default build/demo)"}}, 0, 0},
      {"accuracy", "LEVEL [options]",
       "every technique configuration vs the path-traced reference: accuracy.csv, error-vs-GPU-ms chart, heat maps",
       {device,
        {"--out", "DIR", "output folder (default ./accuracy)"},
        {"--spp", "N", "reference samples per pixel (default 64; the direct-only reference is exact with 1)"},
        {"--resolution", "WxH", "image size (default 256x256)"},
        {"--frame", "N", "simulation time N/60 s (default 0)"},
        {"--frames", "N", "timed frames per configuration (default 20, after 5 warm-up frames)"},
        {"--rows", "LIST", "only these techniques' rows, e.g. direct,probes,dnrt (default: every row)"}},
       1, 1},
      {"bake", "LEVEL [options]", "precompute what the effects need (probes, DNRT fields) into the caches; one line per bake",
       {effects, {"--force", "", "re-bake even when the cache holds a valid entry (to time a bake)"}}, 1, 1},
      {"export", "LEVEL OUT.glb [--time T]", "write the composed level as one glTF 2.0 binary (meshes, materials, cameras, lights)",
       {{"--time", "T", "simulation time in seconds at which dynamic props are placed (default 0)"}}, 2, 2},
      {"bench", "vlm-grid|dnrt [options]",
       "vlm-grid: time the VLM grid builds (scatter vs gather); dnrt: the DNRT paper's Tables 6-8 (GPU ms, ratios)",
       {{"--lights", "N", "virtual lights (default 10000)"},
        {"--grid", "G", "cells per axis (default 50)"},
        {"--k", "K", "candidates per cell (default 32)"},
        {"--range", "R", "active-hemisphere range (default 2.5)"},
        {"--runs", "N", "builds per timing; the median is printed (default 3)"},
        {"--no-gather", "", "skip the gather build (it is O(cells × lights))"},
        // bench dnrt (game/bench_dnrt.hpp)
        device,
        {"--levels", "LIST", "dnrt: Table 8 levels, names in content/levels or .json (default cornell-1,cornell-5,cornell-10)"},
        {"--variant-levels", "LIST", "dnrt: levels for the SH/grid/intrusion/mode rows (default cornell-1,cornell-10; none)"},
        {"--resolution", "WxH", "dnrt: render size (default 1280x720)"},
        {"--frames", "N", "dnrt: measured frames per session (default 30, after 5 warm-up frames)"},
        {"--rays", "N", "dnrt: bake rays per grid vertex for every field (a square; default each entity's)"},
        {"--csv", "FILE", "dnrt: also write the rows as CSV"}},
       1, 1},
  };
  return specs;
}

GpuOptions gpuOptions(const cli::Args& args) { return {args.str("--device"), false}; }

}  // namespace bounce::game
