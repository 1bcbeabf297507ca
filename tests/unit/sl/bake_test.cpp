// SL bake (engine/gi/sl/bake.hpp) and sphere-set file (sphere_set.hpp): a sphere mesh against
// closed forms, meshes from content/src and ../shared/assets (tiny counts), a skinned mesh's joints,
// determinism, the file's round trip and its validation.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>

#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/gi/sl/bake.hpp"
#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/probe_shadow.hpp"
#include "engine/math/sampling.hpp"
#include "tests/unit/dnrt/test_meshes.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

const double kSqrt4Pi = std::sqrt(4.0 * math::kPi);

BakeSettings tiny(int spheres) {
  BakeSettings s;
  s.spheres = spheres;
  s.order = 4;
  s.directions = 92;
  s.samplesPerAxis = 24;  // N = 576: enough for sums, fast
  s.surfaceSamples = 1024;
  s.iterations = 6;
  return s;
}

// Every primitive of a glTF in its mesh's local frame (node transforms ignored: one mesh's bake),
// base colour factors as albedo, and the skin attributes when present.
ref::SceneDesc loadMesh(const std::filesystem::path& file, Skin* skin = nullptr) {
  asset::CookOptions o;
  o.decodeImages = false;
  const auto a = asset::cook(file, o);
  ref::SceneDesc s;
  for (const auto& m : a.materials) s.materials.push_back(ref::RefMaterial{glm::vec3(m.baseColorFactor)});
  if (s.materials.empty()) s.materials.push_back(ref::RefMaterial{});
  for (const auto& mesh : a.meshes)
    for (const auto& p : mesh.primitives) {
      ref::RefMesh rm;
      rm.positions = p.positions;
      rm.normals = p.normals;
      rm.indices = p.indices;
      rm.material = p.material < 0 ? 0 : std::uint32_t(p.material);
      s.meshes.push_back(std::move(rm));
      if (skin) {
        skin->joints.push_back(p.joints);
        skin->weights.push_back(p.weights);
      }
    }
  return s;
}

std::filesystem::path shared(const std::string& rel) { return std::filesystem::path(BOUNCE_SHARED_DIR) / rel; }

}  // namespace

// One SL on a UV sphere of radius 1: the fit is the sphere itself, every direction has a sample on
// the surface with a radial normal, the Voronoi basis sums add up to the projection of 1 and the
// albedo SH of a uniform ρ is ρ·1.
TEST(SlBake, OneSphereOnASphereMesh) {
  const auto mesh = gi::dnrt::testing::sphere(glm::vec3(0.0f), 1.0f, glm::vec3(0.6f), 48);
  const SphereSet set = bake(mesh, tiny(1));
  ASSERT_EQ(set.spheres.size(), 1u);
  const SlSphere& s = set.spheres[0];
  // A 48-ring UV sphere's vertices lie on r = 1; its flat triangles dip inside by ≤ 1 − cos(π/96).
  EXPECT_LT(glm::length(s.centre), 0.01f);
  EXPECT_NEAR(s.radius, 1.0f, 0.01f);
  EXPECT_EQ(set.coverageError, 0.0f);
  EXPECT_LT(set.volumeOvershoot, 0.05f);  // polygonal sphere inside its bound: ~3·(1−cos(π/96))
  ASSERT_EQ(s.samples.size(), 92u);
  std::vector<double> sum(16, 0.0);
  for (const auto& x : s.samples) {
    EXPECT_NEAR(glm::length(x.position - s.centre), 1.0f, 0.01f);
    EXPECT_GT(glm::dot(x.normal, glm::normalize(x.position - s.centre)), 0.99f);
    for (int c = 0; c < 16; ++c) sum[c] += x.basis[c];
  }
  // Σ_j (4π/N) Y_j = (4π/N) Σ_k y(ω̂_k): its DC is exactly 4π Y_00 = √(4π); the other bands are the
  // stratified estimate of ∫Y_i = 0 (576 jittered strata: |·| < 0.05).
  EXPECT_NEAR(sum[0], kSqrt4Pi, 1e-5);
  for (int c = 1; c < 16; ++c) EXPECT_NEAR(sum[c], 0.0, 0.05) << c;
  EXPECT_NEAR(s.albedo[0], 0.6 * kSqrt4Pi, 1e-5);
  for (int c = 1; c < 16; ++c) EXPECT_NEAR(s.albedo[c * 3], 0.0, 0.05 * 0.6) << c;
  EXPECT_EQ(s.intersects, 0u);
  EXPECT_EQ(s.vertices.size(), mesh.meshes[0].positions.size());
}

// Meshes from content/src and ../shared/assets with 8 spheres: every sample point bounded, small
// coverage error, finite overshoot, the intersect masks symmetric, every vertex covered once.
TEST(SlBake, RealMeshesWithEightSpheres) {
  for (const auto& file : {std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/src/Box/glTF-Binary/Box.glb",
                           shared("assets/Suzanne/glTF/Suzanne.gltf")}) {
    const auto mesh = loadMesh(file);
    const SphereSet set = bake(mesh, tiny(8));
    std::size_t vertices = 0, samples = 0;
    for (const auto& m : mesh.meshes) vertices += m.positions.size();
    std::size_t covered = 0;
    for (std::size_t i = 0; i < set.spheres.size(); ++i) {
      const auto& s = set.spheres[i];
      EXPECT_GT(s.radius, 0.0f);
      covered += s.vertices.size();
      samples += s.samples.size();
      for (std::size_t j = 0; j < set.spheres.size(); ++j)
        EXPECT_EQ((s.intersects >> j) & 1u, (set.spheres[j].intersects >> i) & 1u);
      for (const auto& x : s.samples) EXPECT_TRUE(std::isfinite(x.position.x) && std::isfinite(x.basis[0]));
    }
    EXPECT_EQ(covered, vertices);
    std::printf("%s: 8 spheres, coverage error %.4f, volume overshoot %.3f, %zu samples\n",
                file.filename().string().c_str(), set.coverageError, set.volumeOvershoot, samples);
    // Every triangle's corners lie in a sphere, hence the whole surface: nothing outside.
    EXPECT_EQ(set.coverageError, 0.0f) << file;
    EXPECT_TRUE(std::isfinite(set.volumeOvershoot));
    EXPECT_GT(samples, 8u);
  }
}

// A skinned mesh: each sphere lists the joints of the vertices it covers.
TEST(SlBake, SkinnedMeshSpheresKnowTheirJoints) {
  Skin skin;
  const auto mesh = loadMesh(shared("assets/RiggedSimple/glTF-Binary/RiggedSimple.glb"), &skin);
  ASSERT_FALSE(skin.joints.empty());
  ASSERT_FALSE(skin.joints[0].empty());
  const SphereSet set = bake(mesh, tiny(8), skin);
  std::size_t withJoints = 0;
  for (const auto& s : set.spheres) {
    if (!s.vertices.empty()) {
      EXPECT_FALSE(s.joints.empty());
    }
    withJoints += s.joints.empty() ? 0 : 1;
    EXPECT_TRUE(std::is_sorted(s.joints.begin(), s.joints.end()));
  }
  EXPECT_GT(withJoints, 0u);
}

TEST(SlBake, DeterministicAndRoundTrips) {
  const auto mesh = gi::dnrt::testing::twoToneSphere(glm::vec3(0.1f), 0.7f, glm::vec3(0.9f, 0.2f, 0.1f),
                                                     glm::vec3(0.1f, 0.2f, 0.8f), 24);
  const SphereSet a = bake(mesh, tiny(4));
  SphereSet b;
  {
    // One worker thread: the result must not depend on the thread count (per-sphere work only
    // depends on the sphere's index).
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    b = bake(mesh, tiny(4));
  }
  const auto bytes = serialize(a);
  EXPECT_EQ(bytes, serialize(b));
  const SphereSet c = deserialize(bytes, "mem.slset");
  EXPECT_EQ(serialize(c), bytes);
  for (const auto& sp : a.spheres)
    for (float x : sp.albedo) EXPECT_TRUE(std::isfinite(x));
}

TEST(SlBake, MalformedFilesAreInputErrors) {
  const auto mesh = gi::dnrt::testing::sphere(glm::vec3(0.0f), 1.0f, glm::vec3(0.5f), 16);
  auto bytes = serialize(bake(mesh, tiny(2)));
  auto expectInput = [](std::vector<std::uint8_t> b, const char* what) {
    try {
      deserialize(b, "bad.slset");
      ADD_FAILURE() << what << ": accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.slset"), std::string::npos) << e.what();
    }
  };
  expectInput(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 20), "truncated");
  auto magic = bytes;
  magic[0] = 'X';
  expectInput(magic, "magic");
  auto version = bytes;
  version[8] = 99;
  expectInput(version, "version");
  auto trailing = bytes;
  trailing.push_back(0);
  expectInput(trailing, "trailing");
  // A NaN radius: header 8 + version 4 + settings 24 + bound 16 + metrics 8 + count 4 + centre 12.
  auto nan = bytes;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.data() + 8 + 4 + 24 + 16 + 8 + 4 + 12, &q, 4);
  expectInput(nan, "nan radius");
  // The last sphere's scales are the file's last 8 bytes (bounce, shadow): each must be in (0, 1].
  for (std::size_t back : {8u, 4u})
    for (float bad : {0.0f, 1.5f, -0.25f}) {
      auto scale = bytes;
      std::memcpy(scale.data() + scale.size() - back, &bad, 4);
      expectInput(scale, back == 8 ? "bounce scale" : "shadow scale");
    }
}

// Pass 1's projection (Eq. 10–11) on baked data: a sphere mesh of albedo ρ whose samples all
// reflect L gives an SL of uniform intensity ρL, whose average radiance seen from anywhere is ρL.
TEST(SlBake, IntensityFromSamplesOfAUniformSphere) {
  const auto mesh = gi::dnrt::testing::sphere(glm::vec3(0.0f), 1.0f, glm::vec3(0.5f, 0.25f, 1.0f), 32);
  const SphereSet set = bake(mesh, tiny(1));
  const SlSphere& s = set.spheres[0];
  std::vector<glm::dvec3> radiance(s.samples.size(), glm::dvec3(2.0));
  std::vector<std::vector<float>> basis;
  for (const auto& x : s.samples) basis.push_back(x.basis);
  Light light;
  light.sphere = {glm::dvec3(0, 0, 3), 1.0};
  light.intensity = intensityFromSamples(radiance, basis, s.albedo, 4);
  // DC of a product = Y_00 (a · b): the exact DCs give 2ρ√(4π); the higher bands' stratified noise
  // (|·| < 0.05 in each factor, see above) adds Y_00 Σ a_i b_i, measured 3.6e-4 relative: 1e-3.
  EXPECT_NEAR(light.intensity[0].x, 2.0 * 0.5 * kSqrt4Pi, 1e-3 * 2.0 * 0.5 * kSqrt4Pi);
  EXPECT_NEAR(light.intensity[0].z, 2.0 * 1.0 * kSqrt4Pi, 1e-3 * 2.0 * 1.0 * kSqrt4Pi);
  const auto e = evaluate(std::span<const Light>(&light, 1), glm::dvec3(0.0), glm::dvec3(0, 0, 1), {});
  // Higher bands carry the stratified estimate's noise (|·| < 0.05 each, products of two of them).
  EXPECT_NEAR(e.terms[0].average.x, 1.0, 0.05);
  EXPECT_NEAR(e.terms[0].average.y, 0.5, 0.05);
  EXPECT_NEAR(e.terms[0].average.z, 2.0, 0.05);
}

// The count setting's sweep on Suzanne (printed for the report): coverage stays 0, overshoot falls
// as spheres are added (not strictly: the fit is a local optimum), and 64 spheres fit in the masks.
TEST(SlBake, SphereCountSweepOnSuzanne) {
  const auto mesh = loadMesh(shared("assets/Suzanne/glTF/Suzanne.gltf"));
  float first = 0.0f, last = 0.0f;
  for (int k : {8, 16, 32, 64}) {
    BakeSettings st = tiny(k);
    st.samplesPerAxis = 8;  // the sweep is about the fit; keep the per-sphere ray work small
    const SphereSet set = bake(mesh, st);
    std::printf("Suzanne spheres=%d coverage_error=%.4f volume_overshoot=%.3f\n", k, set.coverageError,
                set.volumeOvershoot);
    EXPECT_EQ(set.coverageError, 0.0f);
    EXPECT_EQ(int(set.spheres.size()), k);
    (k == 8 ? first : last) = set.volumeOvershoot;
  }
  EXPECT_LT(last, first);
}

// Issue 13's bounce excess on the characters level: a whole real object as its SLs under uniform
// light (every surface point re-emits ρL, ρ = 1 here). The truth at a receiver is L times the
// cosine-weighted solid angle of the MESH (brute force: rays from the receiver against it); the SLs
// give Σ_i L̃_i Ṽ_i with intersecting spheres of one object ignored as each other's blockers (§6.2:
// their occlusion is baked into the samples). Printed: SL / truth per receiver, and the sum of the
// spheres' own caps (no blocking at all) / truth. The ratio is the bounce's geometric over-count,
// which the bake's bounce scale (bounce_scale.hpp) removes.
TEST(SlBake, UniformlyLitCharacterSlsVsItsMesh) {
  for (const char* rel : {"content/src/CesiumMan/glTF-Binary/CesiumMan.glb", "content/src/Fox/glTF-Binary/Fox.glb"}) {
    auto mesh = loadMesh(std::filesystem::path(BOUNCE_SOURCE_DIR) / rel);
    for (auto& m : mesh.materials) m.albedo = glm::vec3(1.0f);
    for (int count : {8, 32}) {
      BakeSettings bs = tiny(count);
      const SphereSet set = bake(mesh, bs);
      std::vector<Light> lights;
      for (const SlSphere& s : set.spheres) {
        std::vector<glm::dvec3> radiance(s.samples.size(), glm::dvec3(1.0));  // L_p = L = 1 (uniform)
        std::vector<std::vector<float>> basis;
        for (const auto& x : s.samples) basis.push_back(x.basis);
        Light l;
        l.sphere = {glm::dvec3(s.centre), double(s.radius)};
        l.intensity = intensityFromSamples(radiance, basis, s.albedo, 4);
        l.object = 0;
        lights.push_back(std::move(l));
      }
      std::vector<Sphere> raw;
      for (const Light& l : lights) raw.push_back(l.sphere);
      const double share = unionShare(raw);
      const ref::SceneBvh bvh(mesh);
      const glm::dvec3 c(set.boundCentre);
      const double R = set.boundRadius;
      double sumRatio = 0.0, sumCaps = 0.0, sumUnion = 0.0, sumAllBlock = 0.0, sumVsUnion = 0.0, sumScaled = 0.0;
      int n = 0;
      for (const glm::dvec3 axis : {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0),
                                    glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)})
        for (double k : {0.8, 1.5}) {
          const glm::dvec3 p = c + k * R * axis, nrm = -axis;
          constexpr int kN = 20000;
          double truth = 0.0, unionCaps = 0.0;  // the mesh's and the spheres' union's cos-weighted solid angle
          for (int i = 0; i < kN; ++i) {
            const glm::dvec3 d = math::fibonacciSphere(i, kN);
            const double cs = glm::dot(d, nrm);
            if (cs <= 0.0) continue;
            if (bvh.occluded(glm::vec3(p), glm::vec3(d), 1e-5f * float(R), 1e30f)) truth += cs * 4.0 * math::kPi / kN;
            bool hit = false;
            for (const Light& l : lights) {
              const Adjusted a = adjustForReceiver(l.sphere, p, nrm);
              if (a.culled) continue;
              const glm::dvec3 oc = a.sphere.centre - p;
              const double b = glm::dot(oc, d), h2 = glm::dot(oc, oc) - b * b;
              hit = hit || (b > 0.0 && h2 < a.sphere.radius * a.sphere.radius);
            }
            if (hit) unionCaps += cs * 4.0 * math::kPi / kN;
          }
          sumUnion += unionCaps / truth;
          if (truth < 1e-3) continue;
          const auto e = evaluate(lights, p, nrm, {});
          double caps = 0.0;  // every sphere's own unoccluded cap, L̃ ≈ 1 (uniform)
          for (const auto& t : e.terms)
            if (!t.culled) caps += std::sin(t.theta) * std::sin(t.theta) * math::kPi;  // ≈ cap's Ṽ facing it
          sumRatio += e.irradiance.x / truth;
          sumScaled += set.spheres[0].bounceScale * e.irradiance.x / truth;
          {  // every closer sphere a blocker, intersecting or not (each its own object for `intersects`)
            std::vector<Light> apart = lights;
            for (std::size_t i = 0; i < apart.size(); ++i) apart[i].object = int(i);
            sumAllBlock += evaluate(apart, p, nrm, {}).irradiance.x / truth;
          }
          sumCaps += caps / truth;
          sumVsUnion += e.irradiance.x / unionCaps;
          ++n;
        }
      std::printf("%s, %d spheres (overshoot %.2f), means over %d receivers: SL / mesh truth %.2f, union of the "
                  "spheres / mesh %.2f, summed caps / mesh %.2f, SL with intersecting spheres as blockers / mesh %.2f; SL / union %.2f, union share u_o %.3f; bounce scale %.3f, scaled SL / mesh %.2f\n",
                  rel, count, set.volumeOvershoot, n, sumRatio / n, sumUnion / n, sumCaps / n, sumAllBlock / n,
                  sumVsUnion / n, share, set.spheres[0].bounceScale, sumScaled / n);
      // Unscaled, the SLs give 1.9–4.0× the mesh's light on these receivers (printed); the bake's
      // bounce scale (fitted on other receivers: two shells around the set) brings them near it.
      EXPECT_GT(sumRatio / n, 1.5);
      EXPECT_NEAR(sumScaled / n, 1.0, 0.35) << rel << " " << count;
    }
  }
}

// Issue 13, session 17: where SL's near-field shadow on the probes' light is too strong. Under
// uniform unit radiance the true darkening of a floor receiver by a character is the MESH's
// cosine-weighted solid angle Ω_mesh (rays against the mesh), and sl.shadow's (the C++ reference
// sl::probeShadow, the level's settings uncut: 16 spheres, order 4, influence 0, the baked union share and
// shadow scale) should equal it. Three numbers per distance band split SL/mesh into its factors:
//   union/mesh: the spheres' union Ω_union over Ω_mesh (geometry: the set bounds the surface);
//   s_shadow: the baked scale, fitted on shells at 1.1 and 2 bounding radii (bounce_scale.cpp);
//   SL/(s·union): what the Ratio form's k and σ do on top (overlaps, exp).
// Characters in metres and standing on the floor (CesiumMan is Z-up in its mesh frame, the Fox
// Y-up at the level's scale 0.006); receivers on the floor at 16 azimuths and 0.1…2 m from the
// bounding centre's vertical axis, those under the body (Ω_mesh > π/2) left out. Bind pose.
TEST(SlBake, NearFieldShadowOnTheFloorVsTheMesh) {
  struct Character {
    const char* rel;
    int up;
    float scale;
  };
  for (const Character ch : {Character{"content/src/CesiumMan/glTF-Binary/CesiumMan.glb", 2, 1.0f},
                             Character{"content/src/Fox/glTF-Binary/Fox.glb", 1, 0.006f}}) {
    auto mesh = loadMesh(std::filesystem::path(BOUNCE_SOURCE_DIR) / ch.rel);
    float floorH = std::numeric_limits<float>::max();
    for (auto& m : mesh.meshes)
      for (auto& v : m.positions) {
        v *= ch.scale;
        floorH = std::min(floorH, v[ch.up]);
      }
    BakeSettings bs;  // the level's: 16 spheres, order 4, default fit
    const SphereSet set = bake(mesh, bs);
    std::vector<Light> lights;
    std::vector<Sphere> raw;
    for (const SlSphere& s : set.spheres) {
      Light l;
      l.sphere = {glm::dvec3(s.centre), double(s.radius)};
      l.object = 0;
      lights.push_back(l);
      raw.push_back(l.sphere);
    }
    ShadowSettings ss;
    ss.order = 4;
    ss.influence = 0.0;  // uncut, as the split's rows (influence=0)
    ss.objectShare = {unionShare(raw)};
    ss.objectSilhouette = {double(set.spheres[0].shadowScale)};
    std::vector<glm::dvec3> radiance(9, glm::dvec3(0.0));
    radiance[0] = glm::dvec3(2.0 * std::sqrt(math::kPi));  // L ≡ 1: L_00 = ∫ Y_00 = 2√π, E_u = π
    const ref::SceneBvh bvh(mesh);
    glm::dvec3 up(0.0);
    up[ch.up] = 1.0;
    const int a1 = (ch.up + 1) % 3, a2 = (ch.up + 2) % 3;
    const double bands[] = {0.0, 0.25, 0.5, 1.0, 2.0};
    double meshB[4] = {}, unionB[4] = {}, slB[4] = {}, slNoShareB[4] = {};
    int nB[4] = {}, clampedB[4] = {};  // receivers whose k sits at its floor 1/kShadowMaxRatio
    constexpr int kRays = 2048;
    for (int ring = 1; ring <= 20; ++ring)
      for (int az = 0; az < 16; ++az) {
        const double r = 0.1 * ring, phi = 2.0 * math::kPi * (az + 0.5) / 16.0;
        glm::dvec3 p(set.boundCentre);
        p[ch.up] = double(floorH) + 1e-3;
        p[a1] += r * std::cos(phi);
        p[a2] += r * std::sin(phi);
        double om = 0.0, ou = 0.0;
        for (int i = 0; i < kRays; ++i) {
          const glm::dvec3 d = math::fibonacciSphere(i, kRays);
          const double cs = glm::dot(d, up);
          if (cs <= 0.0) continue;
          if (bvh.occluded(glm::vec3(p), glm::vec3(d), 1e-5f, 1e30f)) om += cs * 4.0 * math::kPi / kRays;
          for (const Sphere& s : raw) {
            const glm::dvec3 oc = s.centre - p;
            const double b = glm::dot(oc, d);
            if (b > 0.0 && glm::dot(oc, oc) - b * b < s.radius * s.radius) {
              ou += cs * 4.0 * math::kPi / kRays;
              break;
            }
          }
        }
        if (om > 0.5 * math::kPi) continue;  // under the body
        const ProbeShadow ps = probeShadow(lights, p, up, radiance, ss);
        ASSERT_TRUE(std::isfinite(ps.delta.x));
        EXPECT_LE(ps.delta.x, 0.0);
        EXPECT_GE(ps.delta.x, -ps.unshadowed.x - 1e-9);
        ShadowSettings noShare = ss;
        noShare.objectSilhouette = {1.0};
        const double slNoShare = -probeShadow(lights, p, up, radiance, noShare).delta.x;
        int b = 0;
        while (b < 3 && r > bands[b + 1]) ++b;
        meshB[b] += om;
        unionB[b] += ou;
        slB[b] += -ps.delta.x;
        slNoShareB[b] += slNoShare;
        clampedB[b] += ps.ratio <= 1.0 / kShadowMaxRatio + 1e-12 ? 1 : 0;
        ++nB[b];
      }
    std::printf("%s: 16 spheres, overshoot %.2f, union share %.3f, shadow scale %.3f\n", ch.rel, set.volumeOvershoot,
                ss.objectShare[0], ss.objectSilhouette[0]);
    for (int b = 0; b < 4; ++b) {
      if (nB[b] == 0) continue;
      std::printf("  %.2f-%.2f m, %3d receivers: mesh %.4f sr, union/mesh %.3f, SL/mesh %.3f, SL(s=1)/union %.3f, SL/(s·union) %.3f, k at 1/4: %d\n",
                  bands[b], bands[b + 1], nB[b], meshB[b] / nB[b], unionB[b] / meshB[b], slB[b] / meshB[b],
                  slNoShareB[b] / unionB[b], slB[b] / (ss.objectSilhouette[0] * unionB[b]), clampedB[b]);
      // The spheres bound the surface: a ray that meets the mesh meets a sphere first (coverage 0).
      EXPECT_GE(unionB[b], 0.98 * meshB[b]) << ch.rel << " band " << b;
      // Within 0.5 m the baked shadow scale and k already bring the union's 1.7–2.4× down to the
      // mesh's amount (measured 0.85–1.09): under uniform light SL's near-field shadow is NOT too
      // strong, so the 1.5× excess measured in the level (README "SL's near-field shadow, session
      // 17") is not the sphere set's overshoot. (Beyond 1 m the Fox's reads 2.0×: there k sits at
      // its floor 1/kShadowMaxRatio on every receiver (printed: 160 of 160; CesiumMan 111 of 160), so
      // the shadow scale 0.575 changes SL by 0.98× only. Not asserted: a finding, not a contract.)
      if (b < 2) EXPECT_NEAR(slB[b] / meshB[b], 1.0, 0.3) << ch.rel << " band " << b;
    }
  }
}
