#include "game/bench_rtf.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "engine/core/error.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/rtf/bake.hpp"
#include "engine/gi/rtf/evaluate.hpp"
#include "engine/gi/resolution.hpp"  // header only: the --rtf-resolution names
#include "engine/math/sampling.hpp"
#include "engine/scene/systems.hpp"
#include "game/bench_dnrt.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "game/session.hpp"
#include "game/timing_stats.hpp"

namespace bounce::game {

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Parsed as a non-negative integer so that lo = 0 can be given (--byte-components 0 = none in 8 bits,
// the default); the range check names the option's own bounds.
int intIn(const cli::Args& args, const char* option, int fallback, int lo, int hi) {
  const int v = args.nonNegativeInt(option, fallback);
  if (v < lo || v > hi)
    throwInputError("bounce bench rtf", option, std::to_string(v) + " out of range",
                    std::to_string(lo) + ".." + std::to_string(hi));
  return v;
}

}  // namespace

int runBenchRtf(const cli::Args& args) {
  gi::rtf::FieldSettings s;  // the paper's resolution unless told otherwise
  // The shading's G-buffer pixels per sample per axis (engine/gi/resolution.hpp), checked before any bake.
  const std::vector<std::uint32_t> steps = gi::parseResolutionList(
      args.list("--rtf-resolution").value_or(std::vector<std::string>{"full"}), "bounce bench", "--rtf-resolution");
  s.proxies = intIn(args, "--proxies", s.proxies, 1, 64);
  s.spheres = intIn(args, "--spheres", s.spheres, 2, 64);
  s.faceSize = intIn(args, "--face", s.faceSize, 1, 64);
  s.raysPerAxis = intIn(args, "--rays", s.raysPerAxis, 1, 256);
  s.vertexRaysPerAxis = intIn(args, "--vertex-rays", s.vertexRaysPerAxis, 1, 256);
  s.clusters = intIn(args, "--clusters", s.clusters, 1, 4096);
  s.components = intIn(args, "--components", s.components, 1, 256);
  if (args.has("--byte-components")) s.byteComponents = intIn(args, "--byte-components", 0, 0, s.components);
  if (args.has("--radii")) {  // "INNER,OUTER" in units of η (a level component's inner/outer)
    const std::string v = args.str("--radii");
    const std::size_t comma = v.find(',');
    char* end = nullptr;
    const double inner = std::strtod(v.c_str(), &end);
    const bool innerOk = comma != std::string::npos && end == v.c_str() + comma;
    const double outer = innerOk ? std::strtod(v.c_str() + comma + 1, &end) : 0.0;
    if (!innerOk || *end != '\0' || !(inner > 0.0) || !(outer > inner) || !(outer <= 100.0))
      throwInputError("bounce bench rtf", "--radii", "'" + v + "' is not INNER,OUTER", "0 < INNER < OUTER <= 100, e.g. 0.5,4");
    s.innerRadius = float(inner), s.outerRadius = float(outer);
  }
  const int bounces = intIn(args, "--bounces", 2, 1, 4);
  const int runs = intIn(args, "--runs", 3, 1, 1000);
  const int maxObjects = intIn(args, "--objects", 1000, 1, 1000);
  // --object ID: one entity alone, baked at THIS command's settings (above), not at its own `rtf`
  // component's: issue 14's goal is measured per prop by choosing the settings for it (README "CPCA on
  // every prop, session 14"). Any entity with a mesh will do (an `rtf` component needs one; a
  // `dnrt` one is not asked for). The GPU rows put the fields on the level's first n dnrt objects, so
  // only with --no-gpu. The id is checked against the level file before anything is cooked or baked.
  const std::string only = args.str("--object", "");
  if (args.has("--object") && (only.empty() || !args.has("--no-gpu")))
    throwInputError("bounce bench rtf", "--object", only.empty() ? "no id" : "without --no-gpu",
                    "--object ID --no-gpu, ID an entity with a mesh");
  const std::string levelArg = args.str("--level", "cornell-5");
  const scene::Level level = scene::loadLevel(benchLevelPath(levelArg));
  if (!only.empty()) {
    std::string ids;  // the entities --object accepts, for the message
    const scene::EntityDesc* found = nullptr;
    for (const scene::EntityDesc& e : level.entities) {
      if (e.mesh) ids += (ids.empty() ? "" : ", ") + e.id;
      if (e.id == only) found = &e;
    }
    if (!found || !found->mesh)
      throwInputError("bounce bench rtf", "--object", "'" + only + (found ? "' has no mesh" : "' is no entity of " + levelArg),
                      "an entity with a mesh: one of " + ids);
  }

  gi::dnrt::LevelObjects objects;
  gi::dnrt::loadLevelObjects(level, cookCacheDir(), objects);
  if (!only.empty()) {
    // loadLevelObjects() keeps the dnrt entities; the one asked for may be any entity with a mesh
    // (its registry and reference assets hold every entity and every mesh).
    objects.entities.clear();
    objects.registry.view<scene::Name, scene::MeshRef>().each([&](ecs::Entity e, scene::Name& name, scene::MeshRef&) {
      if (name.id == only) objects.entities.push_back(e);
    });
    if (objects.entities.size() != 1)
      throw InternalError("bench rtf: " + std::to_string(objects.entities.size()) + " entities named '" + only + "'");
  } else if (objects.entities.empty()) {
    throwInputError(levelArg, "/entities", "no dynamic object", "entities with a dnrt component, or --object ID");
  }
  std::vector<gi::rtf::Field> fields;
  std::vector<glm::mat4> worlds;
  for (ecs::Entity e : objects.entities) {
    if (int(fields.size()) >= maxObjects) break;
    const ref::SceneDesc object = gi::dnrt::objectScene(objects.registry, e, objects.assets);
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t cpu0 = std::clock();  // the process's CPU time, all threads: wall time on a shared host says little
    bool cached = false;
    fields.push_back(gi::rtf::bakeCached(object, s, cacheDir("rtf"), &cached));
    const double seconds = cached ? 0.0 : secondsSince(t0);
    const double cpuSeconds = cached ? 0.0 : double(std::clock() - cpu0) / CLOCKS_PER_SEC;
    const gi::rtf::Field& f = fields.back();
    // ratio= is the STORED ratio: fp32 bytes of the ITF / bytes of the file's CPCA (fp16 basis and
    // α, the last --byte-components of them as 8-bit codes and fp32 scales, uint32 cluster ids:
    // cpca.hpp storedBytes); frobenius= the error after that rounding (bake.cpp). The float ratio
    // (what the ξ pass's fp32 buffers hold) is compressionRatio(f.itf), about half of it.
    const double ratio = gi::rtf::storedRatio(f.itf);
    const double rawMb = double(gi::rtf::sampleCount(s)) * double(gi::rtf::itfDimension(s)) * 4.0 / 1e6;
    const scene::Name* name = objects.registry.tryGet<scene::Name>(e);
    const std::string id = name ? name->id : std::to_string(e.index());
    std::printf("object=%s proxies=%d clusters=%d components=%d byte_components=%d ratio=%.1f frobenius=%.4f bake_s=%.1f bake_cpu_s=%.1f raw_mb=%.1f "
                "compressed_mb=%.2f cached=%d\n",
                id.c_str(), s.proxies, f.itf.clusters, f.itf.components, f.itf.byteComponents, ratio, f.frobenius, seconds, cpuSeconds, rawMb,
                rawMb / ratio, cached ? 1 : 0);  // always there: gpu-bench.sh's CSV takes its columns from the first line
    std::fflush(stdout);
    worlds.push_back(objects.registry.get<scene::WorldTransform>(e).matrix);
  }

  const gi::dnrt::ConstantEnvironment env(glm::vec3(1.0f));
  constexpr int kReceivers = 64;  // shading: points on a ring around the scene's objects
  for (std::size_t n = 1; n <= fields.size(); ++n) {
    std::vector<gi::rtf::Object> scene;
    for (std::size_t i = 0; i < n; ++i) scene.push_back({&fields[i], worlds[i]});
    std::vector<double> bounceMs, shadeUs;
    gi::rtf::BounceResult bounced;
    for (int r = 0; r < runs; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      bounced = gi::rtf::bounce(scene, env, bounces);
      bounceMs.push_back(secondsSince(t0) * 1e3);
      const auto t1 = std::chrono::steady_clock::now();
      const gi::rtf::Placement p = gi::rtf::place(fields[0], worlds[0]);
      for (int k = 0; k < kReceivers; ++k) {
        const double a = 2.0 * math::kPi * k / kReceivers;
        const glm::vec3 dir(float(std::cos(a)), 0.0f, float(std::sin(a)));
        gi::rtf::shade(scene, bounced, env, p.centreWorld + 1.5f * p.radiusWorld * dir, -dir, glm::vec3(0.5f), -1);
      }
      shadeUs.push_back(secondsSince(t1) * 1e6 / kReceivers);
    }
    std::sort(bounceMs.begin(), bounceMs.end());
    std::sort(shadeUs.begin(), shadeUs.end());
    std::printf("objects=%zu bounces=%d rtf_bounce_cpu_ms=%.3f rtf_shade_cpu_us_per_receiver=%.2f runs=%d\n", n, bounces,
                bounceMs[bounceMs.size() / 2], shadeUs[shadeUs.size() / 2], runs);
    std::fflush(stdout);
  }

  // GPU: the level with the first n of those objects carrying an `rtf` component at the settings
  // above (the fields just baked: same key), the others drawn without one, rendered with
  // direct,shadows,probes,rtf; medians of the "rtf.bounce" (ξ pass) and "rtf" (shading) scopes,
  // and of the per-object shading scopes "rtf/<id>", over --frames after kWarmupFrames (timeFrames).
  if (args.has("--no-gpu")) return 0;
  const auto res = args.resolution("--resolution").value_or(std::pair<int, int>{1280, 720});
  const int frames = intIn(args, "--frames", 30, 1, 100000);
  gpu::Context ctx({args.str("--device", "")});
  gpu::OffscreenPresenter presenter(ctx, {std::uint32_t(res.first), std::uint32_t(res.second)});
  for (std::size_t n = 1; n <= fields.size(); ++n)
    for (const std::uint32_t step : steps) {
      scene::Level configured = level;
      scene::overrideEffects(configured, "direct,shadows,probes,rtf");
      configured.rtf.step = step;
      std::size_t k = 0;
      for (auto& e : configured.entities) {
        if (!e.dnrt) continue;  // the bench's objects (above)
        e.rtf.reset();
        if (k++ >= n) continue;
        scene::Rtf c;
        c.proxies = s.proxies, c.bounces = bounces, c.spheres = s.spheres, c.face = s.faceSize, c.rays = s.raysPerAxis;
        c.vertexRays = s.vertexRaysPerAxis, c.clusters = s.clusters, c.components = s.components;
        c.byteComponents = s.byteComponents;  // else the GPU rows would bake (and time) a field without the 8-bit tail
        c.inner = s.innerRadius, c.outer = s.outerRadius;
        e.rtf = c;
      }
      TimingCollector timings;
      {
        Session session(ctx, configured);
        timeFrames(session, presenter, frames, timings);
      }
      double bounceGpu = 0.0, shade = 0.0, upsample = 0.0, perObject = 0.0;
      std::size_t objectRows = 0, measured = 0;
      for (const PassStats& p : timings.stats()) {
        if (p.pass == "rtf.bounce" && p.object.empty()) bounceGpu = p.medianMs, measured = p.frames;
        if (p.pass == "rtf" && p.object.empty()) shade = p.medianMs;
        if (p.pass == "rtf.upsample" && p.object.empty()) upsample = p.medianMs;
        if (p.pass == "rtf" && !p.object.empty()) perObject += p.medianMs, ++objectRows;
      }
      std::printf("objects=%zu bounces=%d %dx%d rtf_bounce_ms=%.3f rtf_ms=%.3f rtf_per_object_ms=%.3f frames=%zu resolution=%s "
                  "rtf_upsample_ms=%.3f\n",
                  n, bounces, res.first, res.second, bounceGpu, shade + upsample,
                  objectRows ? perObject / double(objectRows) : 0.0, measured, gi::resolutionName(step), upsample);
      std::fflush(stdout);
    }
  return 0;
}

}  // namespace bounce::game
