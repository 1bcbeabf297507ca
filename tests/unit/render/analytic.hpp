#pragma once
// Shared helpers of the analytic render tests: render one frame of a test level headless and
// read back its linear HDR radiance, and the closed-form radiance of the floor of the
// tests/data/render/plane-*.json levels.
//
// The closed forms use only what the level FILE says (entity transforms and light parameters as
// loadLevel parsed them), never the renderer's extracted RenderWorld, so a wrong light direction,
// a mirrored camera or a Y flip in the renderer shows up as a mismatch.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/render/renderer.hpp"
#include "engine/scene/level.hpp"

namespace bounce::rtest {

inline const std::filesystem::path kDataDir = std::filesystem::path(BOUNCE_SOURCE_DIR) / "tests/data/render";

// One rendered frame: linear radiance as float RGB, rows top to bottom, and what ran.
struct Frame {
  std::uint32_t width = 0, height = 0;
  std::vector<float> rgb;
  std::vector<std::string> passes;  // Renderer::executedPasses()
  glm::vec3 at(std::uint32_t x, std::uint32_t y) const {
    const std::size_t i = (std::size_t(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// Loads `level` (with an optional effects override), simulates t = 0 and renders one frame of
// `width`×`height` through an OffscreenPresenter with keepHdr; uses the test's shared Context.
Frame renderLevel(const std::filesystem::path& level, std::uint32_t width, std::uint32_t height,
                  const std::optional<std::vector<std::string>>& effects = std::nullopt);

// The floor scene of the plane-*.json levels, as the level file describes it.
struct FloorScene {
  // Camera: world position, orientation (looks down local −Z, up local +Y), vertical fov.
  glm::vec3 eye{0.0f};
  glm::quat cameraRotation{1, 0, 0, 0};
  float yfovRad = 1.0f;
  float floorY = 0.0f;     // the floor is the plane y = floorY, normal +Y
  glm::vec3 albedo{1.0f};  // ρ of the floor
  // The light named "lamp".
  scene::Light light;
  glm::vec3 lightPosition{0.0f};
  glm::vec3 lightDirection{0.0f, 0.0f, -1.0f};  // direction the light travels (local −Z)
};
FloorScene readFloorScene(const scene::Level& level);

// The floor point seen through the centre of pixel (x, y) of a width×height image (row 0 at the
// top, as Vulkan images and readHdr() store it); nullopt when the ray misses the floor plane.
std::optional<glm::vec3> floorPoint(const FloorScene& s, std::uint32_t width, std::uint32_t height, std::uint32_t x,
                                    std::uint32_t y);

// Irradiance E at floor point p (normal +Y) from the lamp, unshadowed:
//   point:        E = I·cosθ/d² = I·h/d³         (h: height of the light above p, d: distance)
//   spot:         the same × s², s = clamp((cos α − cos θ_outer)/(cos θ_inner − cos θ_outer), 0, 1)
//                 with α the angle between the spot axis and the ray to p (lights.glsl)
//   directional:  E = E₀·cosθ = E₀·(n·(−direction))₊
// times the light colour.
glm::vec3 irradiance(const FloorScene& s, glm::vec3 p);

// Lambertian reflected radiance L = ρ/π · E.
inline glm::vec3 floorRadiance(const FloorScene& s, glm::vec3 p) {
  return s.albedo * irradiance(s, p) / glm::pi<float>();
}

}  // namespace bounce::rtest
