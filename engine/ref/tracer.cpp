#include "engine/ref/tracer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"
#include "engine/math/sampling.hpp"
#include "engine/ref/surface_albedo.hpp"

namespace bounce::ref {
namespace {

constexpr std::uint32_t kTile = 16;  // pixels per tile side: enough work per task, good cache locality
constexpr double kInvPi = 1.0 / math::kPi;
// Ray origins move off the surface by this fraction of the position's magnitude (at least of 1 m),
// so a secondary ray cannot hit the triangle it leaves: far above Embree's float rounding
// (~1e-7 relative), far below any feature of a level (0.1 mm at 1 m).
constexpr float kOffsetScale = 1e-4f;
// Shadow rays stop this fraction short of a point or spot light, so geometry *at* the light's
// position (a lamp inside its fixture) does not block it.
constexpr float kShadowShorten = 1e-4f;

glm::vec3 offsetOrigin(const glm::vec3& p, const glm::vec3& ng, const glm::vec3& dir) {
  const float scale = std::max({1.0f, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  const float eps = kOffsetScale * scale;
  return p + (glm::dot(dir, ng) >= 0.0f ? eps : -eps) * ng;
}

double maxComponent(const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); }

}  // namespace

CameraRay cameraRay(const RefCamera& camera, std::uint32_t width, std::uint32_t height, std::uint32_t x,
                    std::uint32_t y) {
  // NDC of the pixel centre, as the lighting pass reconstructs it: ((x + ½)/W)·2 − 1, likewise y.
  const double ndcX = (x + 0.5) / width * 2.0 - 1.0;
  const double ndcY = (y + 0.5) / height * 2.0 - 1.0;
  // Inverse of perspectiveVk: x_clip = x_v/(aspect·tan(fov/2)), y_clip = −y_v/tan(fov/2) (Vulkan's
  // +Y-down flip), w_clip = −z_v. The view-space point at z_v = −1 is therefore:
  const double tanHalf = std::tan(0.5 * double(camera.yfovRad));
  const double aspect = double(width) / double(height);
  const glm::dvec3 view(ndcX * aspect * tanHalf, -ndcY * tanHalf, -1.0);
  const double length = glm::length(view);
  CameraRay r;
  r.origin = glm::vec3(camera.world[3]);
  r.direction = glm::vec3(glm::normalize(glm::dmat3(glm::mat3(camera.world)) * view));
  // Depth clipping happens on view-space z: z_v = −near at t = near·|view| along the unit ray.
  r.tMin = float(camera.near * length);
  r.tMax = float(camera.far * length);
  return r;
}

glm::dvec3 tracePath(const SceneBvh& bvh, const TraceSettings& settings, std::uint32_t x, std::uint32_t y,
                     std::uint32_t sample, std::uint64_t& rays) {
  math::Pcg32 rng = math::Pcg32::fromIndex(((std::uint64_t(y) * settings.width + x) << 32) | sample);
  const CameraRay camera = cameraRay(bvh.scene().camera, settings.width, settings.height, x, y);
  return tracePathFrom(bvh, camera.origin, camera.direction, camera.tMin, camera.tMax, settings.bounces, rng, rays);
}

glm::dvec3 tracePathFrom(const SceneBvh& bvh, glm::vec3 origin, glm::vec3 dir, float tMin, float tMax,
                         std::uint32_t bounces, math::Pcg32& rng, std::uint64_t& rays, Hit* firstHit,
                         bool* hitAnything) {
  const SceneDesc& scene = bvh.scene();
  if (hitAnything) *hitAnything = false;
  glm::dvec3 radiance(0.0), throughput(1.0);
  for (std::uint32_t depth = 0;; ++depth) {
    Hit hit;
    ++rays;
    if (!bvh.intersect(origin, dir, tMin, tMax, hit)) {
      radiance += throughput * glm::dvec3(scene.background);
      break;
    }
    if (depth == 0) {
      if (firstHit) *firstHit = hit;
      if (hitAnything) *hitAnything = true;
    }
    const RefMaterial& mat = scene.materials[hit.material];
    const glm::vec3 albedo = surfaceAlbedo(scene, hit);  // gbuffer.frag stores clamp(albedo, 0, 1)
    glm::vec3 emissive = mat.emissive;
    if (mat.emissiveTexture >= 0) emissive *= scene.textures[mat.emissiveTexture].sample(hit.uv);
    radiance += throughput * glm::dvec3(emissive);

    // Two-sided shading (gbuffer.frag): both normals face the side the ray came from.
    glm::vec3 n = hit.shadingNormal, ng = hit.geometricNormal;
    if (glm::dot(n, dir) > 0.0f) n = -n;
    if (glm::dot(ng, dir) > 0.0f) ng = -ng;

    // Next-event estimation: lighting.frag's sum with a traced visibility V_i instead of a shadow map.
    if (albedo != glm::vec3(0.0f)) {
      glm::dvec3 irradiance(0.0);
      for (const RefLight& light : scene.lights) {
        glm::vec3 toLight;
        float dist;
        const glm::vec3 e = incidentIrradiance(light, hit.position, toLight, dist);
        const float cosTheta = glm::dot(n, toLight);
        // A light behind the geometric surface does not reach it, whatever the shading normal says.
        if (cosTheta <= 0.0f || glm::dot(ng, toLight) <= 0.0f || e == glm::vec3(0.0f)) continue;
        ++rays;
        float reach = light.type == RefLightType::Directional ? dist : dist * (1.0f - kShadowShorten);
        glm::vec3 aim = toLight;
        if (light.radius > 0.0f && light.type != RefLightType::Directional && dist > light.radius) {
          // A sphere light (scene::Light::radius; SL local lights, engine/gi/sl/local_light.hpp): the
          // centre's unshadowed E cos θ times the visible fraction of the sphere's cap, estimated by
          // one shadow ray at a direction uniform in the cap's solid angle, stopping at the sphere.
          // No random numbers are drawn for point lights, so their references are unchanged.
          const glm::dvec2 u = rng.next2D();
          const double sinA = double(light.radius) / double(dist), cosA = std::sqrt(std::max(0.0, 1.0 - sinA * sinA));
          const double c = 1.0 - u.x * (1.0 - cosA), s = std::sqrt(std::max(0.0, 1.0 - c * c));
          const double phi = 2.0 * math::kPi * u.y;
          const glm::dvec3 w(toLight);
          const glm::dvec3 t = glm::normalize(std::abs(w.x) < 0.9 ? glm::cross(w, glm::dvec3(1, 0, 0)) : glm::cross(w, glm::dvec3(0, 1, 0)));
          aim = glm::vec3(c * w + s * (std::cos(phi) * t + std::sin(phi) * glm::cross(w, t)));
          // Near intersection with the sphere along aim: t = d c − √(R² − d² s²) (d = dist, c·s the aim's angle).
          const double d = double(dist), h2 = std::max(0.0, double(light.radius) * light.radius - d * d * s * s);
          reach = float((d * c - std::sqrt(h2)) * (1.0 - double(kShadowShorten)));
          if (glm::dot(ng, aim) <= 0.0f) continue;  // this part of the sphere is below the surface
        }
        if (bvh.occluded(offsetOrigin(hit.position, ng, aim), aim, 0.0f, reach)) continue;
        irradiance += glm::dvec3(e) * double(cosTheta);
      }
      radiance += throughput * glm::dvec3(albedo) * kInvPi * irradiance;
    }

    if (depth >= bounces) break;
    // Cosine-weighted bounce: Lambert BRDF ρ/π × cosθ / pdf (cosθ/π) = ρ.
    throughput *= glm::dvec3(albedo);
    if (depth >= kRouletteAfter) {
      const double survive = std::min(1.0, maxComponent(throughput));
      if (survive <= 0.0 || rng.nextDouble() >= survive) break;
      throughput /= survive;
    }
    if (maxComponent(throughput) <= 0.0) break;
    const glm::vec3 wi = glm::vec3(math::cosineHemisphere(rng.next2D(), glm::dvec3(n)));
    // Sampled about the shading normal, wi can point into the surface; a reflection cannot go
    // there, so the path ends (pbrt-v3 BSDF::f: reflection only when wi, wo share a side of ng).
    if (glm::dot(wi, ng) <= 0.0f) break;
    origin = offsetOrigin(hit.position, ng, wi);
    dir = glm::normalize(wi);
    tMin = 0.0f;
    tMax = std::numeric_limits<float>::infinity();
  }
  return radiance;
}

gpu::FloatImage trace(const SceneBvh& bvh, const TraceSettings& settings, TraceStats* stats) {
  if (settings.width == 0 || settings.height == 0 || settings.spp == 0)
    throw InternalError("ref::trace: empty image or zero samples per pixel");
  const auto start = std::chrono::steady_clock::now();
  const std::uint32_t tilesX = (settings.width + kTile - 1) / kTile, tilesY = (settings.height + kTile - 1) / kTile;
  const std::size_t tiles = std::size_t(tilesX) * tilesY;
  const std::uint32_t passSpp = std::max(1u, settings.passSpp);
  const std::uint32_t passes = (settings.spp + passSpp - 1) / passSpp;

  std::vector<glm::dvec3> sum(std::size_t(settings.width) * settings.height, glm::dvec3(0.0));
  std::atomic<std::uint64_t> rays{0}, nonFinite{0};
  std::optional<Progress> progress;
  if (!settings.label.empty()) progress.emplace(settings.label, tiles * passes);
  for (std::uint32_t pass = 0; pass < passes; ++pass) {
    const std::uint32_t first = pass * passSpp, last = std::min(settings.spp, first + passSpp);
    parallelFor(0, tiles, [&](std::size_t tile) {
      const std::uint32_t x0 = std::uint32_t(tile % tilesX) * kTile, y0 = std::uint32_t(tile / tilesX) * kTile;
      std::uint64_t tileRays = 0, tileBad = 0;
      for (std::uint32_t y = y0; y < std::min(y0 + kTile, settings.height); ++y)
        for (std::uint32_t x = x0; x < std::min(x0 + kTile, settings.width); ++x) {
          glm::dvec3& acc = sum[std::size_t(y) * settings.width + x];
          for (std::uint32_t s = first; s < last; ++s) {
            const glm::dvec3 l = tracePath(bvh, settings, x, y, s, tileRays);
            // A NaN/Inf sample would poison the pixel; none is expected, so count and report it.
            if (std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z)) acc += l;
            else ++tileBad;
          }
        }
      rays += tileRays;
      nonFinite += tileBad;
      if (progress) progress->advance();
    });
  }
  if (progress) progress->finish();
  if (nonFinite > 0) log::warn("reference: " + std::to_string(nonFinite.load()) + " non-finite path samples dropped");

  gpu::FloatImage image{settings.width, settings.height, std::vector<float>(sum.size() * 3)};
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const glm::dvec3 mean = sum[i] / double(settings.spp);
    image.rgb[3 * i] = float(mean.x), image.rgb[3 * i + 1] = float(mean.y), image.rgb[3 * i + 2] = float(mean.z);
  }
  if (stats) {
    stats->rays = rays.load();
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return image;
}

}  // namespace bounce::ref
