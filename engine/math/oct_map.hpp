#pragma once
// Octahedral direction maps, the C++ face of shaders/common/oct_map.glsl (compiled from it in
// oct_map.cpp, so C++ and GLSL pick one texel for one direction): a kOctMapRes² grid of texels over
// the octahedral square of shaders/probes/probe_tiles.glsl (the probes' maps of the static radiance,
// engine/gi/probes/probe_volume.hpp dirMap).
#include <glm/glm.hpp>

namespace bounce::math {

inline constexpr int kOctMapRes = 16;
inline constexpr int kOctMapTexels = kOctMapRes * kOctMapRes;

// Row-major texel (y · kOctMapRes + x) whose square holds the unit direction.
int octTexel(const glm::vec3& unitDirection);
// Unit direction through texel t's centre.
glm::vec3 octTexelDirection(int texel);

}  // namespace bounce::math
