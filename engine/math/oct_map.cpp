#include "engine/math/oct_map.hpp"

namespace bounce::math {

namespace glsl {
using namespace glm;
#include "shaders/probes/probe_tiles.glsl"
#include "shaders/common/oct_map.glsl"
static_assert(OCT_MAP_RES == kOctMapRes && OCT_MAP_TEXELS == kOctMapTexels, "keep in step with oct_map.glsl");
}  // namespace glsl

int octTexel(const glm::vec3& d) { return glsl::octTexel(d); }
glm::vec3 octTexelDirection(int t) { return glsl::octTexelDirection(t); }

}  // namespace bounce::math
