#pragma once
// The shadow rays of incident::SceneVisibility (incident.hpp), with what blocks them left to the
// caller: RTF's bouncing step traces them through the static level AND the other posed objects
// (engine/gi/rtf/occluders.hpp), and its room shadows through the posed objects alone.
#include <functional>

#include <glm/glm.hpp>

#include "engine/render/gpu_types.hpp"

namespace bounce::gi::incident {

// `occluded(o, d, tMax)`: is anything on the ray from origin o along unit direction d before the
// light at distance tMax (∞ for a directional light)?
using RayTest = std::function<bool(glm::vec3 o, glm::vec3 d, float tMax)>;
// The fraction in [0, 1] of SceneVisibility::visible's rays from the receiver (the sphere of `radius`
// around p; 0: the point p, one ray) to `light` that `occluded` does not block.
float traceVisibility(const render::LightGpu& light, glm::vec3 p, float radius, const RayTest& occluded);

}  // namespace bounce::gi::incident
