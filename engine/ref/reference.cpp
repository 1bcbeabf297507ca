#include "engine/ref/reference.hpp"

#include "engine/anim/animator.hpp"

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/capture.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::ref {
namespace {

// A capture script names itself with "bounce_capture"; anything else is read as a level, whose
// loader reports syntax errors and a missing "bounce_level" in its usual one-line form.
bool isCaptureScript(const std::filesystem::path& path) {
  const auto json = nlohmann::json::parse(readFileText(path), nullptr, /*allow_exceptions=*/false);
  return json.is_object() && json.contains("bounce_capture");
}

std::string joinList(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& e : items) s += (s.empty() ? "" : ",") + e;
  return s;
}

}  // namespace

ReferenceResult renderReference(const ReferenceRequest& request) {
  // 1. What to render: the level, the time, the camera motion and the resolution.
  std::optional<scene::CaptureScript> script;
  scene::Level level;
  double dt = kLevelFrameDt;
  std::pair<std::uint32_t, std::uint32_t> resolution{kDefaultResolution, kDefaultResolution};
  if (isCaptureScript(request.input)) {
    script = scene::loadCaptureScript(request.input);
    level = scene::loadLevel(script->level);
    if (script->effects) level.effects = *script->effects;
    dt = script->dt;
    resolution = {script->resolution.x, script->resolution.y};
    if (request.frame >= script->frames)
      throwInputError(request.input.string(), "--frame", "frame " + std::to_string(request.frame) + " is not simulated",
                      "a frame below the script's " + std::to_string(script->frames) + " frames");
  } else {
    level = scene::loadLevel(request.input);
  }
  // Effects do not change the reference (header comment), but a bad list is still an error.
  if (request.effects) scene::overrideEffects(level, joinList(*request.effects));
  if (request.resolution) resolution = *request.resolution;

  TraceSettings settings;
  settings.width = resolution.first;
  settings.height = resolution.second;
  settings.spp = request.spp.value_or(kDefaultSpp);
  settings.bounces = request.bounces.value_or(kUnlimitedBounces);
  settings.label = request.progress ? "reference " + request.input.filename().string() : std::string();
  if (settings.spp == 0) throwInputError("bounce reference", "--spp", "0 samples per pixel", "a positive integer");

  // 2. The scene at time frame·dt, as a capture run would pose it (Session::update).
  ecs::Registry registry;
  scene::instantiate(level, registry);
  if (script && script->camera) {
    if (ecs::Entity cam = scene::activeCamera(registry); !cam.isNull()) {
      scene::Motion motion = *script->camera;
      motion.base = registry.get<scene::Transform>(cam);
      registry.emplaceOrReplace<scene::Motion>(cam, std::move(motion));
    }
  }
  ReferenceResult result;
  result.timeSeconds = double(request.frame) * dt;
  scene::motionSystem(registry, result.timeSeconds);
  anim::attachAnimators(registry, request.cookCache);
  anim::animationSystem(registry, result.timeSeconds);  // the posed meshes (engine/anim), as the renderer draws them
  scene::transformSystem(registry);
  ReferenceAssets assets;
  assets.load(registry, request.cookCache);
  SceneDesc desc = extractScene(registry, level, assets);

  // 3. The cache key (reference.hpp lists what it covers).
  Hasher h;
  h.str("bounce-reference").u64(kTracerVersion);
  const auto levelBytes = readFileBytes(level.source);
  h.u64(levelBytes.size()).bytes(levelBytes.data(), levelBytes.size());
  for (const auto& [k, entry] : assets.entries()) h.str(k).str(entry.contentKey);
  h.pod(result.timeSeconds).pod(desc.camera.world).pod(desc.camera.yfovRad).pod(desc.camera.near).pod(desc.camera.far);
  h.u64(settings.width).u64(settings.height).u64(settings.spp).u64(settings.bounces);
  result.key = h.hex();
  result.cachePath = request.cacheDir / (result.key + ".pfm");

  if (std::filesystem::exists(result.cachePath)) {
    try {
      gpu::FloatImage cached = gpu::readPfm(result.cachePath);
      if (cached.width == settings.width && cached.height == settings.height) {
        result.image = std::move(cached);
        result.fromCache = true;
        return result;
      }
      log::warn(result.cachePath.string() + ": cached reference has the wrong size; tracing again");
    } catch (const InputError& e) {
      log::warn(std::string(e.what()) + "; tracing again");
    }
  }

  // 4. Trace and cache.
  SceneBvh bvh(std::move(desc));
  result.triangles = bvh.triangleCount();
  result.image = trace(bvh, settings, &result.stats);
  gpu::writePfm(result.cachePath, result.image);
  return result;
}

}  // namespace bounce::ref
