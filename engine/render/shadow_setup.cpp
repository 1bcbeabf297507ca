#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/gpu_scene.hpp"

namespace bounce::render {

glm::mat4 perspectiveVk(float yfovRad, float aspect, float near, float far) {
  glm::mat4 p = glm::perspectiveRH_ZO(yfovRad, aspect, near, far);
  p[1][1] *= -1.0f;  // Vulkan clip space has +Y down
  return p;
}

namespace {

// Cube faces in lights.glsl cubeFace() order. Any up vector works (the lookup uses the same
// matrices); these are the usual cube-map ones.
const glm::vec3 kFaceDir[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const glm::vec3 kFaceUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

// Far plane: the farthest corner of the scene bounds from the light, so every caster fits.
float farthestCorner(const RenderWorld& w, glm::vec3 p) {
  float d = 0.0f;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c{i & 1 ? w.sceneMax.x : w.sceneMin.x, i & 2 ? w.sceneMax.y : w.sceneMin.y,
                i & 4 ? w.sceneMax.z : w.sceneMin.z};
    d = std::max(d, glm::length(c - p));
  }
  return std::max(d * 1.01f, 1e-3f);
}

}  // namespace

glm::vec2 depthViewRange(const RenderWorld& world) {
  const glm::vec3 eye(world.camera.position);
  const glm::vec3 nearest = glm::clamp(eye, world.sceneMin, world.sceneMax);
  const float lo = glm::length(nearest - eye);
  const float hi = std::min(farthestCorner(world, eye) / 1.01f, world.cameraFar);
  return {std::min(lo, hi), std::max(hi, lo + 1e-4f)};
}

void buildShadowLayers(RenderWorld& world, std::uint32_t resolution) {
  world.shadowLayers.clear();
  const float res = static_cast<float>(resolution);
  for (std::uint32_t i = 0; i < world.lights.size(); ++i) {
    LightGpu& l = world.lights[i];
    if (l.shadow.x < 0.0f) continue;  // this light casts no shadows
    const auto type = static_cast<LightType>(static_cast<std::uint32_t>(l.positionType.w + 0.5f));
    const glm::vec3 pos(l.positionType);
    const glm::vec3 dir(l.directionRange);
    l.shadow.x = static_cast<float>(world.shadowLayers.size());
    l.shadow.w = 0.0f;  // depth bias lives in the rasteriser (shadow_pass.hpp) and normal offset
    if (type == LightType::Point) {
      const float far = farthestCorner(world, pos);
      // Near plane: small against the scene, large enough to keep depth precision (1/1000 of far).
      const glm::mat4 proj = perspectiveVk(glm::half_pi<float>(), 1.0f, far * 1e-3f, far);
      for (int f = 0; f < 6; ++f)
        world.shadowLayers.push_back({proj * glm::lookAtRH(pos, pos + kFaceDir[f], kFaceUp[f]), i});
      l.shadow.y = 2.0f / res;  // texel footprint per metre of distance: 2·tan(45°)/resolution
      l.shadow.z = 0.0f;
    } else if (type == LightType::Spot) {
      const float far = farthestCorner(world, pos);
      const float halfAngle = std::min(std::acos(std::clamp(l.cone.x, -1.0f, 1.0f)) * 1.05f, 1.5f);
      const glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      world.shadowLayers.push_back(
          {perspectiveVk(2.0f * halfAngle, 1.0f, far * 1e-3f, far) * glm::lookAtRH(pos, pos + dir, up), i});
      l.shadow.y = 2.0f * std::tan(halfAngle) / res;
      l.shadow.z = 0.0f;
    } else {
      const glm::vec3 centre = 0.5f * (world.sceneMin + world.sceneMax);
      const float radius = std::max(0.5f * glm::length(world.sceneMax - world.sceneMin), 1e-3f);
      const glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      const glm::mat4 view = glm::lookAtRH(centre - dir * (2.0f * radius), centre, up);
      glm::mat4 proj = glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.0f, 4.0f * radius);
      proj[1][1] *= -1.0f;
      world.shadowLayers.push_back({proj * view, i});
      l.shadow.y = 0.0f;
      l.shadow.z = 2.0f * radius / res;
    }
  }
}

}  // namespace bounce::render
