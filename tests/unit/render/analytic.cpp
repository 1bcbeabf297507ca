#include "tests/unit/render/analytic.hpp"

#include <algorithm>
#include <glm/gtc/constants.hpp>
#include <stdexcept>

#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

namespace bounce::rtest {

Frame renderLevel(const std::filesystem::path& level, std::uint32_t width, std::uint32_t height,
                  const std::optional<std::vector<std::string>>& effects) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, game::loadLevelWithEffects(level, effects));
  session.update(0.0);
  gpu::OffscreenPresenter presenter(ctx, {width, height});
  render::FrameSettings settings;
  settings.keepHdr = true;
  session.render(presenter, settings);
  Frame f;
  f.width = width;
  f.height = height;
  f.rgb = session.renderer().readHdr();
  f.passes = session.renderer().executedPasses();
  return f;
}

namespace {
const scene::EntityDesc& entity(const scene::Level& level, const std::string& id) {
  for (const auto& e : level.entities)
    if (e.id == id) return e;
  throw std::runtime_error("test level " + level.source.string() + " has no entity '" + id + "'");
}
}  // namespace

FloorScene readFloorScene(const scene::Level& level) {
  FloorScene s;
  const auto& cam = entity(level, "camera");
  s.eye = cam.transform.translation;
  s.cameraRotation = cam.transform.rotation;
  s.yfovRad = cam.camera.value().yfovRad;
  const auto& floor = entity(level, "floor");
  s.floorY = floor.transform.translation.y;
  s.albedo = floor.material.value().albedo.value();
  const auto& lamp = entity(level, "lamp");
  s.light = lamp.light.value();
  s.lightPosition = lamp.transform.translation;
  s.lightDirection = glm::normalize(lamp.transform.rotation * glm::vec3(0, 0, -1));
  return s;
}

std::optional<glm::vec3> floorPoint(const FloorScene& s, std::uint32_t width, std::uint32_t height, std::uint32_t x,
                                    std::uint32_t y) {
  const float aspect = float(width) / float(height);
  const float t = std::tan(0.5f * s.yfovRad);
  // Pixel centre in [-1, 1]²; +sx to the camera's right, +sy to its up (row 0 is the top row).
  const float sx = ((float(x) + 0.5f) / float(width) * 2.0f - 1.0f) * t * aspect;
  const float sy = (1.0f - (float(y) + 0.5f) / float(height) * 2.0f) * t;
  const glm::vec3 dir = s.cameraRotation * glm::vec3(sx, sy, -1.0f);
  if (dir.y >= 0.0f) return std::nullopt;
  const float along = (s.floorY - s.eye.y) / dir.y;
  return s.eye + along * dir;
}

glm::vec3 irradiance(const FloorScene& s, glm::vec3 p) {
  const glm::vec3 n(0, 1, 0);
  const glm::vec3 color = s.light.color * s.light.intensity;
  if (s.light.type == scene::LightType::Directional) return color * std::max(0.0f, glm::dot(n, -s.lightDirection));
  const glm::vec3 v = s.lightPosition - p;
  const float d = glm::length(v);
  const float h = v.y;
  if (h <= 0.0f) return glm::vec3(0.0f);
  glm::vec3 e = color * h / (d * d * d);
  if (s.light.type == scene::LightType::Spot) {
    const float cosAlpha = glm::dot(-v / d, s.lightDirection);
    const float cosOuter = std::cos(s.light.outerConeRad), cosInner = std::cos(s.light.innerConeRad);
    const float k = std::clamp((cosAlpha - cosOuter) / (cosInner - cosOuter), 0.0f, 1.0f);
    e *= k * k;
  }
  return e;
}

}  // namespace bounce::rtest
