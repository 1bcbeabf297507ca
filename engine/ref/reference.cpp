#include "engine/ref/reference.hpp"

#include <algorithm>

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

namespace {

// Steps 1-3 of a reference: the request validated, the scene posed, the key computed.
struct Prepared {
  TraceSettings settings;
  SceneDesc desc;
  ReferenceResult result;  // timeSeconds, key, cachePath
};

Prepared prepare(const ReferenceRequest& request) {
  Prepared p;
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

  TraceSettings& settings = p.settings;
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
  ReferenceResult& result = p.result;
  result.timeSeconds = double(request.frame) * dt;
  scene::motionSystem(registry, result.timeSeconds);
  anim::attachAnimators(registry, request.cookCache);
  anim::animationSystem(registry, result.timeSeconds);  // the posed meshes (engine/anim), as the renderer draws them
  scene::transformSystem(registry);
  ReferenceAssets assets;
  assets.load(registry, request.cookCache);
  p.desc = extractScene(registry, level, assets);
  const SceneDesc& desc = p.desc;

  // 3. The cache key (reference.hpp lists what it covers). The assets by content key, sorted, not
  // by their absolute paths: a moved checkout names the same entries.
  Hasher h;
  h.str("bounce-reference").u64(kTracerVersion);
  const auto levelBytes = readFileBytes(level.source);
  h.u64(levelBytes.size()).bytes(levelBytes.data(), levelBytes.size());
  std::vector<std::string> contentKeys;
  for (const auto& [path, entry] : assets.entries()) contentKeys.push_back(entry.contentKey);
  std::sort(contentKeys.begin(), contentKeys.end());
  h.u64(contentKeys.size());
  for (const auto& k : contentKeys) h.str(k);
  h.pod(result.timeSeconds).pod(desc.camera.world).pod(desc.camera.yfovRad).pod(desc.camera.near).pod(desc.camera.far);
  h.u64(settings.width).u64(settings.height).u64(settings.spp).u64(settings.bounces);
  result.key = h.hex();
  result.cachePath = request.cacheDir / (result.key + ".pfm");
  return p;
}

}  // namespace

std::optional<gpu::FloatImage> loadCachedReference(const std::filesystem::path& file, std::uint32_t width,
                                                   std::uint32_t height) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  try {
    gpu::FloatImage cached = gpu::readPfm(file);
    if (cached.width == width && cached.height == height) return cached;
    log::warn(file.string() + ": cached reference has the wrong size; tracing again");
  } catch (const InputError& e) {
    log::warn(std::string(e.what()) + "; tracing again");
  }
  return std::nullopt;
}

ReferencePlan planReference(const ReferenceRequest& request) {
  const Prepared p = prepare(request);
  return {p.result.key, p.result.cachePath, p.settings.width, p.settings.height};
}

ReferenceResult renderReference(const ReferenceRequest& request) {
  Prepared p = prepare(request);
  ReferenceResult& result = p.result;
  if (auto cached = loadCachedReference(result.cachePath, p.settings.width, p.settings.height)) {
    result.image = std::move(*cached);
    result.fromCache = true;
    return result;
  }

  // 4. Trace and cache (writePfm writes atomically: temp file + rename).
  SceneBvh bvh(std::move(p.desc));
  result.triangles = bvh.triangleCount();
  result.image = trace(bvh, p.settings, &result.stats);
  gpu::writePfm(result.cachePath, result.image);
  return std::move(result);
}

}  // namespace bounce::ref
