#pragma once
// CPU mirrors of the GLSL structs in shaders/common (std140/std430 layouts: every member a vec4 or
// mat4, so both layouts agree). static_asserts pin the sizes the shaders expect.
#include <cstdint>
#include <glm/glm.hpp>

namespace bounce::render {

struct CameraGpu {  // frame.glsl: Camera
  glm::mat4 view;
  glm::mat4 proj;
  glm::mat4 viewProj;
  glm::mat4 invViewProj;
  glm::vec4 position;
  glm::vec4 resolution;  // width, height, 1/width, 1/height
};
static_assert(sizeof(CameraGpu) == 4 * 64 + 2 * 16);

struct InstanceGpu {  // frame.glsl: Instance
  glm::mat4 model;
  glm::mat4 normalMatrix;
  glm::vec4 albedo;    // rgb factor, a = 1 when a base colour texture is bound
  glm::vec4 emissive;  // rgb factor, a = 1 when an emissive texture is bound
  glm::uvec4 ids;      // x = entity id
};
static_assert(sizeof(InstanceGpu) == 2 * 64 + 3 * 16);

enum class LightType : std::uint32_t { Directional = 0, Point = 1, Spot = 2 };

struct LightGpu {  // lights.glsl: Light
  glm::vec4 positionType;
  glm::vec4 directionRange;
  glm::vec4 radiance;
  glm::vec4 cone;
  glm::vec4 shadow;  // x first layer (<0 none), y texel/metre, z texel constant, w depth bias
};
static_assert(sizeof(LightGpu) == 5 * 16);

// Capacity of the lighting and debug-view passes' uniform blocks (lights.glsl: kMaxLights,
// kMaxShadowLayers); the frame's light and shadow-matrix buffers are padded to it. A frame with
// more is an error (Renderer::writeFrameData), not a silent cut.
inline constexpr std::uint32_t kMaxLights = 128;
inline constexpr std::uint32_t kMaxShadowLayers = 192;

}  // namespace bounce::render
