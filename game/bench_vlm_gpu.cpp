#include "game/bench_vlm_gpu.hpp"

#include <algorithm>
#include <cstdio>
#include <queue>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/core/paths.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "game/session.hpp"
#include "game/timing_stats.hpp"

namespace bounce::game {

namespace {

constexpr double kDt = 1.0 / 60.0;
// "Without the grid" and "every list full": a hemisphere range this large reaches every cell of
// the scene from every light (level.cpp caps the range here too).
constexpr float kEverywhereRange = 100.0f;

// Splits the largest triangle at the midpoint of its longest edge until there are `count`
// (the halves keep the winding, so the emitting side, and the light's scale and tag).
std::vector<gi::vlm::VirtualLight> subdivide(std::vector<gi::vlm::VirtualLight> lights, std::size_t count) {
  auto area = [](const gi::vlm::VirtualLight& l) { return glm::length(glm::cross(l.v1 - l.v0, l.v2 - l.v0)); };
  using Item = std::pair<float, std::size_t>;
  std::priority_queue<Item> largest;
  for (std::size_t i = 0; i < lights.size(); ++i) largest.push({area(lights[i]), i});
  while (lights.size() < count && !largest.empty()) {
    const std::size_t i = largest.top().second;
    largest.pop();
    gi::vlm::VirtualLight a = lights[i];
    // Rotate so that v0–v1 is the longest edge.
    for (int r = 0; r < 2; ++r) {
      const float e01 = glm::length(a.v1 - a.v0), e12 = glm::length(a.v2 - a.v1), e20 = glm::length(a.v0 - a.v2);
      if (e01 >= e12 && e01 >= e20) break;
      a = {a.v1, a.v2, a.v0, a.scale, a.tag};
    }
    const glm::vec3 m = 0.5f * (a.v0 + a.v1);
    gi::vlm::VirtualLight first = a, second = a;
    first.v1 = m;   // (v0, m, v2)
    second.v0 = m;  // (m, v1, v2)
    lights[i] = first;
    lights.push_back(second);
    largest.push({area(lights[i]), i});
    largest.push({area(lights.back()), lights.size() - 1});
  }
  return lights;
}

struct Bench {
  scene::Level level;
  gpu::Context ctx;
  std::unique_ptr<Session> session;
  std::unique_ptr<gpu::OffscreenPresenter> presenter;
  std::vector<gi::vlm::VirtualLight> baseLights;  // the level's static VLM triangles
  std::size_t dynamicLights = 0;
  int warmup = 1, frames = 3;
  double t = 0.0;
  VkExtent2D extent{};

  explicit Bench(const cli::Args& args)
      : level(loadLevelWithEffects(args.has("--level") ? args.str("--level")
                                                       : (contentDir() / "levels" / "cornell-vlm.json").string(),
                                   std::nullopt)),
        ctx({args.str("--device")}) {
    const auto res = args.resolution("--resolution").value_or(std::pair{1280, 720});
    extent = {std::uint32_t(res.first), std::uint32_t(res.second)};
    frames = args.positiveInt("--frames", 3);
    warmup = args.has("--warmup") ? args.positiveInt("--warmup", 1) : 1;
    if (!level.effects.has(scene::Effect::Vlm))
      throwInputError(level.source.string(), "/effects", "the level's effects do not name vlm", "a level with a VLM");
    session = std::make_unique<Session>(ctx, level);
    if (!session->vlm() || session->vlm()->lightCount() == 0)
      throwInputError(level.source.string(), "/entities", "no entity carries a vlm", "a level with a VLM");
    presenter = std::make_unique<gpu::OffscreenPresenter>(ctx, extent);
    baseLights.assign(session->vlm()->staticLights().begin(), session->vlm()->staticLights().end());
    dynamicLights = session->vlm()->lightCount() - baseLights.size();
    if (baseLights.empty()) throwInputError(level.source.string(), "/entities", "no static VLM", "a static VLM to subdivide");
    // Compile the pipelines before any timing (DESIGN.md machine facts).
    for (int i = 0; i < 2; ++i) frame();
  }

  ~Bench() {
    if (session) session->renderer().frames().waitIdle();  // before the presenter goes
  }

  void frame() {
    session->update(t);
    session->render(*presenter, {});
    t += kDt;
  }

  // Sets `total` lights (static ones split from the level's) and the grid, renders, returns the
  // median GPU ms of the passes "vlm" and "vlm.lights".
  std::pair<double, double> run(std::size_t total, const gi::vlm::NodeSettings& settings) {
    if (total <= dynamicLights)
      throwInputError("bounce bench", "--lights", std::to_string(total) + " lights",
                      "more than the level's " + std::to_string(dynamicLights) + " dynamic virtual lights");
    auto& vlm = *session->vlm();
    vlm.replaceStaticLights(subdivide(baseLights, total - dynamicLights));
    vlm.setSettings(settings);
    auto& ring = session->renderer().frames();
    for (int i = 0; i < warmup; ++i) frame();
    ring.waitIdle();
    TimingCollector discard, timings;
    discard.collect(ring, 0);
    for (int i = 0; i < frames; ++i) {
      frame();
      timings.collect(ring, 0);
    }
    ring.waitIdle();
    timings.collect(ring, 0);
    double shade = -1.0, lights = -1.0;
    for (const auto& r : timings.stats()) {
      if (r.pass == "vlm" && r.object.empty()) shade = r.medianMs;
      if (r.pass == "vlm.lights" && r.object.empty()) lights = r.medianMs;
    }
    if (shade < 0.0 || lights < 0.0) throw InternalError("bench: no timings for the vlm passes");
    return {shade, lights};
  }
};

std::vector<int> counts(const cli::Args& args, const std::string& option, std::vector<int> fallback) {
  if (!args.has(option)) return fallback;
  std::vector<int> out;
  const auto items = *args.list(option);  // a copy: list() returns by value
  for (const auto& s : items) {
    std::size_t used = 0;
    int v = 0;
    try {
      v = std::stoi(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || v < 1 || v > 4096) throwInputError("bounce bench", option, "'" + s + "'", "integers in [1, 4096]");
    out.push_back(v);
  }
  return out;
}

}  // namespace

int runBenchVlmLights(const cli::Args& args) {
  const auto ns = counts(args, "--counts", {20, 40, 60, 80, 100, 120, 140, 160, 180, 200, 220, 240});
  Bench bench(args);
  for (int n : ns) {
    gi::vlm::NodeSettings s = bench.session->vlm()->settings();
    s.grid = 1;
    s.k = std::uint32_t(n);
    s.range = kEverywhereRange;
    s.conservativeThreshold = 0.0f;
    const auto [shade, lights] = bench.run(std::size_t(n), s);
    const auto o = bench.session->vlm()->overflow();
    // One cell that lists every light: nothing may overflow, or this would not be "no grid".
    if (o.cellsPerGrid != 1 || o.staticCells != 0 || o.dynamicMaxCells != 0)
      throw InternalError("bench vlm-lights: the single cell did not hold every light");
    std::printf("lights=%d grid=1 k=%d %ux%u vlm_ms=%.2f vlm_lights_ms=%.2f frames=%d\n", n, n, bench.extent.width,
                bench.extent.height, shade, lights, bench.frames);
    std::fflush(stdout);
  }
  return 0;
}

int runBenchVlmK(const cli::Args& args) {
  const auto ks = counts(args, "--counts", {10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120});
  const int total = args.positiveInt("--lights", 240);
  Bench bench(args);
  for (int k : ks) {
    gi::vlm::NodeSettings s = bench.session->vlm()->settings();
    s.k = std::uint32_t(k);
    s.range = kEverywhereRange;
    s.conservativeThreshold = 0.0f;
    const auto [shade, lights] = bench.run(std::size_t(total), s);
    const auto o = bench.session->vlm()->overflow();
    std::printf("k=%d lights=%d grid=%d %ux%u vlm_ms=%.2f vlm_lights_ms=%.2f overflow_cells=%llu/%llu frames=%d\n", k,
                total, s.grid, bench.extent.width, bench.extent.height, shade, lights,
                static_cast<unsigned long long>(o.staticCells), static_cast<unsigned long long>(o.cellsPerGrid),
                bench.frames);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace bounce::game
