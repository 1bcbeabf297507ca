#include "game/viewer_level.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "engine/asset/gltf_buffer.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/paths.hpp"
#include "engine/scene/asset_instances.hpp"
#include "game/session.hpp"

namespace bounce::game {

namespace {

using Json = nlohmann::ordered_json;

// Numbers as the shortest decimal that reads back as the same float (hand-editable files).
double num(float v) { return asset::shortestDecimal(v); }
Json vec(const glm::vec3& v) { return Json::array({num(v.x), num(v.y), num(v.z)}); }

// Path of `file` as the level at `levelDir` should write it: relative when both share a root.
std::string relativeTo(const std::filesystem::path& file, const std::filesystem::path& levelDir) {
  std::error_code ec;
  const auto rel = std::filesystem::relative(std::filesystem::absolute(file), std::filesystem::absolute(levelDir), ec);
  return (ec || rel.empty() ? std::filesystem::absolute(file) : rel).generic_string();
}

// Euler angles (degrees, the level's rotation_euler_deg: X then Y) that turn the camera's −Z
// towards the unit direction `f`: −Z rotated by X(p) then Y(y) is (−cos p sin y, sin p, −cos p cos y).
glm::vec3 eulerLookingAlong(const glm::vec3& f) {
  const float pitch = std::asin(std::clamp(f.y, -1.0f, 1.0f));
  const float yaw = std::atan2(-f.x, -f.z);
  return glm::degrees(glm::vec3(pitch, yaw, 0.0f));
}

std::filesystem::path groundAsset() { return contentDir() / "src/ground/ground.gltf"; }

std::filesystem::path viewerCacheFile(const std::filesystem::path& input, const std::string& suffix) {
  const auto abs = std::filesystem::absolute(input).lexically_normal();
  return cacheDir("levels") / (input.stem().string() + "-" + Hasher().str(abs.string()).hex().substr(0, 8) + suffix);
}

}  // namespace

bool isGltfFile(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb";
}

float AssetBounds::radius() const { return std::max(0.5f * glm::length(max - min), 1e-3f); }

AssetBounds assetBounds(const std::filesystem::path& asset, const std::filesystem::path& cookCache) {
  scene::MeshRef ref;
  ref.asset = std::filesystem::absolute(asset).lexically_normal();
  const asset::CookedAsset cooked = scene::cookForRef(ref, cookCache);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  scene::forEachInstancedNode(cooked, ref, glm::mat4(1.0f), [&](int n, const glm::mat4& world) {
    const asset::Node& node = cooked.nodes[std::size_t(n)];
    if (node.mesh < 0 || node.vlm.present) return;
    const asset::Bounds& b = cooked.meshes[std::size_t(node.mesh)].bounds;
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 corner{i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z};
      const glm::vec3 p = glm::vec3(world * glm::vec4(corner, 1.0f));
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  });
  if (!(lo.x <= hi.x) || !std::isfinite(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z))
    throwInputError(asset.string(), "/scenes", "no mesh to show in the default scene", "a glTF with at least one mesh");
  return {lo, hi};
}

std::string viewerLevelText(const std::filesystem::path& asset, const AssetBounds& bounds,
                            const std::filesystem::path& levelDir) {
  const glm::vec3 c = bounds.centre();
  const float r = bounds.radius();
  // The bounding sphere fits the vertical field of view with 5 % to spare.
  const float distance = 1.05f * r / std::sin(0.5f * glm::radians(kViewerYfovDeg));
  const glm::vec3 toCamera = glm::normalize(glm::vec3(0.45f, 0.4f, 1.0f));  // front, above, right
  const glm::vec3 eye = c + toCamera * distance;
  const float groundHalf = kViewerGroundHalf * r;
  const float groundY = bounds.min.y;

  Json level;
  level["bounce_level"] = 1;
  level["name"] = asset.filename().string();
  level["effects"] = Json::array({"direct", "shadows", "probes"});
  level["background"] = vec(glm::vec3(kViewerSky));
  level["probes"] = {{"spacing", num(2.0f * groundHalf / float(kViewerProbesPerAxis))}, {"order", 3}, {"rays", kViewerProbeRays}};
  Json entities = Json::array();
  entities.push_back({{"id", "asset"}, {"mesh", {{"asset", relativeTo(asset, levelDir)}}}});
  entities.push_back({{"id", "ground"},
                      {"transform", {{"translation", vec({c.x, groundY, c.z})}, {"scale", vec(glm::vec3(2.0f * groundHalf, 1.0f, 2.0f * groundHalf))}}},
                      {"mesh", {{"asset", relativeTo(groundAsset(), levelDir)}}}});
  entities.push_back({{"id", "camera"},
                      {"transform", {{"translation", vec(eye)}, {"rotation_euler_deg", vec(eulerLookingAlong(-toCamera))}}},
                      {"camera", {{"yfov_deg", num(kViewerYfovDeg)},
                                  {"near", num(0.02f * distance)},
                                  {"far", num(distance + 2.0f * (kViewerGroundHalf + 1.0f) * r)}}}});
  // The sun shines from the upper front left (its −Z turned down 45° and −35° about +Y), so the
  // shadow falls back and to the right, where the camera (front right) sees it.
  entities.push_back({{"id", "sun"},
                      {"transform", {{"rotation_euler_deg", vec({-45.0f, -35.0f, 0.0f})}}},
                      {"light", {{"type", "directional"}, {"color", vec(glm::vec3(1.0f, 0.96f, 0.9f))},
                                 {"intensity", num(kViewerSunIrradiance)}, {"shadows", true}}}});
  level["entities"] = std::move(entities);
  return level.dump(2) + "\n";
}

std::filesystem::path levelPathFor(const std::filesystem::path& input) {
  if (!isGltfFile(input)) return input;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(input, ec))
    throwInputError(input.string(), "file", "not found", "an existing .gltf or .glb file");
  const auto file = viewerCacheFile(input, ".json");
  writeFileAtomic(file, viewerLevelText(input, assetBounds(input, cookCacheDir()), file.parent_path()));
  return file;
}

std::filesystem::path captureScriptPathFor(const std::filesystem::path& input) {
  if (!isGltfFile(input)) return input;
  const auto level = levelPathFor(input);
  Json script;
  script["bounce_capture"] = 1;
  script["level"] = level.filename().string();
  script["resolution"] = Json::array({640, 480});
  script["dt"] = 1.0 / 60.0;
  script["frames"] = 1;
  script["capture"] = Json::array({0});
  const auto file = viewerCacheFile(input, ".capture.json");
  writeFileAtomic(file, script.dump(2) + "\n");
  return file;
}

}  // namespace bounce::game
