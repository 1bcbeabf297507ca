// Issue 13, session 18 (README "SL's blocked light on the characters' floor, session 18"): the light
// side of SL's near-field shadow on the characters level. Session 17 found the geometry right under
// uniform light (SlBake.NearFieldShadowOnTheFloorVsTheMesh: SL 0.85–1.09× the mesh's solid angle within
// 0.5 m, bind pose) while the level's shadow is ~1.5× the reference's occlusion there, so the excess
// would lie in the RADIANCE SL takes as blocked. This test measures that radiance at floor receivers
// by each character, on the level's own pose (t = 0, as `bounce accuracy` renders it) and in the bind
// pose, with the level's baked probes:
//   Ω    = ∫_mesh cos dω                         the mesh's cosine-weighted solid angle (sr)
//   T    = ∫_mesh L_static(p, ω) cos dω          the light the mesh hides: radiance traced in the
//                                                STATIC level (ref::tracePathFrom, as the probes'
//                                                bake traces it), W/m²
//   R    = ∫_mesh max(0, L_p(ω)) cos dω          the same with the receiver's probe SH L_p
//                                                ("blocked_light": "receiver")
//   S    = ∫_mesh max(0, L_j(ω)) cos dω          the same with the SH at the posed SL j nearest the
//                                                mesh point the ray meets ("blocked_light": "sphere")
//   SL_u = −ΔE of sl::probeShadow under uniform unit radiance (the geometry, this pose)
//   SL_s, SL_r = −ΔE of sl::probeShadow with the probes' SH, sphere / receiver mode (uncut, the level's
//                sets, union shares and shadow scales)
// What splits S/T: the static field's own SH at p and at the SL (order 3 windowed as the bake does,
// order 4), the radiance traced from the SL's centre along the same ray (no SH at all), an octahedral
// map of it at the SL (8², 16² texels); and SL_s with the SLs' SH replaced by the traced SH, by the
// radiance traced along d_j (the bound of an exact directional read) and by the octahedral maps.
// Session 19 (README "SL's blocked light read from the probes' direction maps, session 19"): SL_m, SL_s
// as shipped with "blocked_read": "map" — the probe bake's own 16² direction maps (probe_volume.hpp
// dirMap) blended at each SL by incident::ProbeSource::radianceShAndMap (the lookup pass 1 makes),
// read at d_j (BlockedRead::Map). Asserted ≈ 1 once the geometry's own factor SL_u/mesh is divided out.
// R/T and S/T are the one number each: the probes' blocked light over the traced one. Receivers are
// floor points whose ray to the lamp the characters do not block (the indirect-only pixels of
// `bounce accuracy`), binned by their horizontal distance to the character's nearest vertex.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "engine/anim/animator.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/incident/session_light.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/gi/sl/probe_shadow.hpp"
#include "engine/gi/sl/technique.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_convolve.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/math/sh_project.hpp"
#include "engine/math/sh_window.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/ref/scene_bvh.hpp"
#include "engine/ref/tracer.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"
#include "tests/support/technique_level.hpp"

namespace bounce::gi::sl {
namespace {

namespace fs = std::filesystem;

double mean3(const glm::dvec3& v) { return (v.x + v.y + v.z) / 3.0; }

// The characters' room: cornell.gltf at scale 6, floor at y = 0, walls at |x|, |z| ≈ 1.67 m.
constexpr double kFloorY = 0.0;
constexpr double kRoomHalf = 1.62;
constexpr int kDirections = 4096;  // Fibonacci sphere; the upper half is the receiver's hemisphere
constexpr int kPathsPerDirection = 2;
constexpr int kMaxPerBand = 10;
constexpr double kBands[] = {0.02, 0.25, 0.5, 1.0};
constexpr int kBandCount = 3;

struct Sums {
  double omega = 0, traced = 0, receiverSh = 0, sphereSh = 0, slUniform = 0, slSphere = 0, slReceiver = 0;
  double tracedShP = 0, tracedShS = 0;  // the traced field's own order-3 SH at p / at the SL
  double slSphereTraced = 0;            // SL_s with that SH at each SL in place of the probes'
  double slSphereExact = 0;             // SL_s with the radiance traced from each SL along d_j (any order)
  double octS[2] = {}, slOct[2] = {};   // an octahedral map of the traced field at the SL, 8² / 16² texels
  double slMap = 0;                     // SL_m: "blocked_read": "map", the probes' baked maps blended at the SL
  double tracedS4 = 0;        // the traced field's order-4 SH at the SL (unwindowed)
  double tracedAtSphere = 0;  // the static radiance traced from the SL's centre along ω (no SH: any order)
  int n = 0;
};

// The static level's radiance at `o` projected to order-3 SH as the probe bake projects it (one path
// per stratified direction, 24² of them, the same Sloan window search): what a perfect probe AT o
// would hold. Splits R/T into the order-3 truncation of the true field (this over T) and the probes'
// placement and interpolation (R over this). `order` 4 and `window` false: what a higher-order or
// unwindowed probe would hold.
// Octahedral map (z the pole): unit direction ↔ [0, 1]².
glm::dvec2 octEncode(const glm::dvec3& d) {
  glm::dvec2 p = glm::dvec2(d.x, d.y) / (std::abs(d.x) + std::abs(d.y) + std::abs(d.z));
  if (d.z < 0.0)
    p = (1.0 - glm::abs(glm::dvec2(p.y, p.x))) * glm::dvec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
  return p * 0.5 + 0.5;
}
glm::dvec3 octDecode(const glm::dvec2& uv) {
  const glm::dvec2 f = uv * 2.0 - 1.0;
  glm::dvec3 n(f.x, f.y, 1.0 - std::abs(f.x) - std::abs(f.y));
  const double t = std::max(-n.z, 0.0);
  n.x += n.x >= 0.0 ? -t : t;
  n.y += n.y >= 0.0 ? -t : t;
  return glm::normalize(n);
}
// The static radiance at `o` as a res² octahedral map, each texel the mean of 4 paths through it: the
// directional store a probe could keep in place of (or beside) its SH. Read at the nearest texel.
struct OctMap {
  int res = 8;
  std::vector<double> texel;  // channel mean, W/(m²·sr)
  double read(const glm::dvec3& d) const {
    const glm::dvec2 uv = octEncode(d);
    const int x = std::min(res - 1, int(uv.x * res)), y = std::min(res - 1, int(uv.y * res));
    return texel[std::size_t(y * res + x)];
  }
};
OctMap tracedOct(const ref::SceneBvh& bvh, const glm::dvec3& o, int res, std::uint64_t seed) {
  OctMap m;
  m.res = res;
  math::Pcg32 rng = math::Pcg32::fromIndex(seed);
  std::uint64_t rays = 0;
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) {
        const glm::dvec2 uv((x + rng.nextDouble()) / res, (y + rng.nextDouble()) / res);
        sum += mean3(ref::tracePathFrom(bvh, glm::vec3(o), glm::vec3(octDecode(uv)), 1e-5f, 1e30f, ref::kUnlimitedBounces, rng, rays));
      }
      m.texel.push_back(sum / 4.0);
    }
  return m;
}

std::vector<glm::dvec3> tracedSh(const ref::SceneBvh& bvh, const glm::dvec3& o, std::uint64_t seed, int order = 3,
                                 bool window = true) {
  math::Pcg32 rng = math::Pcg32::fromIndex(seed);
  std::uint64_t rays = 0;
  auto radiance = [&](const glm::dvec3& d) {
    return ref::tracePathFrom(bvh, glm::vec3(o), glm::vec3(d), 1e-5f, 1e30f, ref::kUnlimitedBounces, rng, rays);
  };
  std::vector<glm::dvec3> l = sh::projectMonteCarlo(radiance, order, 24, seed);
  if (!window) return l;
  const std::vector<glm::dvec3> e = sh::convolveCosine<glm::dvec3>(l);
  const std::vector<glm::dvec3> dirs = math::fibonacciSphere(probes::kWindowDirections);
  const std::optional<double> width = sh::minimalWindow(e, sh::Window::Sloan, dirs, 0.0);
  if (!width || std::isfinite(*width)) l = sh::applyWindow<glm::dvec3>(l, sh::Window::Sloan, width ? *width : 1.0);
  return l;
}

TEST(SlBlockedLight, CharactersFloorProbesVsTraced) {
  const fs::path file = fs::path(BOUNCE_SOURCE_DIR) / "content/levels/characters.json";
  const scene::Level level = scene::loadLevel(file);
  const fs::path cook = testlevel::cookCache();
  const probes::ProbeVolume volume =
      probes::loadOrBake(level, cook, bounce::cacheDir("probes"), probes::settingsFrom(level)).volume;
  const incident::ProbeSource source(volume);
  const ref::SceneBvh staticBvh(probes::staticScene(level, cook));

  int nearChecked = 0;  // bands within 0.5 m that reached the asserts (none would pass silently)
  for (const bool posed : {true, false}) {
    ecs::Registry registry;
    scene::instantiate(level, registry);
    anim::attachAnimators(registry, cook);
    scene::motionSystem(registry, 0.0);
    anim::animationSystem(registry, 0.0);
    scene::transformSystem(registry);
    SessionRuntime runtime(registry, cook, cacheFolder());
    const auto& parts = runtime.participants();
    ASSERT_EQ(parts.size(), 2u);
    if (!posed) {
      for (const Participant& p : parts) registry.remove<anim::Pose>(p.entity);
      runtime.update(FrameUpdate{registry, 0.0});
    }
    // Per character: its posed mesh alone (BVH), its vertices, its SLs.
    ref::ReferenceAssets assets;
    assets.load(registry, cook);
    std::vector<std::unique_ptr<ref::SceneBvh>> meshes;
    std::vector<std::vector<glm::vec3>> vertices;
    std::vector<Light> lights;
    std::vector<std::vector<glm::dvec3>> sphereSh, sphereMap;
    std::vector<int> owner;  // light → character
    ShadowSettings ss;
    ss.order = 4;
    ss.influence = 0.0;  // uncut, as the split's rows
    for (std::size_t c = 0; c < parts.size(); ++c) {
      ecs::Registry one;
      const ecs::Entity e = one.create();
      one.emplace<scene::MeshRef>(e, registry.get<scene::MeshRef>(parts[c].entity));
      one.emplace<scene::WorldTransform>(e, registry.get<scene::WorldTransform>(parts[c].entity));
      if (const auto* pose = registry.tryGet<anim::Pose>(parts[c].entity)) one.emplace<anim::Pose>(e, *pose);
      ref::SceneDesc scene = ref::extractScene(one, scene::Level{}, assets);
      vertices.emplace_back();
      for (const auto& m : scene.meshes) vertices.back().insert(vertices.back().end(), m.positions.begin(), m.positions.end());
      meshes.push_back(std::make_unique<ref::SceneBvh>(std::move(scene)));
      std::vector<Sphere> local;
      for (const SlSphere& s : parts[c].set.spheres) local.push_back({glm::dvec3(s.centre), double(s.radius)});
      ss.objectShare.push_back(unionShare(local));
      ss.objectSilhouette.push_back(parts[c].set.spheres.front().shadowScale);
      for (const PosedSphere& q : parts[c].spheres) {
        Light l;
        l.sphere = {glm::dvec3(q.centre), double(q.radius)};
        l.object = int(c);
        lights.push_back(l);
        owner.push_back(int(c));
        incident::DirectionMap map;
        const incident::RadianceSH L = source.radianceShAndMap(q.centre, map);  // pass 1's one lookup
        sphereSh.emplace_back(L.begin(), L.end());
        sphereMap.emplace_back(map.begin(), map.end());
      }
    }
    // The traced field's SH at each posed SL centre (the static level: the field the probes hold).
    std::vector<std::vector<glm::dvec3>> sphereTraced;
    std::vector<std::vector<glm::dvec3>> sphere4;
    std::vector<OctMap> oct[2];
    for (std::size_t l = 0; l < lights.size(); ++l) {
      oct[0].push_back(tracedOct(staticBvh, lights[l].sphere.centre, 8, 9000 + l));
      oct[1].push_back(tracedOct(staticBvh, lights[l].sphere.centre, 16, 9500 + l));
      sphereTraced.push_back(tracedSh(staticBvh, lights[l].sphere.centre, 7000 + l));
      sphere4.push_back(tracedSh(staticBvh, lights[l].sphere.centre, 7000 + l, 4, false));
    }
    ShadowSettings atSphere = ss;
    atSphere.blocked = BlockedLight::Sphere;
    atSphere.sphereRadiance = sphereSh;
    ShadowSettings atSphereMap = atSphere;  // as shipped with "blocked_read": "map"
    atSphereMap.read = BlockedRead::Map;
    atSphereMap.sphereMap = sphereMap;
    ShadowSettings atSphereTraced = atSphere;
    atSphereTraced.sphereRadiance = sphereTraced;
    const ref::SceneDesc full = ref::extractScene(registry, level, assets, false);
    ASSERT_EQ(full.lights.size(), 1u);  // characters.json "ceiling-lamp"
    const glm::dvec3 lamp(full.lights[0].position);
    std::vector<glm::dvec3> uniform(9, glm::dvec3(0.0));
    uniform[0] = glm::dvec3(2.0 * std::sqrt(math::kPi));  // L ≡ 1

    std::printf("%s pose (t = 0)\n", posed ? "animated" : "bind");
    for (std::size_t c = 0; c < parts.size(); ++c) {
      // Candidate receivers: a 10 cm floor grid around the character's footprint.
      glm::dvec2 lo(1e30), hi(-1e30);
      for (const glm::vec3& v : vertices[c]) lo = glm::min(lo, glm::dvec2(v.x, v.z)), hi = glm::max(hi, glm::dvec2(v.x, v.z));
      std::vector<std::vector<std::pair<glm::dvec3, double>>> band(kBandCount);
      for (double x = lo.x - 1.0; x <= hi.x + 1.0; x += 0.1)
        for (double z = lo.y - 1.0; z <= hi.y + 1.0; z += 0.1) {
          auto footprint = [&](std::size_t k) {
            double d2 = 1e30;
            for (const glm::vec3& v : vertices[k]) d2 = std::min(d2, (v.x - x) * (v.x - x) + (v.z - z) * (v.z - z));
            return std::sqrt(d2);
          };
          const double d = footprint(c);
          if (d < kBands[0] || d >= kBands[kBandCount]) continue;
          if (footprint(1 - c) < d) continue;  // nearer the other character
          if (std::abs(x) > kRoomHalf || std::abs(z) > kRoomHalf) continue;
          const glm::dvec3 p(x, kFloorY + 1e-3, z);
          const glm::vec3 toLamp = glm::vec3(glm::normalize(lamp - p));
          const float lampT = float(glm::length(lamp - p));
          bool lit = true;
          for (const auto& m : meshes) lit = lit && !m->occluded(glm::vec3(p), toLamp, 1e-5f, lampT);
          if (!lit) continue;  // in a character's direct shadow: not an indirect-only pixel
          int b = 0;
          while (b + 1 < kBandCount && d >= kBands[b + 1]) ++b;
          band[std::size_t(b)].push_back({p, d});
        }
      for (int b = 0; b < kBandCount; ++b) {
        auto& cand = band[std::size_t(b)];
        Sums s;
        const std::size_t stride = std::max<std::size_t>(1, cand.size() / kMaxPerBand);
        for (std::size_t i = 0; i < cand.size(); i += stride) {
          const glm::dvec3 p = cand[i].first, n(0.0, 1.0, 0.0);
          const std::vector<glm::vec3> receiverSh32 = volume.radianceSH(glm::vec3(p), glm::vec3(n));
          const std::vector<glm::dvec3> receiverSh(receiverSh32.begin(), receiverSh32.end());
          const std::vector<glm::dvec3> pTraced = tracedSh(staticBvh, p, (std::uint64_t(c) << 20) + i);
          Sums r;
          std::uint64_t rays = 0;
          for (int k = 0; k < kDirections; ++k) {
            const glm::dvec3 d = math::fibonacciSphere(k, kDirections);
            const double cs = d.y;
            if (cs <= 0.0) continue;
            ref::Hit hit;
            if (!meshes[c]->intersect(glm::vec3(p), glm::vec3(d), 1e-5f, 1e30f, hit)) continue;
            const double w = cs * 4.0 * math::kPi / kDirections;
            r.omega += w;
            glm::dvec3 traced(0.0);
            math::Pcg32 rng = math::Pcg32::fromIndex((std::uint64_t(c * 4096 + i) << 32) | std::uint64_t(k));
            for (int j = 0; j < kPathsPerDirection; ++j)
              traced += ref::tracePathFrom(staticBvh, glm::vec3(p), glm::vec3(d), 1e-5f, 1e30f, ref::kUnlimitedBounces, rng, rays);
            r.traced += w * mean3(traced) / kPathsPerDirection;
            r.receiverSh += w * mean3(glm::max(sh::evalSum<glm::dvec3, double>(receiverSh, d), glm::dvec3(0.0)));
            // The posed SL of this character nearest the mesh point the ray meets.
            std::size_t best = 0;
            double bestGap = 1e30;
            for (std::size_t l = 0; l < lights.size(); ++l) {
              if (owner[l] != int(c)) continue;
              const double gap = glm::length(lights[l].sphere.centre - glm::dvec3(hit.position)) - lights[l].sphere.radius;
              if (gap < bestGap) bestGap = gap, best = l;
            }
            r.sphereSh += w * mean3(glm::max(sh::evalSum<glm::dvec3, double>(sphereSh[best], d), glm::dvec3(0.0)));
            r.tracedShP += w * mean3(glm::max(sh::evalSum<glm::dvec3, double>(pTraced, d), glm::dvec3(0.0)));
            r.tracedShS += w * mean3(glm::max(sh::evalSum<glm::dvec3, double>(sphereTraced[best], d), glm::dvec3(0.0)));
            glm::dvec3 fromSphere(0.0);
            for (int j = 0; j < kPathsPerDirection; ++j)
              fromSphere += ref::tracePathFrom(staticBvh, glm::vec3(lights[best].sphere.centre), glm::vec3(d), 1e-5f, 1e30f,
                                               ref::kUnlimitedBounces, rng, rays);
            r.tracedAtSphere += w * mean3(fromSphere) / kPathsPerDirection;
            for (int o = 0; o < 2; ++o) r.octS[o] += w * oct[o][best].read(d);
            r.tracedS4 += w * mean3(glm::max(sh::evalSum<glm::dvec3, double>(sphere4[best], d), glm::dvec3(0.0)));
          }
          if (r.omega > 0.5 * math::kPi || r.omega <= 0.0) continue;  // under the body, or nothing blocked
          const ProbeShadow u = probeShadow(lights, p, n, uniform, ss);
          const ProbeShadow sp = probeShadow(lights, p, n, receiverSh, atSphere);
          const ProbeShadow rc = probeShadow(lights, p, n, receiverSh, ss);
          const ProbeShadow st = probeShadow(lights, p, n, receiverSh, atSphereTraced);
          // The bound of a better read at the spheres: each SL's "SH" a constant, the static radiance
          // traced from its centre towards d_j (the direction sphere mode reads it in; the raw centre's
          // direction, before the receiver rules move it).
          ShadowSettings exactRead = atSphere;
          {
            std::uint64_t rays = 0;
            math::Pcg32 rng = math::Pcg32::fromIndex((std::uint64_t(c * 4096 + i) << 32) | 0xffffu);
            for (std::size_t l = 0; l < lights.size(); ++l) {
              const glm::dvec3 dj = glm::normalize(lights[l].sphere.centre - p);
              glm::dvec3 L(0.0);
              for (int j = 0; j < 4 * kPathsPerDirection; ++j)
                L += ref::tracePathFrom(staticBvh, glm::vec3(lights[l].sphere.centre), glm::vec3(dj), 1e-5f, 1e30f,
                                        ref::kUnlimitedBounces, rng, rays);
              exactRead.sphereRadiance[l] = std::vector<glm::dvec3>(9, glm::dvec3(0.0));
              exactRead.sphereRadiance[l][0] = 2.0 * std::sqrt(math::kPi) * L / double(4 * kPathsPerDirection);
            }
          }
          const ProbeShadow ex = probeShadow(lights, p, n, receiverSh, exactRead);
          for (int o = 0; o < 2; ++o) {
            ShadowSettings octRead = atSphere;
            for (std::size_t l = 0; l < lights.size(); ++l) {
              octRead.sphereRadiance[l] = std::vector<glm::dvec3>(9, glm::dvec3(0.0));
              octRead.sphereRadiance[l][0] =
                  glm::dvec3(2.0 * std::sqrt(math::kPi) * oct[o][l].read(glm::normalize(lights[l].sphere.centre - p)));
            }
            s.slOct[o] += -mean3(probeShadow(lights, p, n, receiverSh, octRead).delta);
            s.octS[o] += r.octS[o];
          }
          s.slMap += -mean3(probeShadow(lights, p, n, receiverSh, atSphereMap).delta);
          ASSERT_TRUE(std::isfinite(sp.delta.x) && std::isfinite(rc.delta.x) && std::isfinite(u.delta.x));
          s.omega += r.omega, s.traced += r.traced, s.receiverSh += r.receiverSh, s.sphereSh += r.sphereSh;
          s.tracedShP += r.tracedShP, s.tracedShS += r.tracedShS, s.slSphereTraced += -mean3(st.delta);
          s.slSphereExact += -mean3(ex.delta);
          s.tracedAtSphere += r.tracedAtSphere, s.tracedS4 += r.tracedS4;
          s.slUniform += -mean3(u.delta), s.slSphere += -mean3(sp.delta), s.slReceiver += -mean3(rc.delta);
          ++s.n;
        }
        if (s.n == 0) continue;
        const double S = s.sphereSh / s.traced, R = s.receiverSh / s.traced, atSl = s.tracedAtSphere / s.traced;
        const double tracedSh3 = s.tracedShS / s.traced;
        std::printf("  %s %.2f-%.2f m, %2d receivers: mesh %.4f sr, T %.5f W/m2 (mean blocked radiance %.4f)\n"
                    "    blocked light / T: probes' SH at p (R) %.3f, at the SL (S) %.3f; traced field's SH at p %.3f, at the "
                    "SL %.3f (order 4: %.3f); traced from the SL along the ray %.3f\n"
                    "    SL: SL_u/mesh %.3f; SL_s/T %.3f, SL_r/T %.3f, SL_s with the traced SH at the SLs / T %.3f, with the radiance traced from the SLs along d_j / T %.3f\n"
                    "    octahedral map at the SL, 8² / 16²: blocked light / T %.3f / %.3f, SL_s / T %.3f / %.3f\n"
                    "    blocked_read map (the probes' baked maps blended at the SLs): SL_m / T %.3f; light factors "
                    "(SL / T over SL_u / mesh): sh %.3f, map %.3f\n",
                    parts[c].name.c_str(), kBands[b], kBands[b + 1], s.n, s.omega / s.n, s.traced / s.n, s.traced / s.omega, R,
                    S, s.tracedShP / s.traced, tracedSh3, s.tracedS4 / s.traced, atSl, s.slUniform / s.omega,
                    s.slSphere / s.traced, s.slReceiver / s.traced, s.slSphereTraced / s.traced, s.slSphereExact / s.traced, s.octS[0] / s.traced, s.octS[1] / s.traced,
                    s.slOct[0] / s.traced, s.slOct[1] / s.traced, s.slMap / s.traced,
                    (s.slSphere / s.traced) / (s.slUniform / s.omega), (s.slMap / s.traced) / (s.slUniform / s.omega));
        ASSERT_GT(s.traced, 0.0);
        ASSERT_TRUE(std::isfinite(R) && std::isfinite(S) && std::isfinite(atSl));
        if (b < 2) {  // within 0.5 m, where session 17 measured the level's excess
          ++nearChecked;
          // The radiance itself, read at the SL's centre along the receiver's ray, is the receiver's
          // (measured 0.92–0.99): the sphere is the right place to read it (no parallax). Bound ±15 %:
          // two paths per direction, 17 receivers.
          EXPECT_NEAR(atSl, 1.0, 0.15) << parts[c].name << " band " << b;
          // Its order-3 SH is not (measured 1.18–1.64, probes' and the traced field's alike): the
          // excess is the truncation of a field whose bright half is the floor. Asserted > 1.1.
          EXPECT_GT(S, 1.1) << parts[c].name << " band " << b;
          EXPECT_GT(tracedSh3, 1.1) << parts[c].name << " band " << b;
          // "blocked_read": "map" (session 19): the light SL's shadow takes over the light the mesh
          // hides, with the geometry's own factor (SL_u / mesh) divided out. The SH read's is 1.21–1.70
          // (asserted above through S); the maps' measured 0.95–1.35 (printed): ≈ 1 within
          // kMapLightTolerance, the 20° kernel's blur of the floor's bright half over the horizon
          // (bake.hpp kDirMapKernel) and the choice of receivers (±0.1, session 18). And below the SH
          // read's factor by at least kMapGain (measured 0.15–0.40 less): the maps remove the excess.
          constexpr double kMapLightTolerance = 0.4, kMapGain = 0.1;
          const double geometry = s.slUniform / s.omega;
          const double shLight = (s.slSphere / s.traced) / geometry, mapLight = (s.slMap / s.traced) / geometry;
          EXPECT_NEAR(mapLight, 1.0, kMapLightTolerance) << parts[c].name << " band " << b;
          EXPECT_LT(mapLight, shLight - kMapGain) << parts[c].name << " band " << b;
        }
      }
    }
  }
  EXPECT_EQ(nearChecked, 2 * 2 * 2);  // 2 poses × 2 characters (Fox, CesiumMan) × 2 bands
}

}  // namespace
}  // namespace bounce::gi::sl
