#include "game/commands.hpp"

#include <climits>
#include <cstdio>

#include "engine/gpu/context.hpp"

#include "game/play_controls.hpp"

namespace bounce::game {

const std::vector<cli::CommandSpec>& commandSpecs() {
  static const cli::OptionSpec device{"--device", "NAME", "Vulkan device (substring of its name; also BOUNCE_DEVICE)"};
  static const cli::OptionSpec effects{"--effects", "LIST", "replace the level's effects, e.g. direct,shadows"};
  static const std::vector<cli::CommandSpec> specs = {
      // The key map continues the summary, indented to the overview's column.
      {"play", "(LEVEL|FILE.glb) [options]",
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
       {device, effects, {"--dot", "FILE", "output file"}, {"--no-cull", "", "keep passes whose outputs nothing reads"},
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
       {device, {"--out", "DIR", "capture folder when headless (default <build>/demo, e.g. build/release/demo)"}}, 0, 0},
      {"accuracy", "LEVEL [options]",
       "every technique configuration vs the path-traced reference: accuracy.csv, error-vs-GPU-ms chart, heat maps",
       {device,
        {"--out", "DIR", "output folder (default ./accuracy)"},
        {"--spp", "N", "reference samples per pixel (default 64; the direct-only reference is exact with 1)"},
        {"--resolution", "WxH", "image size (default 256x256)"},
        {"--frame", "N", "simulation time N/60 s (default 0)"},
        {"--frames", "N", "timed frames per configuration (default 20, after 5 warm-up frames)"},
        {"--rows", "LIST", "only these techniques' rows, e.g. direct,probes,dnrt (default: every row)"},
        {"--effect-images", "", "also write the images the object-effect errors compare (linear PFMs)"}},
       1, 1},
      {"bake", "LEVEL [options]", "precompute what the effects need (probes, DNRT fields) into the caches; one line per bake job",
       {effects, {"--force", "", "re-bake even when the cache holds a valid entry (to time a bake)"},
        {"--plan", "FILE", "write the jobs as a Ninja file (one edge per job): ninja -f FILE -j N bakes in parallel"},
        {"--list-jobs", "", "print the jobs as JSON lines: key, technique, what, command, inputs, output, extra_outputs"},
        {"--job", "KEY", "run the one job with this content key (the plan's command)"},
        {"--only", "TECHNIQUE[:PART]", "only this technique's jobs, or one part of it (e.g. dnrt:prop-truck); reference: the references bounce accuracy traces"}},
       1, 1},
      {"cache", "--stats|--prune [LEVEL...]",
       "the cache root (BOUNCE_CACHE, default <build>/cache): size per kind, or drop bake entries no level references",
       {{"--stats", "", "entries and bytes per kind (cooked, probes, dnrt, reference, ...)"},
        {"--prune", "", "remove bake entries, references and <cache>/cooked assets that no LEVEL names (default every content/levels/*.json)"}},
       0, SIZE_MAX},
      {"export", "LEVEL OUT.glb [--time T]", "write the composed level as one glTF 2.0 binary (meshes, materials, cameras, lights)",
       {{"--time", "T", "simulation time in seconds at which dynamic props are placed (default 0)"}}, 2, 2},
      {"vlm-make", "(LEVEL|ASSET) --out FILE.gltf [options]",
       "subtractive VLM creation: simplify real geometry to a triangle budget, offset it behind the surface, write an editable glTF",
       {{"--out", "FILE", "output .gltf (buffer embedded; nodes carry extras.bounce_vlm)"},
        {"--triangles", "N", "triangle budget over every source mesh (default 1000)"},
        {"--offset", "M", "metres behind the real surface, along -normal (default 0.005)"},
        {"--node", "NAME", "with a glTF asset: only this node's subtree"}},
       1, 1},
      {"level", "FILE.glb|FILE.gltf --out LEVEL.json",
       "write the level that play/capture/profile/accuracy make for a glTF file (asset, framing camera, sun, ground), to edit",
       {{"--out", "FILE", "output level .json (asset paths relative to it)"}}, 1, 1},
      {"bench", "vlm-grid|vlm-lights|vlm-k|dnrt|skinning|rtf|sl [options]",
       "vlm-grid: time the VLM grid builds (scatter vs gather) on a random scene, one line; vlm-lights / vlm-k: GPU ms\n"
       "              of the VLM passes vs lights per pixel without a grid / vs cell list size K, one line per setting;\n"
       "              dnrt: the DNRT paper's Tables 6-8 (GPU ms, ratios); skinning: vertices/ms, GPU pass vs CPU;\n"
       "              rtf: RTF bake + CPCA per object, CPU bouncing/shading step and GPU passes vs objects (game/bench_rtf.hpp);\n"
       "              sl: SL GPU ms vs sphere count, per-sphere and per-object blocking (game/bench_sl.hpp)",
       {device,
        {"--lights", "N", "virtual lights (vlm-grid default 10000; vlm-k default 240)"},
        {"--grid", "G", "vlm-grid: cells per axis (default 50)"},
        {"--k", "K", "vlm-grid: candidates per cell (default 32)"},
        {"--range", "R", "vlm-grid: active-hemisphere range (default 2.5)"},
        {"--runs", "N", "vlm-grid: builds per timing; the median is printed (default 3); rtf: timing runs (default 3)"},
        {"--no-gather", "", "vlm-grid: skip the gather build (it is O(cells × lights); needed for 100^3 x 100k)"},
        {"--counts", "LIST", "vlm-lights: light counts (default 20,40,...,240); vlm-k: K values (default 10,20,...,120); sl: total sphere counts over the level's sl entities (default 8,16,32,64,128)"},
        {"--level", "FILE", "vlm-lights/vlm-k: a level with a VLM (default content/levels/cornell-vlm.json); rtf: default cornell-5"},
        {"--resolution", "WxH", "vlm-lights/vlm-k/dnrt/rtf: render size (default 1280x720)"},
        {"--frames", "N", "vlm-lights/vlm-k: timed frames per setting (default 3); dnrt/rtf: per session (default 30, after 5 warm-up)"},
        {"--warmup", "N", "vlm-lights/vlm-k: untimed frames after each change (default 1)"},
        // bench dnrt (game/bench_dnrt.hpp)
        {"--levels", "LIST", "dnrt: Table 8 levels, names in content/levels or .json (default cornell-1,cornell-5,cornell-10)"},
        {"--variant-levels", "LIST", "dnrt: levels for the SH/grid/intrusion/mode rows (default cornell-1,cornell-10; none)"},
        {"--rays", "N", "dnrt: bake rays per grid vertex for every field (a square; default each entity's); rtf: ITF cube-map face size, 6*N^2 rays per sample (default 16)"},
        {"--csv", "FILE", "dnrt: also write the rows as CSV"},
        {"--instances", "N", "skinning: CesiumMan copies of the synthetic cage (default 306, ~1M vertices)"},
        {"--assets", "DIR", "skinning: the shared assets folder (default <source>/../shared/assets)"},
        // bench rtf (game/bench_rtf.hpp); --level, --rays and --runs above also apply
        {"--proxies", "N", "rtf: proxies per object (default 16)"},
        {"--spheres", "N", "rtf: concentric spheres (default 16)"},
        {"--face", "N", "rtf: cube-map face size per sphere, 6*N^2 samples (default 16)"},
        {"--vertex-rays", "N", "rtf: vertex transfer rays per axis (default 16)"},
        {"--clusters", "N", "rtf: CPCA clusters (default 32)"},
        {"--components", "N", "rtf: CPCA components per cluster (default 16)"},
        {"--byte-components", "N", "rtf: the last N components stored in 8 bits (default 0: all fp16)"},
        {"--bounces", "N", "rtf: inter-object bounces 1..4 (default 2)"},
        {"--objects", "N", "rtf: only the level's first N entities with a dnrt component (default all)"},
        {"--object", "ID", "rtf: only the entity with this id (any entity with a mesh), baked at this command's settings, not its rtf component's (needs --no-gpu)"},
        // bench sl (game/bench_sl.hpp); --level (default characters), --resolution (default 1280x720) and --frames (default 3) above also apply
        {"--influence", "F", "sl: every sl component's influence (0 = off, else 3..1000 radii; default the level's)"},
        {"--sl-resolution", "LIST", "sl: pass 2's resolution, full, half, quarter or a list such as full,half,quarter (default full); sl_ms then adds sl.upsample"},
        {"--fused", "", "sl: run the probes too, so pass 2 is the shipped levels' one walk for sl and sl.shadow (sl_ms holds both terms)"},
        {"--radii", "INNER,OUTER", "rtf: innermost and outermost sphere radii in units of the bounding radius (default 0.1,8)"},
        {"--no-gpu", "", "rtf: only the bake and CPU lines"},
        {"--rtf-resolution", "LIST", "rtf: the shading's resolution, full, half, quarter or a list such as full,quarter (default full); rtf_ms then adds rtf.upsample"},
        {"--only", "TEXT", "skinning: only the models whose name contains TEXT (e.g. +subdiv)"}},
       1, 1},
  };
  return specs;
}

GpuOptions gpuOptions(const cli::Args& args) { return {args.str("--device"), false}; }

int exitCodeAfterCommand(const std::string& command, int code) {
  const std::uint64_t errors = gpu::validationErrorsTotal();
  if (errors == 0) return code;
  // A command that already failed (exit 1) has said why; play prints its own count.
  if (code != 1)
    std::fprintf(stderr, "bounce %s: %llu Vulkan validation error(s), printed above\n", command.c_str(),
                 static_cast<unsigned long long>(errors));
  return 1;
}

}  // namespace bounce::game
