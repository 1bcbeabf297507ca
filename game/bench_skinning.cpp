#include "game/bench_skinning.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "engine/anim/animator.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/paths.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "game/session.hpp"
#include "game/timing_stats.hpp"

namespace bounce::game {

namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr int kWarmup = 3;

struct Model {
  std::string name;
  std::filesystem::path asset;
  int instances = 1;
};

// A level with `instances` copies of the asset in a row in front of the camera (direct light only).
std::filesystem::path writeLevel(const Model& m) {
  std::string entities = R"({"id": "camera", "transform": {"translation": [0, 1, 4]}, "camera": {"yfov_deg": 60}})";
  for (int i = 0; i < m.instances; ++i)
    entities += R"(, {"id": "m)" + std::to_string(i) + R"(", "transform": {"translation": [)" + std::to_string(0.01 * i) +
                R"(, 0, 0]}, "mesh": {"asset": ")" + m.asset.string() + R"("}})";
  const auto path = cacheDir("bench") / ("skinning-" + m.name + ".json");
  writeFileAtomic(path, R"({"bounce_level": 1, "effects": ["direct"], "entities": [)" + entities + "]}");
  return path;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void run(gpu::Context& ctx, const Model& m, int frames) {
  Session session(ctx, scene::loadLevel(writeLevel(m)));
  gpu::OffscreenPresenter presenter(ctx, {64, 64});
  auto& ring = session.renderer().frames();
  double t = 0.0;
  for (int i = 0; i < kWarmup; ++i, t += kDt) {
    session.update(t);
    session.render(presenter, {});
  }
  ring.waitIdle();
  TimingCollector discard, timings;
  discard.collect(ring, 0);
  std::vector<double> cpuMs;
  std::size_t vertices = 0, joints = 0;
  for (int i = 0; i < frames; ++i, t += kDt) {
    session.update(t);
    session.render(presenter, {});
    timings.collect(ring, 0);
    // The CPU face on the same poses: every skinned primitive of every instance, once.
    vertices = joints = 0;
    const auto t0 = std::chrono::steady_clock::now();
    session.registry().view<anim::Animator, anim::Pose>().each([&](ecs::Entity, anim::Animator& an, anim::Pose& pose) {
      const asset::CookedAsset& a = *an.asset;
      std::vector<glm::vec3> p, n;
      for (std::size_t node = 0; node < a.nodes.size(); ++node) {
        if (!anim::isSkinned(a, int(node))) continue;
        joints = std::max(joints, a.skins[std::size_t(a.nodes[node].skin)].joints.size());
        for (std::size_t pi = 0; pi < a.meshes[std::size_t(a.nodes[node].mesh)].primitives.size(); ++pi) {
          anim::posePrimitive(a, int(node), pi, &pose, p, n);
          vertices += p.size();
        }
      }
    });
    cpuMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  ring.waitIdle();
  timings.collect(ring, 0);
  double gpuMs = -1.0;
  for (const auto& r : timings.stats())
    if (r.pass == "skinning" && r.object.empty()) gpuMs = r.medianMs;
  if (gpuMs < 0.0) throw InternalError("bench skinning: no timings for the skinning pass (" + m.name + ")");
  const double cpu = median(cpuMs);
  std::printf("model=%s vertices=%zu joints=%zu instances=%d gpu_ms=%.3f gpu_vertices_per_ms=%.0f cpu_ms=%.3f "
              "cpu_vertices_per_ms=%.0f frames=%d\n",
              m.name.c_str(), vertices, joints, m.instances, gpuMs, double(vertices) / std::max(gpuMs, 1e-6), cpu,
              double(vertices) / std::max(cpu, 1e-6), frames);
  std::fflush(stdout);
}

}  // namespace

int runBenchSkinning(const cli::Args& args) {
  const int frames = args.positiveInt("--frames", 10);
  const int instances = args.positiveInt("--instances", 306);
  // Default: the ../shared/assets beside the checkout that content/ belongs to (a build tree's
  // content/ links to the source tree's); an installed bounce needs --assets.
  std::error_code ec;
  const std::filesystem::path checkout = std::filesystem::weakly_canonical(contentDir(), ec).parent_path();
  const std::filesystem::path shared =
      args.has("--assets") ? std::filesystem::path(args.str("--assets")) : checkout.parent_path() / "shared" / "assets";
  const std::vector<Model> models = {
      {"CesiumMan", shared / "CesiumMan/glTF-Binary/CesiumMan.glb", 1},
      {"Fox", shared / "Fox/glTF-Binary/Fox.glb", 1},
      {"BrainStem", shared / "BrainStem/glTF-Binary/BrainStem.glb", 1},
      {"CesiumMan-x" + std::to_string(instances), shared / "CesiumMan/glTF-Binary/CesiumMan.glb", instances},
  };
  for (const auto& m : models)
    if (!std::filesystem::is_regular_file(m.asset))
      throwInputError("bounce bench skinning", "--assets", "no " + m.asset.string(), "the ../shared/assets folder");
  gpu::Context ctx(gpu::ContextOptions{args.str("--device")});
  for (const auto& m : models) run(ctx, m, frames);
  return 0;
}

}  // namespace bounce::game
