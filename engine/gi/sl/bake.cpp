#include "engine/gi/sl/bake.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"
#include "engine/gi/sl/bounce_scale.hpp"
#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/sphere_fit.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/ref/surface_albedo.hpp"

namespace bounce::gi::sl {
namespace {

constexpr double kPi = math::kPi;

struct Triangles {
  std::vector<glm::dvec3> a, b, c;
  std::vector<double> cumulativeArea;  // inclusive prefix sums
  double area = 0.0;
  double volume = 0.0;  // signed, divergence theorem (closed meshes, outward winding)
};

Triangles flatten(const ref::SceneDesc& object) {
  Triangles t;
  for (const auto& m : object.meshes)
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
      const glm::dvec3 p0 = m.positions[m.indices[i]], p1 = m.positions[m.indices[i + 1]], p2 = m.positions[m.indices[i + 2]];
      t.a.push_back(p0), t.b.push_back(p1), t.c.push_back(p2);
      t.area += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
      t.cumulativeArea.push_back(t.area);
      t.volume += glm::dot(p0, glm::cross(p1, p2)) / 6.0;
    }
  return t;
}

// Area-uniform surface points (deterministic: point i from Pcg32(seed, i)).
std::vector<glm::dvec3> surfacePoints(const Triangles& t, int count, std::uint64_t seed) {
  std::vector<glm::dvec3> out(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    math::Pcg32 rng(seed, std::uint64_t(i));
    const double u = rng.nextDouble() * t.area;
    const std::size_t k = std::min<std::size_t>(
        std::upper_bound(t.cumulativeArea.begin(), t.cumulativeArea.end(), u) - t.cumulativeArea.begin(), t.a.size() - 1);
    double r1 = std::sqrt(rng.nextDouble()), r2 = rng.nextDouble();
    out[i] = (1.0 - r1) * t.a[k] + r1 * (1.0 - r2) * t.b[k] + r1 * r2 * t.c[k];
  }
  return out;
}

using fit::nearestSphere;

// All hits along o + t d (t > 0), nearest first.
std::vector<ref::Hit> allHits(const ref::SceneBvh& bvh, const glm::dvec3& o, const glm::dvec3& d, double scale) {
  std::vector<ref::Hit> hits;
  float tMin = 0.0f;
  const float eps = float(1e-5 * scale);
  for (int guard = 0; guard < 256; ++guard) {
    ref::Hit h;
    if (!bvh.intersect(glm::vec3(o), glm::vec3(d), tMin, std::numeric_limits<float>::infinity(), h)) break;
    hits.push_back(h);
    tMin = h.t + eps;
  }
  return hits;
}

// §4.2's rules for direction ω from sphere `self`: the hit that represents it, or none.
bool sampleHit(const ref::SceneBvh& bvh, const std::vector<Sphere>& spheres, std::size_t self, const glm::dvec3& w,
               double scale, ref::Hit& out) {
  const glm::dvec3 o = spheres[self].centre;
  const auto hits = allHits(bvh, o, w, scale);
  bool anyBack = false, found = false;
  for (const auto& h : hits) {
    if (glm::dot(glm::dvec3(h.geometricNormal), w) <= 0.0) continue;  // front face: ignored
    anyBack = true;
    if (nearestSphere(glm::dvec3(h.position), spheres) == self) out = h, found = true;  // keeps the farthest
  }
  if (found || anyBack) return found;
  // No back face: the centre is outside the object; look behind for front faces (§4.2, third case).
  for (const auto& h : allHits(bvh, o, -w, scale)) {
    if (glm::dot(glm::dvec3(h.geometricNormal), -w) >= 0.0) continue;
    if (nearestSphere(glm::dvec3(h.position), spheres) == self) {
      out = h;
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<glm::vec3> sampleDirections(int count) {
  std::vector<glm::vec3> d;
  for (int i = 0; i < count; ++i) d.push_back(glm::vec3(math::fibonacciSphere(i, count)));
  return d;
}

SphereSet bake(const ref::SceneDesc& object, const BakeSettings& settings, const Skin& skin) {
  checkSettings(settings);
  const Triangles tris = flatten(object);
  if (tris.a.empty() || !(tris.area > 0.0)) throw InternalError("sl::bake: the object has no triangles");
  const int order = settings.order;
  const std::size_t nc = std::size_t(order) * order;

  // 1. Sphere set.
  const auto pts = surfacePoints(tris, settings.surfaceSamples, 0x51u);
  std::vector<Sphere> spheres = fit::cluster(pts, std::min<int>(settings.spheres, int(pts.size())), settings.iterations);
  // §4.1's bounding property ("no holes") on the SURFACE (sphere_fit.hpp). minEdge: 1/256 of the
  // points' bounding-box diagonal — the most a sphere grows for one uncovered piece.
  {
    glm::dvec3 plo(std::numeric_limits<double>::infinity()), phi(-std::numeric_limits<double>::infinity());
    for (const auto& p : pts) plo = glm::min(plo, p), phi = glm::max(phi, p);
    fit::coverTriangles(spheres, tris.a, tris.b, tris.c, glm::length(phi - plo) / 256.0);
  }
  SphereSet set;
  set.settings = settings;
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const auto& s : spheres) lo = glm::min(lo, s.centre - s.radius), hi = glm::max(hi, s.centre + s.radius);
  const glm::dvec3 boundCentre = 0.5 * (lo + hi);
  double boundRadius = 0.0;
  for (const auto& s : spheres) boundRadius = std::max(boundRadius, glm::length(s.centre - boundCentre) + s.radius);
  set.boundCentre = glm::vec3(boundCentre);
  set.boundRadius = float(boundRadius);
  const double scale = std::max(boundRadius, 1e-30);

  // Coverage on an independent point set.
  const auto check = surfacePoints(tris, 2 * settings.surfaceSamples, 0xC0u);
  std::size_t outside = 0;
  for (const auto& p : check) {
    bool in = false;
    for (const auto& s : spheres) in = in || glm::length(p - s.centre) <= s.radius * (1.0 + 1e-6);
    outside += in ? 0 : 1;
  }
  set.coverageError = float(double(outside) / double(check.size()));
  // Union volume: jittered 32³ grid over the spheres' box.
  {
    constexpr int kGrid = 32;
    math::Pcg32 rng(0xB0u);
    const glm::dvec3 ext = hi - lo;
    std::size_t in = 0;
    for (int z = 0; z < kGrid; ++z)
      for (int y = 0; y < kGrid; ++y)
        for (int x = 0; x < kGrid; ++x) {
          const glm::dvec3 q = lo + ext * (glm::dvec3(x, y, z) + glm::dvec3(rng.nextDouble(), rng.nextDouble(), rng.nextDouble())) / double(kGrid);
          for (const auto& s : spheres)
            if (glm::length(q - s.centre) <= s.radius) {
              ++in;
              break;
            }
        }
    const double vUnion = ext.x * ext.y * ext.z * double(in) / double(kGrid * kGrid * kGrid);
    const double vMesh = std::abs(tris.volume);
    set.volumeOvershoot = vMesh > 0.0 ? float(std::max(0.0, vUnion - vMesh) / vMesh) : std::numeric_limits<float>::max();
  }

  set.spheres.resize(spheres.size());
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    SlSphere& sp = set.spheres[i];
    sp.centre = glm::vec3(spheres[i].centre);
    sp.radius = float(spheres[i].radius);
    for (std::size_t j = 0; j < spheres.size(); ++j)
      if (j != i && glm::length(spheres[i].centre - spheres[j].centre) < spheres[i].radius + spheres[j].radius)
        sp.intersects |= std::uint64_t(1) << j;
  }

  // 5. Covered vertices and joints.
  std::uint32_t vertexBase = 0;
  std::vector<std::set<std::uint16_t>> joints(spheres.size());
  for (std::size_t m = 0; m < object.meshes.size(); ++m) {
    const auto& mesh = object.meshes[m];
    const bool skinned = m < skin.joints.size() && skin.joints[m].size() == mesh.positions.size() &&
                         m < skin.weights.size() && skin.weights[m].size() == mesh.positions.size();
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const std::size_t s = nearestSphere(glm::dvec3(mesh.positions[v]), spheres);
      set.spheres[s].vertices.push_back(vertexBase + std::uint32_t(v));
      if (skinned)
        for (int k = 0; k < 4; ++k)
          if (skin.weights[m][v][k] > 0.0f) joints[s].insert(skin.joints[m][v][k]);
    }
    vertexBase += std::uint32_t(mesh.positions.size());
  }
  for (std::size_t s = 0; s < spheres.size(); ++s) set.spheres[s].joints.assign(joints[s].begin(), joints[s].end());

  // 2–4. Per sphere, in parallel (each sphere's work depends on nothing but its index).
  const ref::SceneBvh bvh(object);
  const auto dirs = sampleDirections(settings.directions);
  math::Pcg32 prng(0x10u);
  const auto strata = math::stratified2D(settings.samplesPerAxis, prng);
  std::vector<glm::dvec3> proj;
  for (const auto& u : strata) proj.push_back(math::uniformSphere(u));
  const double w = 4.0 * kPi / double(proj.size());
  std::vector<std::size_t> cellOf(proj.size());
  for (std::size_t k = 0; k < proj.size(); ++k) {
    std::size_t best = 0;
    for (std::size_t j = 1; j < dirs.size(); ++j)
      if (glm::dot(proj[k], glm::dvec3(dirs[j])) > glm::dot(proj[k], glm::dvec3(dirs[best]))) best = j;
    cellOf[k] = best;
  }
  Progress progress("sl bake", spheres.size());
  parallelFor(0, spheres.size(), [&](std::size_t i) {
    SlSphere& sp = set.spheres[i];
    std::vector<int> sampleOfDir(dirs.size(), -1);
    for (std::size_t j = 0; j < dirs.size(); ++j) {
      ref::Hit h;
      if (!sampleHit(bvh, spheres, i, glm::dvec3(dirs[j]), scale, h)) continue;
      SurfaceSample s;
      s.position = h.position;
      // Outward normal: the shading normal turned to agree with the winding's geometric normal.
      s.normal = glm::dot(h.shadingNormal, h.geometricNormal) < 0.0f ? -h.shadingNormal : h.shadingNormal;
      s.direction = std::uint32_t(j);
      s.basis.assign(nc, 0.0f);
      sampleOfDir[j] = int(sp.samples.size());
      sp.samples.push_back(std::move(s));
    }
    std::vector<double> basis(nc * sp.samples.size(), 0.0);
    std::vector<glm::dvec3> albedo(nc, glm::dvec3(0.0));
    for (std::size_t k = 0; k < proj.size(); ++k) {
      const auto y = sh::evalBasis<double>(order, proj[k]);
      if (const int s = sampleOfDir[cellOf[k]]; s >= 0)
        for (std::size_t c = 0; c < nc; ++c) basis[std::size_t(s) * nc + c] += y[c];  // Eq. 10's Y_j
      ref::Hit h;
      if (sampleHit(bvh, spheres, i, proj[k], scale, h)) {
        const glm::dvec3 a(ref::surfaceAlbedo(object, h));
        for (std::size_t c = 0; c < nc; ++c) albedo[c] += a * y[c];
      }
    }
    for (std::size_t s = 0; s < sp.samples.size(); ++s)
      for (std::size_t c = 0; c < nc; ++c) sp.samples[s].basis[c] = float(w * basis[s * nc + c]);
    sp.albedo.resize(nc * 3);
    for (std::size_t c = 0; c < nc; ++c)
      for (int ch = 0; ch < 3; ++ch) sp.albedo[c * 3 + std::size_t(ch)] = float(w * albedo[c][ch]);
    progress.advance();
  });
  progress.finish();
  // 6. The bounce scale (bounce_scale.hpp): the mesh's light over the SLs' under uniform light.
  const BounceScales scales = fitBounceScale(set, bvh);
  for (SlSphere& sp : set.spheres) sp.bounceScale = float(scales.bounce), sp.shadowScale = float(scales.shadow);
  return set;
}

}  // namespace bounce::gi::sl
