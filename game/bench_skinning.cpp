#include "game/bench_skinning.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>

#include "engine/anim/animator.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/anim/subdivision.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/paths.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "game/session.hpp"
#include "game/timing_stats.hpp"

#include <opensubdiv/osd/bufferDescriptor.h>
#include <opensubdiv/osd/cpuEvaluator.h>

namespace bounce::game {

namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr int kWarmup = 3;

struct Model {
  std::string name;
  std::filesystem::path asset;
  int instances = 1;
  bool subdivided = false;  // "subdivision": catmull-clark, 1 level: the cage refined every frame
};

// A level with `instances` copies of the asset in a row in front of the camera (direct light only).
std::filesystem::path writeLevel(const Model& m) {
  std::string entities = R"({"id": "camera", "transform": {"translation": [0, 1, 4]}, "camera": {"yfov_deg": 60}})";
  for (int i = 0; i < m.instances; ++i)
    entities += R"(, {"id": "m)" + std::to_string(i) + R"(", "transform": {"translation": [)" + std::to_string(0.01 * i) +
                R"(, 0, 0]}, "mesh": {"asset": ")" + m.asset.string() + "\"" +
                (m.subdivided ? R"(, "subdivision": {"scheme": "catmull-clark", "levels": 1})" : "") + "}}";
  const auto path = cacheDir("bench") / ("skinning-" + m.name + ".json");
  writeFileAtomic(path, R"({"bounce_level": 1, "effects": ["direct"], "entities": [)" + entities + "]}");
  return path;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// The CPU subdivision step of one frame, on cages posed beforehand: LimitStencilJob on TBB's pool
// (the CPU face), the same loop on one thread, and OpenSubdiv's Osd::CpuEvaluator::EvalStencils
// (one thread, positions and both tangents, no normals) on the same tables.
struct StencilTimes {
  double parallelMs = 0, serialMs = 0, osdMs = 0;
  double serialCpuMs = 0;  // the serial loop's thread CPU time: its rate without the host's other load
  std::size_t refined = 0, weights = 0;
};

double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

struct PosedCage {
  const asset::LimitStencils* stencils;
  std::vector<glm::vec3> positions, normals;
  std::vector<int> sizes, offsets, indices;  // Osd's int tables
};

StencilTimes timeStencils(std::vector<PosedCage>& cages) {
  StencilTimes t;
  std::vector<glm::vec3> outP, outN, du, dv;
  auto clock = [](auto&& fn) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  };
  for (PosedCage& c : cages) {
    const std::size_t rows = c.stencils->offsets.size() - 1;
    t.refined += rows;
    t.weights += c.stencils->indices.size();
    outP.resize(rows);
    outN.resize(rows);
    t.parallelMs += clock([&] { anim::LimitStencilJob{c.stencils, c.positions, c.normals, outP, outN, true}.run(); });
    const double cpu0 = threadCpuMs();
    t.serialMs += clock([&] { anim::LimitStencilJob{c.stencils, c.positions, c.normals, outP, outN, false}.run(); });
    t.serialCpuMs += threadCpuMs() - cpu0;
    if (c.sizes.empty()) {
      for (std::size_t v = 0; v < rows; ++v) {
        c.offsets.push_back(int(c.stencils->offsets[v]));
        c.sizes.push_back(int(c.stencils->offsets[v + 1] - c.stencils->offsets[v]));
      }
      c.indices.assign(c.stencils->indices.begin(), c.stencils->indices.end());
    }
    du.resize(rows);
    dv.resize(rows);
    namespace osd = OpenSubdiv::OPENSUBDIV_VERSION::Osd;
    const osd::BufferDescriptor desc(0, 3, 3);
    t.osdMs += clock([&] {
      osd::CpuEvaluator::EvalStencils(&c.positions[0].x, desc, &outP[0].x, desc, &du[0].x, desc, &dv[0].x, desc,
                                      c.sizes.data(), c.offsets.data(), c.indices.data(), c.stencils->weights.data(),
                                      c.stencils->duWeights.data(), c.stencils->dvWeights.data(), 0, int(rows));
    });
  }
  return t;
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
  std::vector<double> cpuMs, parallelMs, serialMs, osdMs, serialCpuMs;
  std::size_t vertices = 0, joints = 0, refined = 0, weights = 0;
  for (int i = 0; i < frames; ++i, t += kDt) {
    session.update(t);
    session.render(presenter, {});
    timings.collect(ring, 0);
    // The CPU face on the same poses: every deformed (skinned or morphed) primitive (a subdivided
    // mesh's cage primitive) of every instance, once.
    vertices = joints = 0;
    std::vector<PosedCage> cages;
    const auto t0 = std::chrono::steady_clock::now();
    session.registry().view<anim::Animator, anim::Pose>().each([&](ecs::Entity, anim::Animator& an, anim::Pose& pose) {
      const asset::CookedAsset& a = *an.asset;
      std::vector<glm::vec3> p, n;
      for (std::size_t node = 0; node < a.nodes.size(); ++node) {
        if (!anim::isDeformed(a, int(node))) continue;
        if (anim::isSkinned(a, int(node))) joints = std::max(joints, a.skins[std::size_t(a.nodes[node].skin)].joints.size());
        const asset::Mesh& mesh = a.meshes[std::size_t(a.nodes[node].mesh)];
        for (const asset::Primitive& prim : mesh.primitives) {
          const asset::Primitive& skinned =
              mesh.cage >= 0 ? a.meshes[std::size_t(mesh.cage)].primitives[std::size_t(prim.stencils.cagePrimitive)] : prim;
          anim::poseVertices(a, int(node), skinned, &pose, p, n);
          vertices += p.size();
          if (mesh.cage >= 0) cages.push_back({&prim.stencils, p, n, {}, {}, {}});
        }
      }
    });
    cpuMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (!cages.empty()) {
      const StencilTimes st = timeStencils(cages);
      parallelMs.push_back(st.parallelMs);
      serialMs.push_back(st.serialMs);
      osdMs.push_back(st.osdMs);
      serialCpuMs.push_back(st.serialCpuMs);
      refined = st.refined;
      weights = st.weights;
    }
  }
  ring.waitIdle();
  timings.collect(ring, 0);
  double gpuMs = -1.0, subdivMs = -1.0;
  for (const auto& r : timings.stats()) {
    if (r.pass == "skinning" && r.object.empty()) gpuMs = r.medianMs;
    if (r.pass == "subdivision" && r.object.empty()) subdivMs = r.medianMs;
  }
  if (gpuMs < 0.0) throw InternalError("bench skinning: no timings for the skinning pass (" + m.name + ")");
  if (m.subdivided && subdivMs < 0.0) throw InternalError("bench skinning: no timings for the subdivision pass (" + m.name + ")");
  const double cpu = median(cpuMs);
  std::printf("model=%s vertices=%zu joints=%zu instances=%d gpu_ms=%.3f gpu_vertices_per_ms=%.0f cpu_ms=%.3f "
              "cpu_vertices_per_ms=%.0f",
              m.name.c_str(), vertices, joints, m.instances, gpuMs, double(vertices) / std::max(gpuMs, 1e-6), cpu,
              double(vertices) / std::max(cpu, 1e-6));
  if (m.subdivided) {
    // Subdivision step: refined vertices per ms, GPU pass vs CPU face (TBB pool), and the CPU
    // stencil rate in millions of vertex·weights per second (one weight applied to one vertex).
    const double par = median(parallelMs), ser = median(serialMs), osd = median(osdMs), serCpu = median(serialCpuMs);
    std::printf(" refined_vertices=%zu stencil_weights=%zu subdiv_gpu_ms=%.3f subdiv_gpu_vertices_per_ms=%.0f "
                "subdiv_cpu_ms=%.3f subdiv_cpu_vertices_per_ms=%.0f cpu_mweights_per_s=%.1f "
                "subdiv_cpu1_ms=%.3f cpu1_mweights_per_s=%.1f cpu1_mweights_per_cpu_s=%.1f osd_cpu1_ms=%.3f",
                refined, weights, subdivMs, double(refined) / std::max(subdivMs, 1e-6), par,
                double(refined) / std::max(par, 1e-6), double(weights) / std::max(par, 1e-6) / 1e3, ser,
                double(weights) / std::max(ser, 1e-6) / 1e3, double(weights) / std::max(serCpu, 1e-6) / 1e3, osd);
  }
  std::printf(" frames=%d\n", frames);
  std::fflush(stdout);
}

}  // namespace

int runBenchSkinning(const cli::Args& args) {
  const int frames = args.positiveInt("--frames", 10);
  const int instances = args.positiveInt("--instances", 306);
  // Only the models whose name contains this (e.g. "+subdiv"); all when absent.
  const std::string only = args.has("--only") ? args.str("--only") : "";
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
      {"CesiumMan+subdiv", shared / "CesiumMan/glTF-Binary/CesiumMan.glb", 1, true},
      {"Fox+subdiv", shared / "Fox/glTF-Binary/Fox.glb", 1, true},
      {"BrainStem+subdiv", shared / "BrainStem/glTF-Binary/BrainStem.glb", 1, true},
      {"CesiumMan-x" + std::to_string(instances) + "+subdiv", shared / "CesiumMan/glTF-Binary/CesiumMan.glb", instances, true},
      // Morph targets (3 per mesh) on the GPU: one sheet morphed alone, one strip morphed then skinned.
      {"Morph", contentDir() / "src/morph/morph.gltf", 1},
      {"Morph-x" + std::to_string(instances), contentDir() / "src/morph/morph.gltf", instances},
  };
  for (const auto& m : models)
    if (!std::filesystem::is_regular_file(m.asset))
      throwInputError("bounce bench skinning", "--assets", "no " + m.asset.string(), "the ../shared/assets folder");
  gpu::Context ctx(gpu::ContextOptions{args.str("--device")});
  for (const auto& m : models)
    if (only.empty() || m.name.find(only) != std::string::npos) run(ctx, m, frames);
  return 0;
}

}  // namespace bounce::game
