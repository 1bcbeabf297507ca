// `bounce bench vlm-grid`: times the VLM grid builds (engine/gi/vlm/grid.hpp) on a random scene —
// the scatter build against the thesis's gather build (Table 5.2 analogue) — and prints one line:
//   lights=N grid=G k=K scatter_ms=… gather_ms=… overflow_cells=… candidates=… first_scatter_ms=…
// (candidates: (light, cell) pairs the heuristic accepted, before truncation to K).
// Each time is the median of --runs builds. CPU-only (TBB on every core). With --no-gather (the
// gather build is O(cells × lights): 100³ cells × 100k lights is 10¹¹ tests) gather_ms=skipped.
// `bounce bench vlm-lights|vlm-k`: GPU benches, game/bench_vlm_gpu.hpp.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/gi/vlm/grid.hpp"
#include "game/bench_rtf.hpp"
#include "game/bench_skinning.hpp"
#include "game/bench_sl.hpp"
#include "game/bench_vlm_gpu.hpp"
#include "game/commands.hpp"

namespace bounce::game {

namespace {

template <class F>
double medianMs(int runs, F&& build) {
  std::vector<double> ms;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    build();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace

int runBench(const cli::Args& args) {
  const std::string what = args.positional.at(0);
  if (what == "vlm-lights") return runBenchVlmLights(args);
  if (what == "vlm-k") return runBenchVlmK(args);
  if (what == "dnrt") return runBenchDnrt(args);  // bench_dnrt.cpp
  if (what == "skinning") return runBenchSkinning(args);  // bench_skinning.cpp
  if (what == "rtf") return runBenchRtf(args);  // bench_rtf.cpp
  if (what == "sl") return runBenchSl(args);    // bench_sl.cpp
  if (what != "vlm-grid")
    throwInputError("bounce bench", "benchmark", "unknown benchmark '" + what + "'", "vlm-grid, vlm-lights, vlm-k, dnrt, skinning, rtf or sl");
  const int lights = args.positiveInt("--lights", 10000);
  const int grid = args.positiveInt("--grid", 50);
  const int k = args.positiveInt("--k", 32);
  const int runs = args.positiveInt("--runs", 3);
  const double range = args.has("--range") ? std::stod(args.str("--range")) : 2.5;
  if (!(range > 0.0 && range < 100.0)) throwInputError("bounce bench", "--range", "out of range", "0 < range < 100");
  if (grid > 512) throwInputError("bounce bench", "--grid", "too many cells", "a grid of at most 512³");

  const auto scene = gi::vlm::randomGridScene(std::uint32_t(lights), 1);
  const auto desc = gi::vlm::fitGrid(glm::vec3(0.0f), glm::vec3(1.0f), glm::uvec3(std::uint32_t(grid)), std::uint32_t(k), float(range));
  gi::vlm::Grid scatter, gather;
  // The scatter build as the per-frame dynamic grid runs it: one builder and one grid reused, so
  // the median is the steady state; the first build (fresh memory, page faults) is printed apart.
  gi::vlm::GridScatterBuilder builder;
  const double firstMs = medianMs(1, [&] { builder.build(scene, desc, scatter); });
  const double scatterMs = medianMs(runs, [&] { builder.build(scene, desc, scatter); });
  const double gatherMs = args.has("--no-gather") ? 0.0 : medianMs(runs, [&] { gather = gi::vlm::buildGridGather(scene, desc); });
  if (!args.has("--no-gather") && gather.slots != scatter.slots)
    throw InternalError("bench vlm-grid: scatter and gather builds disagree");
  char gatherText[32] = "skipped";
  if (!args.has("--no-gather")) std::snprintf(gatherText, sizeof gatherText, "%.2f", gatherMs);
  std::printf("lights=%d grid=%d k=%d scatter_ms=%.2f gather_ms=%s overflow_cells=%llu candidates=%llu first_scatter_ms=%.2f\n",
              lights, grid, k, scatterMs, gatherText, static_cast<unsigned long long>(scatter.overflowCells),
              static_cast<unsigned long long>(scatter.candidates), firstMs);
  return 0;
}

}  // namespace bounce::game
