#include "engine/ref/scene_bvh.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/core/error.hpp"

namespace bounce::ref {

// lights.glsl compiled as C++ (its header): the passes' light math, one copy. Light has the
// members of the shader's struct (render::LightGpu's; engine/ref does not depend on render).
// Outside the anonymous namespace: there, cubeFace (not called here) would warn as unused.
namespace lightsglsl {
using namespace glm;
struct Light {
  vec4 positionType, directionRange, radiance, cone, shadow;
};
#define BOUNCE_LIGHTS_HOST
#define LIGHTS_OUT(T) T&
#include "shaders/common/lights.glsl"
#undef LIGHTS_OUT
#undef BOUNCE_LIGHTS_HOST
}  // namespace lightsglsl

namespace {

// sRGB EOTF (IEC 61966-2-1), what the GPU applies to each texel of an *_SRGB image before filtering.
float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

void check(bool ok, const std::string& what) {
  if (!ok) throw InternalError("ref::SceneBvh: " + what);
}

}  // namespace

RefTexture makeTexture(std::uint32_t width, std::uint32_t height, const std::vector<std::uint8_t>& rgba8, bool srgb) {
  RefTexture t;
  if (width == 0 || height == 0 || rgba8.size() != std::size_t(width) * height * 4) {
    t.width = t.height = 1;
    t.texels = {glm::vec3(1.0f)};
    return t;
  }
  float lut[256];
  for (int i = 0; i < 256; ++i) lut[i] = srgb ? srgbToLinear(i / 255.0f) : i / 255.0f;
  t.width = width;
  t.height = height;
  t.texels.resize(std::size_t(width) * height);
  for (std::size_t i = 0; i < t.texels.size(); ++i)
    t.texels[i] = {lut[rgba8[4 * i]], lut[rgba8[4 * i + 1]], lut[rgba8[4 * i + 2]]};
  return t;
}

glm::vec3 RefTexture::sample(glm::vec2 uv) const {
  if (texels.empty()) return glm::vec3(1.0f);
  // Continuous texel coordinates: texel i covers [i, i+1), its centre is i + ½.
  const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return texels[0];
  const float fx = std::floor(x), fy = std::floor(y);
  const float ax = x - fx, ay = y - fy;
  auto wrap = [](float i, std::uint32_t n) {
    const double m = std::fmod(double(i), double(n));
    return std::uint32_t(m < 0.0 ? m + n : m) % n;
  };
  const std::uint32_t x0 = wrap(fx, width), x1 = wrap(fx + 1.0f, width);
  const std::uint32_t y0 = wrap(fy, height), y1 = wrap(fy + 1.0f, height);
  auto at = [&](std::uint32_t i, std::uint32_t j) { return texels[std::size_t(j) * width + i]; };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), ax), glm::mix(at(x0, y1), at(x1, y1), ax), ay);
}

glm::vec3 incidentIrradiance(const RefLight& light, const glm::vec3& p, glm::vec3& toLight, float& dist) {
  const std::uint32_t type = light.type == RefLightType::Directional ? lightsglsl::kLightDirectional
                             : light.type == RefLightType::Spot      ? lightsglsl::kLightSpot
                                                                     : lightsglsl::kLightPoint;
  const lightsglsl::Light l{glm::vec4(light.position, float(type)), glm::vec4(light.direction, light.range),
                            glm::vec4(light.radiance, 0.0f), glm::vec4(light.cosOuter, light.cosInner, 0.0f, 0.0f),
                            glm::vec4(0.0f)};
  return lightsglsl::incidentIrradiance(l, p, toLight, dist);
}

namespace {

// One Embree device for every SceneBvh of the process, each BVH holding a reference (session-18 review):
// RTF's occluders build one BVH per object, and a device each cost its own memory pools (and its own
// threads, with Embree's internal tasking). Embree's devices are thread-safe, and rtcGetDeviceError
// keeps its error code per thread, so the build check below still reads this BVH's own error. The
// holder's reference is dropped at exit; the device goes with the last BVH.
RTCDevice sharedDevice() {
  struct Holder {
    RTCDevice device = rtcNewDevice(nullptr);
    ~Holder() {
      if (device) rtcReleaseDevice(device);
    }
  };
  static const Holder holder;  // created once, thread-safe (C++11 statics)
  return holder.device;
}

}  // namespace

struct SceneBvh::Embree {
  RTCDevice device = nullptr;  // sharedDevice(), one reference held
  RTCScene scene = nullptr;
  std::vector<std::uint32_t> meshOfGeometry;  // Embree geometry id → SceneDesc::meshes index
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

SceneBvh::SceneBvh(SceneDesc scene) : scene_(std::move(scene)), embree_(std::make_unique<Embree>()) {
  // The scene comes from our own code (reference_scene.cpp or a test), so a broken one is a bug.
  for (std::size_t m = 0; m < scene_.meshes.size(); ++m) {
    const RefMesh& mesh = scene_.meshes[m];
    const std::string name = "mesh " + std::to_string(m);
    check(mesh.normals.size() == mesh.positions.size(), name + ": one normal per position");
    check(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size(), name + ": uvs empty or one per position");
    check(mesh.indices.size() % 3 == 0, name + ": index count not a multiple of 3");
    check(mesh.material < scene_.materials.size(), name + ": material out of range");
    for (std::uint32_t i : mesh.indices) check(i < mesh.positions.size(), name + ": index out of range");
  }
  for (const RefMaterial& mat : scene_.materials) {
    check(mat.albedoTexture < int(scene_.textures.size()), "albedo texture out of range");
    check(mat.emissiveTexture < int(scene_.textures.size()), "emissive texture out of range");
  }

  embree_->device = sharedDevice();
  check(embree_->device != nullptr, "rtcNewDevice failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  rtcRetainDevice(embree_->device);
  rtcGetDeviceError(embree_->device);  // clears a code an earlier call on this thread left on the shared device
  embree_->scene = rtcNewScene(embree_->device);
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);  // watertight: no leaks along shared edges
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  for (std::size_t m = 0; m < scene_.meshes.size(); ++m) {
    const RefMesh& mesh = scene_.meshes[m];
    if (mesh.indices.empty()) continue;
    RTCGeometry g = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree pads these buffers itself (its SIMD loads read past the last vertex).
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                         3 * sizeof(float), mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      std::copy_n(&mesh.positions[i].x, 3, v + 3 * i);
    auto* idx = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(std::uint32_t), mesh.indices.size() / 3));
    std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(embree_->scene, g);
    rtcReleaseGeometry(g);
    if (embree_->meshOfGeometry.size() <= id) embree_->meshOfGeometry.resize(id + 1, 0);
    embree_->meshOfGeometry[id] = static_cast<std::uint32_t>(m);
    triangles_ += mesh.indices.size() / 3;
  }
  rtcCommitScene(embree_->scene);
  const RTCError err = rtcGetDeviceError(embree_->device);
  check(err == RTC_ERROR_NONE, "Embree error " + std::to_string(int(err)) + " while building the BVH");
}

SceneBvh::~SceneBvh() = default;

bool SceneBvh::intersect(const glm::vec3& o, const glm::vec3& d, float tMin, float tMax, Hit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = tMin;
  rh.ray.tfar = tMax;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(embree_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

  const RefMesh& mesh = scene_.meshes[embree_->meshOfGeometry[rh.hit.geomID]];
  const std::uint32_t* tri = &mesh.indices[3 * std::size_t(rh.hit.primID)];
  const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;  // Embree: p = w·p0 + u·p1 + v·p2
  const glm::vec3 &p0 = mesh.positions[tri[0]], &p1 = mesh.positions[tri[1]], &p2 = mesh.positions[tri[2]];
  hit.t = rh.ray.tfar;
  hit.position = w * p0 + u * p1 + v * p2;
  const glm::vec3 ng = glm::cross(p1 - p0, p2 - p0);
  const float ngLength = glm::length(ng);
  hit.geometricNormal = ngLength > 0.0f ? ng / ngLength : -d;
  const glm::vec3 ns = w * mesh.normals[tri[0]] + u * mesh.normals[tri[1]] + v * mesh.normals[tri[2]];
  const float nsLength = glm::length(ns);
  hit.shadingNormal = nsLength > 0.0f && std::isfinite(nsLength) ? ns / nsLength : hit.geometricNormal;
  hit.uv = mesh.uvs.empty() ? glm::vec2(0.0f) : w * mesh.uvs[tri[0]] + u * mesh.uvs[tri[1]] + v * mesh.uvs[tri[2]];
  hit.material = mesh.material;
  hit.mesh = embree_->meshOfGeometry[rh.hit.geomID];
  hit.triangle = rh.hit.primID;
  hit.barycentric = glm::vec3(w, u, v);
  return true;
}

bool SceneBvh::occluded(const glm::vec3& o, const glm::vec3& d, float tMin, float tMax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = o.x, ray.org_y = o.y, ray.org_z = o.z;
  ray.dir_x = d.x, ray.dir_y = d.y, ray.dir_z = d.z;
  ray.tnear = tMin;
  ray.tfar = tMax;
  ray.mask = 0xffffffffu;
  rtcOccluded1(embree_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to −∞ on an occluded ray
}

void hashGeometry(Hasher& h, const SceneDesc& object) {
  h.u64(object.meshes.size());
  for (const auto& m : object.meshes) {
    h.u64(m.positions.size()).bytes(m.positions.data(), m.positions.size() * sizeof(glm::vec3));
    h.u64(m.normals.size()).bytes(m.normals.data(), m.normals.size() * sizeof(glm::vec3));
    h.u64(m.uvs.size()).bytes(m.uvs.data(), m.uvs.size() * sizeof(glm::vec2));
    h.u64(m.indices.size()).bytes(m.indices.data(), m.indices.size() * sizeof(std::uint32_t));
    h.pod(m.material);
  }
  h.u64(object.materials.size());
  for (const auto& m : object.materials) h.pod(m.albedo).pod(m.albedoTexture);
  h.u64(object.textures.size());
  for (const auto& t : object.textures)
    h.pod(t.width).pod(t.height).bytes(t.texels.data(), t.texels.size() * sizeof(glm::vec3));
}

}  // namespace bounce::ref
