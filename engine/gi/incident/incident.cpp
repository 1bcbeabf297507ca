#include "engine/gi/incident/incident.hpp"
#include "engine/gi/incident/shadow_rays.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/math/sh.hpp"

namespace bounce::gi::incident {

namespace glsl {
using namespace glm;
// lights.glsl compiled as C++ (its header): the Light struct is render::LightGpu (same members,
// same std430 layout); rangeWindow, cubeFace, incidentIrradiance and the kLight* type constants
// come from the shader file itself, so this CPU face, the passes and the path tracer (engine/ref,
// which compiles it too) share one copy of the light math.
using Light = render::LightGpu;
#define BOUNCE_LIGHTS_HOST
#define LIGHTS_OUT(T) T&
#include "shaders/common/lights.glsl"
#undef LIGHTS_OUT
#undef BOUNCE_LIGHTS_HOST
static_assert(kLightDirectional == uint(render::LightType::Directional) && kLightPoint == uint(render::LightType::Point) &&
              kLightSpot == uint(render::LightType::Spot));

// GLSL parameter qualifiers: `inout vec3 sh[9]` / `out float y[9]` decay to pointers, so writes
// reach the caller as they do in GLSL.
#define in
#define out
#define inout
#define BOUNCE_INCIDENT_HOST
#include "shaders/common/incident.glsl"
#undef BOUNCE_INCIDENT_HOST
#undef inout
#undef out
#undef in
}  // namespace glsl

void addLight(const render::LightGpu& light, glm::vec3 p, float radius, float visibility, RadianceSH& sh) {
  glsl::incidentAddLight(light, p, radius, visibility, sh.data());
}

void addCap(glm::vec3 toLight, float cosAlpha, glm::vec3 e, RadianceSH& sh) {
  glsl::incidentAddCap(toLight, cosAlpha, e, sh.data());
}

float capCosine(float radius, float dist) { return glsl::incidentCapCosine(radius, dist); }

glm::vec3 lightIrradiance(const render::LightGpu& light, glm::vec3 p, glm::vec3& toLight, float& dist) {
  return glsl::incidentIrradiance(light, p, toLight, dist);
}

ref::RefLight refLight(const render::LightGpu& l) {
  ref::RefLight r;
  const auto type = render::LightType(std::uint32_t(l.positionType.w + 0.5f));
  r.type = type == render::LightType::Directional ? ref::RefLightType::Directional
           : type == render::LightType::Spot      ? ref::RefLightType::Spot
                                                  : ref::RefLightType::Point;
  r.position = glm::vec3(l.positionType);
  r.direction = glm::vec3(l.directionRange);
  r.radiance = glm::vec3(l.radiance);
  r.range = l.directionRange.w;
  r.cosOuter = l.cone.x;
  r.cosInner = l.cone.y;
  return r;
}

namespace {

// Ray origins' disc: p plus 8 points at 0.7·radius around it, in the plane facing the light, at
// angles k·45° (the centre ray and two rings' worth of spread for a soft 0..1 fraction).
constexpr float kDiscFraction = 0.7f;
// Shadow rays stop this fraction short of a point light (ref tracer's kShadowShorten), so a light
// sitting on a surface is not occluded by it.
constexpr float kShorten = 1e-4f;

}  // namespace

SceneVisibility::SceneVisibility(ref::SceneDesc scene) : bvh_(std::move(scene)) {}

float SceneVisibility::visible(const render::LightGpu& light, glm::vec3 p, float radius) const {
  return traceVisibility(light, p, radius, [this](glm::vec3 o, glm::vec3 d, float tMax) { return bvh_.occluded(o, d, 0.0f, tMax); });
}

float traceVisibility(const render::LightGpu& light, glm::vec3 p, float radius, const RayTest& occluded) {
  const ref::RefLight l = refLight(light);
  const bool directional = l.type == ref::RefLightType::Directional;
  glm::vec3 toLight = directional ? -l.direction : l.position - p;
  const float len = glm::length(toLight);
  if (!(len > 0.0f)) return 1.0f;  // the light at the receiver's centre: nothing in between
  toLight /= len;
  // An orthonormal frame (t, b) of the disc facing the light (Frisvad-style, branch on the sign).
  const glm::vec3 t = std::abs(toLight.x) < 0.9f ? glm::normalize(glm::cross(toLight, glm::vec3(1, 0, 0)))
                                                 : glm::normalize(glm::cross(toLight, glm::vec3(0, 1, 0)));
  const glm::vec3 b = glm::cross(toLight, t);
  const int rays = radius > 0.0f ? kVisibilityRays : 1;
  int reach = 0;
  for (int k = 0; k < rays; ++k) {
    glm::vec3 o = p;
    if (k > 0) {
      const float a = float(k - 1) * 0.78539816339744831f;  // 45°
      o += kDiscFraction * radius * (std::cos(a) * t + std::sin(a) * b);
    }
    glm::vec3 d = toLight;
    float tMax = std::numeric_limits<float>::infinity();
    if (!directional) {
      d = l.position - o;
      const float dl = glm::length(d);
      if (!(dl > 0.0f)) {
        ++reach;
        continue;
      }
      d /= dl;
      tMax = dl * (1.0f - kShorten);
    }
    if (!occluded(o, d, tMax)) ++reach;
  }
  return float(reach) / float(rays);
}

RadianceSH IndirectSource::radianceShAndMap(glm::vec3 p, DirectionMap& map) const {
  const RadianceSH sh = radianceSH(p);
  for (int t = 0; t < math::kOctMapTexels; ++t)
    map[std::size_t(t)] = sh::evalSum<glm::vec3, float>(std::span<const glm::vec3>(sh), math::octTexelDirection(t));
  return sh;
}

RadianceSH ConstantEnvironment::radianceSH(glm::vec3) const {
  RadianceSH c{};
  // A constant function L has the single coefficient ∫ L Y_00 dω = 4π L Y_00 = 2√π L.
  c[0] = radiance_ * static_cast<float>(4.0 * math::kPi * sh::constants::kY00);
  return c;
}

RadianceSH irradianceSH(const RadianceSH& radiance) {
  const auto e = sh::convolveCosine<glm::vec3>(std::span<const glm::vec3>(radiance));
  RadianceSH out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = e[i];
  return out;
}

RadianceSH Service::lightsSH(glm::vec3 p, float radius, std::span<const render::LightGpu> lights,
                             const BandWindow& window) const {
  RadianceSH sh{};
  for (const render::LightGpu& light : lights) {
    const float v = visibility_ ? std::clamp(visibility_->visible(light, p, radius), 0.0f, 1.0f) : 1.0f;
    if (v > 0.0f) addLight(light, p, radius, v, sh);
  }
  applyWindow(window, sh);
  return sh;
}

void applyWindow(const BandWindow& window, RadianceSH& sh) {
  for (std::size_t i = 0; i < sh.size(); ++i) sh[i] *= window[i == 0 ? 0 : i < 4 ? 1 : 2];
}

RadianceSH Service::radianceSH(glm::vec3 p, float radius, std::span<const render::LightGpu> lights,
                               const BandWindow& window, RadianceSH* lightsPart) const {
  RadianceSH sh = lightsSH(p, radius, lights, window);
  if (lightsPart) *lightsPart = sh;
  if (indirect_) {
    const RadianceSH ind = indirect_->radianceSH(p);
    for (std::size_t i = 0; i < sh.size(); ++i) sh[i] += ind[i];
  }
  return sh;
}

}  // namespace bounce::gi::incident
