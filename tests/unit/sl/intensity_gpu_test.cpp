// SL pass 1 (shaders/sl/intensity.comp) on the device against its C++ reference
// (engine/gi/sl/intensity.hpp: sampleReflection per sample, then Eq. 10–11 in double): a baked
// two-tone sphere's SLs, each posed with its own rotation, translation and scale, lit by a point, a
// spot and a directional light plus per-SL indirect SH, at SH orders 3 and 4; and the shadow path:
// a shadow atlas that occludes everything leaves exactly the indirect light's share; and §5.1's
// blockers: a sample facing one big sphere loses the cap's closed form of its indirect light, and
// the device's blocked samples equal the C++ reference (sl::probeShadow, the function pass 2 uses).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/sl/bake.hpp"
#include "engine/gi/sl/hierarchy.hpp"
#include "engine/gi/sl/intensity.hpp"
#include "engine/gi/sl/intensity_words.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/math/sampling.hpp"
#include "tests/unit/dnrt/test_meshes.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

// The device sums ~92 float terms per coefficient in another order than the double reference,
// and its incident SH per sample is float with ulp-level differences in sqrt/division: a few 1e-6
// of the largest coefficient. 2e-4 of it still catches a wrong basis index, band, pose, albedo
// channel or Gaunt entry (errors ≥ 1e-2 of it).
constexpr double kTolerance = 2e-4;

SphereSet bakedSet(int order) {
  BakeSettings s;
  s.spheres = 5;
  s.order = order;
  s.directions = 92;
  s.samplesPerAxis = 24;
  s.surfaceSamples = 1024;
  s.iterations = 4;
  return bake(gi::dnrt::testing::twoToneSphere(glm::vec3(0.1f, -0.2f, 0.3f), 0.5f, glm::vec3(0.9f, 0.5f, 0.2f),
                                               glm::vec3(0.1f, 0.6f, 0.8f)),
              s);
}

std::vector<render::LightGpu> threeLights() {
  std::vector<render::LightGpu> l(3);
  l[0].positionType = glm::vec4(1.5f, 1.0f, 0.5f, float(render::LightType::Point));
  l[0].directionRange = glm::vec4(0.0f);
  l[0].radiance = glm::vec4(3.0f, 2.5f, 2.0f, 0.0f);
  l[1].positionType = glm::vec4(-1.0f, 2.0f, 1.0f, float(render::LightType::Spot));
  l[1].directionRange = glm::vec4(glm::normalize(glm::vec3(0.4f, -1.0f, -0.3f)), 0.0f);
  l[1].radiance = glm::vec4(4.0f, 4.0f, 5.0f, 0.0f);
  l[1].cone = glm::vec4(std::cos(0.9f), std::cos(0.5f), 0.0f, 0.0f);
  l[2].positionType = glm::vec4(0.0f, 0.0f, 0.0f, float(render::LightType::Directional));
  l[2].directionRange = glm::vec4(glm::normalize(glm::vec3(-0.3f, -1.0f, 0.2f)), 0.0f);
  l[2].radiance = glm::vec4(1.0f, 0.9f, 0.7f, 0.0f);
  for (auto& x : l) x.shadow = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
  return l;
}

struct Frame {
  std::vector<PosedSphere> posed;
  std::vector<gi::incident::RadianceSH> indirect;
};

// Every SL its own pose (rotation about a random axis, translation, scale 0.5..1.5) and indirect SH.
Frame randomFrame(const SphereSet& set, std::uint64_t seed) {
  math::Pcg32 rng(seed);
  Frame f;
  for (const SlSphere& s : set.spheres) {
    const glm::vec3 axis = glm::normalize(glm::vec3(math::uniformSphere(rng.next2D())));
    const float angle = 6.0f * rng.nextFloat();
    const glm::vec3 r = rng.nextFloat3();
    PosedSphere p;
    p.rotation = glm::mat3(glm::rotate(glm::mat4(1.0f), angle, axis));
    p.centre = s.centre + (r - 0.5f) * 0.6f;
    p.radius = s.radius * (0.5f + r.z);
    f.posed.push_back(p);
    gi::incident::RadianceSH ind{};
    ind[0] = glm::vec3(0.8f, 0.7f, 0.6f);
    for (int k = 1; k < 9; ++k) ind[std::size_t(k)] = (rng.nextFloat3() - 0.5f) * 0.3f;
    f.indirect.push_back(ind);
  }
  return f;
}

// A 1×1, 2-layer (so the view is a 2D array, as the atlas's) depth image holding `depth`, ready to
// sample, and the compare sampler the lighting pass uses.
struct Atlas {
  gpu::Image image;
  gpu::SamplerCache samplers;
  VkSampler sampler = VK_NULL_HANDLE;
  Atlas(gpu::Context& ctx, float depth) : samplers(ctx) {
    gpu::ImageDesc d;
    d.format = VK_FORMAT_D32_SFLOAT;
    d.layers = 2;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    d.name = "sl.test.atlas";
    image = gpu::Image(ctx, d);
    const float texels[2] = {depth, depth};
    gpu::upload(ctx, image, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(texels), sizeof texels));
    gpu::SamplerDesc s;
    s.compare = true;
    s.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler = samplers.get(s);
  }
};

// The pass's fp16 pairs (intensity_words.hpp) unpacked: vec4 per (SL·16 + k), rgb = L^c_k.
std::vector<glm::vec4> runPass(gpu::Context& ctx, IntensityPass& pass) {
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) { pass.record(cmd); });
  const auto bytes = gpu::readback(ctx, pass.intensity());
  std::vector<std::uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), words.size() * 4);
  std::vector<glm::vec4> out;
  for (std::size_t i = 0; i + kIntensityWordsPerSl <= words.size(); i += kIntensityWordsPerSl)
    for (const glm::vec3& v : unpackIntensity(std::span(words).subspan(i, kIntensityWordsPerSl))) out.emplace_back(v, 0.0f);
  return out;
}

void expectMatches(const std::vector<glm::vec4>& got, const SphereSet& set, const Frame& f,
                   std::span<const render::LightGpu> lights, int order, const SampleBlockers& blockers = {},
                   double tolerance = kTolerance) {
  const std::size_t nc = std::size_t(order) * std::size_t(order);
  for (std::size_t i = 0; i < set.spheres.size(); ++i) {
    const auto want = intensityReference(set.spheres[i], order, f.posed[i], lights, f.indirect[i], blockers);
    ASSERT_EQ(want.size(), nc);
    double scale = 0.0;
    for (const glm::dvec3& w : want) scale = std::max({scale, std::abs(w.r), std::abs(w.g), std::abs(w.b)});
    ASSERT_GT(scale, 1e-3) << "SL " << i << " receives no light: the fixture tests nothing";
    for (std::size_t k = 0; k < 16; ++k)
      for (int c = 0; c < 3; ++c) {
        const double g = got[i * 16 + k][c];
        if (k >= nc) {
          EXPECT_EQ(g, 0.0) << "SL " << i << " coefficient " << k << " beyond order " << order;
          continue;
        }
        // The float pass's bound plus the fp16 store's rounding (≤ 2⁻¹¹ of the value; 2⁻²⁵ absolute
        // below half's normal range).
        const double bound = tolerance * scale + kIntensityHalfRelative * std::abs(want[k][c]) + 0x1p-25;
        EXPECT_NEAR(g, want[k][c], bound) << "SL " << i << " coefficient " << k << " channel " << c;
      }
  }
}

}  // namespace

TEST(SlIntensityGpu, ComputePassEqualsTheCppReferenceAtOrders3And4) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const std::vector<render::LightGpu> lights = threeLights();
  for (int order : {3, 4}) {
    SCOPED_TRACE("order " + std::to_string(order));
    const SphereSet set = bakedSet(order);
    ASSERT_EQ(set.spheres.size(), 5u);
    const SphereSet* sets[] = {&set};
    IntensityPass pass(ctx, sets, order);
    ASSERT_EQ(pass.sphereCount(), 5u);
    Atlas atlas(ctx, 1.0f);
    pass.setShadowAtlas(atlas.image.view(), atlas.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false);
    for (std::uint64_t seed : {1u, 2u}) {
      const Frame f = randomFrame(set, seed + std::uint64_t(order) * 10);
      pass.setSpheres(f.posed, f.indirect);
      pass.setLights(lights, {});
      expectMatches(runPass(ctx, pass), set, f, lights, order);
    }
  }
}

// Two sets in one pass: SL indices run over the sets in order, each SL reads its own samples.
TEST(SlIntensityGpu, SeveralSetsConcatenate) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const std::vector<render::LightGpu> lights = threeLights();
  const SphereSet a = bakedSet(4);
  SphereSet b = bakedSet(4);
  b.spheres.resize(2);
  for (SlSphere& s : b.spheres)
    for (float& x : s.albedo) x *= 0.5f;
  const SphereSet* sets[] = {&a, &b};
  IntensityPass pass(ctx, sets, 4);
  ASSERT_EQ(pass.sphereCount(), 7u);
  Atlas atlas(ctx, 1.0f);
  pass.setShadowAtlas(atlas.image.view(), atlas.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false);
  Frame fa = randomFrame(a, 7), fb = randomFrame(b, 8);
  Frame all = fa;
  all.posed.insert(all.posed.end(), fb.posed.begin(), fb.posed.end());
  all.indirect.insert(all.indirect.end(), fb.indirect.begin(), fb.indirect.end());
  pass.setSpheres(all.posed, all.indirect);
  pass.setLights(lights, {});
  const std::vector<glm::vec4> got = runPass(ctx, pass);
  expectMatches(std::vector<glm::vec4>(got.begin(), got.begin() + 5 * 16), a, fa, lights, 4);
  expectMatches(std::vector<glm::vec4>(got.begin() + 5 * 16, got.end()), b, fb, lights, 4);
}

// Shadows on: every light's shadow lookup lands on one atlas texel (the matrix sends every point to
// NDC (0, 0, 0.5)). Depth 0 there occludes every light — only the indirect light is left; depth 1
// occludes none — the unshadowed result.
TEST(SlIntensityGpu, ShadowAtlasVisibilityMultipliesTheLights) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  std::vector<render::LightGpu> lights = threeLights();
  lights.erase(lights.begin());  // the spot and the directional light: one atlas layer each
  for (std::size_t i = 0; i < lights.size(); ++i) lights[i].shadow = glm::vec4(float(i), 0.0f, 0.0f, 0.0f);
  glm::mat4 toCentre(0.0f);
  toCentre[3] = glm::vec4(0.0f, 0.0f, 0.5f, 1.0f);
  const std::vector<glm::mat4> matrices = {toCentre, toCentre};
  const SphereSet set = bakedSet(4);
  const SphereSet* sets[] = {&set};
  IntensityPass pass(ctx, sets, 4);
  const Frame f = randomFrame(set, 3);
  pass.setSpheres(f.posed, f.indirect);
  pass.setLights(lights, matrices);
  // The two expectations differ by much more than the tolerance: the lights carry a good share.
  const auto lit = intensityReference(set.spheres[0], 4, f.posed[0], lights, f.indirect[0]);
  const auto dark = intensityReference(set.spheres[0], 4, f.posed[0], {}, f.indirect[0]);
  ASSERT_GT(glm::length(lit[0] - dark[0]), 0.1 * glm::length(lit[0]));
  {
    Atlas occluding(ctx, 0.0f);
    pass.setShadowAtlas(occluding.image.view(), occluding.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, true);
    expectMatches(runPass(ctx, pass), set, f, {}, 4);
  }
  Atlas open(ctx, 1.0f);
  pass.setShadowAtlas(open.image.view(), open.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, true);
  expectMatches(runPass(ctx, pass), set, f, lights, 4);
}

// The fp16-pair layout of pass 1's output (intensity_words.hpp): word 8c + m holds channel c of
// coefficients 2m (low 16 bits) and 2m + 1; every value within half's rounding, 2⁻¹¹ relative, over
// magnitudes 1e-3 … 6e4 and both signs; beyond half's range clamped to ±65504; missing
// coefficients 0. (The shaders' side of the layout: SlIntensityGpu.* unpack pass 1's words with
// unpackIntensity, SlShadeGpu.* feed pass 2 packIntensity's.)
TEST(SlIntensity, HalfPairsKeepEveryCoefficientWithinHalfRounding) {
  std::vector<glm::vec3> coeffs;
  for (int k = 0; k < 16; ++k) {
    const float mag = std::pow(10.0f, -3.0f + 7.7f * float(k) / 15.0f) * 1.2345f;  // 1.2e-3 … 6.2e4
    coeffs.emplace_back(mag, -0.5f * mag, k % 2 ? mag * 0.1f : -mag);
  }
  const auto words = packIntensity(coeffs);
  const auto back = unpackIntensity(words);
  for (std::size_t k = 0; k < 16; ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(back[k][c], coeffs[k][c], kIntensityHalfRelative * std::abs(coeffs[k][c])) << k << " " << c;
  // Layout: channel g (c = 1) of coefficients 6 and 7 sits in word 8 + 3, 6 in the low half.
  EXPECT_EQ(words[11], glm::packHalf2x16(glm::vec2(coeffs[6].g, coeffs[7].g)));
  EXPECT_EQ(words[11] & 0xffffu, glm::packHalf2x16(glm::vec2(coeffs[6].g, 0.0f)));
  // Order 3 (9 coefficients): the last pair's second half and pairs 5–7 are 0; out of range clamps.
  std::vector<glm::vec3> nine(coeffs.begin(), coeffs.begin() + 9);
  nine[0] = glm::vec3(1e6f, -1e6f, 0.0f);
  const auto b9 = unpackIntensity(packIntensity(nine));
  EXPECT_EQ(b9[0], glm::vec3(kIntensityHalfMax, -kIntensityHalfMax, 0.0f));
  for (std::size_t k = 9; k < 16; ++k) EXPECT_EQ(b9[k], glm::vec3(0.0f)) << k;
  EXPECT_NEAR(b9[8].r, nine[8].r, kIntensityHalfRelative * nine[8].r);
}

// §5.1 at one sample point (C++ reference): p on the top of its own SL (normal +z) under uniform
// indirect radiance L, one sphere of another object at angular radius θ (sin θ up to 0.95) whose
// centre is β from n, wholly above the tangent plane.
// probe_shadow.hpp's Ratio form makes one cap's loss exact: L_p = L (1 − sin²θ cos β) (the cosine-
// weighted solid angle of the cap over π). The sample's own SL touches p from below and is culled by
// the receiver rules, so it takes nothing. Float E on the way (sampleReflection): kCapTolerance.
TEST(SlIntensity, ASampleFacingABigBlockerLosesTheCapsClosedForm) {
  constexpr double kCapTolerance = 1e-4;  // of L
  SlSphere rest;
  rest.centre = glm::vec3(0.0f, 0.0f, -0.5f);
  rest.radius = 0.5f;
  SurfaceSample sample;
  sample.position = glm::vec3(0.0f);
  sample.normal = glm::vec3(0.0f, 0.0f, 1.0f);
  PosedSphere posed;
  posed.centre = rest.centre;
  posed.radius = rest.radius;
  const float L = 0.7f;
  gi::incident::RadianceSH uniform{};
  uniform[0] = glm::vec3(L * float(std::sqrt(4.0 * math::kPi)));  // radiance = c00 Y00
  EXPECT_NEAR(sampleReflection(sample, rest, posed, {}, uniform).x, L, kCapTolerance * L);
  int cases = 0;
  for (const double beta : {0.0, 0.5, 1.0})
    for (const double sinTheta : {0.5, 0.8, 0.95}) {
      // The closed form holds for a cap wholly above the tangent plane (β + θ ≤ π/2); a crossing
      // sphere is shrunk above the plane by the receiver rules (evaluate.hpp rule 2).
      if (beta + std::asin(sinTheta) > 0.5 * math::kPi) continue;
      ++cases;
      const double d = 1.0;
      std::vector<Light> blockers(2);
      blockers[0].sphere = {glm::dvec3(posed.centre), double(posed.radius)};  // its own SL (object 0)
      blockers[0].object = 0;
      blockers[1].sphere = {d * glm::dvec3(std::sin(beta), 0.0, std::cos(beta)), d * sinTheta};
      blockers[1].object = 1;
      SampleBlockers b{blockers, ShadowSettings{}};
      const double want = L * (1.0 - sinTheta * sinTheta * std::cos(beta));
      const glm::vec3 got = sampleReflection(sample, rest, posed, {}, uniform, b);
      EXPECT_NEAR(got.x, want, kCapTolerance * L) << "beta " << beta << " sin theta " << sinTheta;
      EXPECT_NEAR(got.z, want, kCapTolerance * L);
    }
  EXPECT_EQ(cases, 6);
}

// The device's blocked samples (intensity.comp with sl/probe_shadow.glsl over ShadeData) equal the
// C++ reference (sampleReflection with sl::probeShadow) at orders 3 and 4: two objects side by side,
// every SL of both a blocker (their own SL and containing neighbours culled by the receiver rules),
// union shares and shadow scales per object as the node sets them. Tolerance: sl.shadow's GLSL vs
// C++ bound (5e-4 of E_u, SlProbeShadowGpu) on ΔE, of the largest coefficient here. The blockers
// move the result by far more than that (checked), so the comparison tests the blocking.
TEST(SlIntensityGpu, BlockedIndirectLightEqualsTheCppReference) {
  constexpr double kBlockedTolerance = 5e-4;
  gpu::Context& ctx = gpu::testkit::sharedContext();
  gpu::SamplerCache samplers(ctx);
  const VkSampler nearest = samplers.get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  const std::vector<render::LightGpu> lights = threeLights();
  for (int order : {3, 4}) {
    SCOPED_TRACE("order " + std::to_string(order));
    const SphereSet a = bakedSet(order), b = bakedSet(order);
    const SphereSet* sets[] = {&a, &b};
    IntensityPass pass(ctx, sets, order);
    Atlas atlas(ctx, 1.0f);
    pass.setShadowAtlas(atlas.image.view(), atlas.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false);
    Frame fa = randomFrame(a, 21), fb = randomFrame(b, 22);
    for (PosedSphere& p : fb.posed) p.centre += glm::vec3(1.1f, 0.0f, 0.0f);  // b beside a
    Frame all = fa;
    all.posed.insert(all.posed.end(), fb.posed.begin(), fb.posed.end());
    all.indirect.insert(all.indirect.end(), fb.indirect.begin(), fb.indirect.end());
    pass.setSpheres(all.posed, all.indirect);
    pass.setLights(lights, {});
    const float share[2] = {0.8f, 0.6f}, silhouette[2] = {0.7f, 0.9f};
    std::vector<ShadedSphere> shaded;
    std::vector<Light> blockers;
    for (std::size_t i = 0; i < all.posed.size(); ++i) {
      const std::uint32_t object = i < a.spheres.size() ? 0u : 1u;
      shaded.push_back({all.posed[i].centre, all.posed[i].radius, all.posed[i].rotation, object, share[object], silhouette[object]});
      Light l;
      l.sphere = {glm::dvec3(all.posed[i].centre), double(all.posed[i].radius)};
      l.rotation = glm::dmat3(all.posed[i].rotation);
      l.object = int(object);
      blockers.push_back(l);
    }
    ShadeData shade(ctx, order);
    shade.setSpheres(shaded);
    pass.setBlockers(shade, nearest);
    ShadowSettings settings;
    settings.order = order;
    settings.objectShare = {share[0], share[1]};
    settings.objectSilhouette = {silhouette[0], silhouette[1]};
    const SampleBlockers with{blockers, settings};
    // Not vacuous: the blocked reference differs from the unblocked one by ≫ the tolerance.
    const auto open = intensityReference(a.spheres[0], order, fa.posed[0], lights, fa.indirect[0]);
    const auto shut = intensityReference(a.spheres[0], order, fa.posed[0], lights, fa.indirect[0], with);
    double moved = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < open.size(); ++k)
      moved = std::max(moved, glm::length(open[k] - shut[k])), scale = std::max(scale, glm::length(open[k]));
    std::printf("order %d: blockers move SL 0's intensity by %.4f of its largest coefficient\n", order, moved / scale);
    EXPECT_GT(moved, 20.0 * kBlockedTolerance * scale);
    const std::vector<glm::vec4> got = runPass(ctx, pass);
    const std::size_t na = a.spheres.size() * 16;
    expectMatches(std::vector<glm::vec4>(got.begin(), got.begin() + std::ptrdiff_t(na)), a, fa, lights, order, with,
                  kBlockedTolerance);
    expectMatches(std::vector<glm::vec4>(got.begin() + std::ptrdiff_t(na), got.end()), b, fb, lights, order, with,
                  kBlockedTolerance);
    // Blockers off again: the unblocked reference.
    pass.setBlockers(shade, nearest, false);
    const std::vector<glm::vec4> unblocked = runPass(ctx, pass);
    expectMatches(std::vector<glm::vec4>(unblocked.begin(), unblocked.begin() + std::ptrdiff_t(na)), a, fa, lights, order);
  }
}

// §7.3 local lights in pass 1: with pc.blockers bit 1 the SLs also block the point and spot lights
// at the samples (sl/local_light.glsl over ShadeData), equal to the C++ reference (sampleReflection
// with sl::localLightVisibility) within kLocalTolerance of the largest coefficient: the GLSL's
// visible fraction is within 1.5e-2 of the C++ (SlLocalLightGpu), of lights that are part of the
// sum. Two objects side by side, lights of radius 0.2 m; the blocking moves the result (checked).
TEST(SlIntensityGpu, LocalLightsBlockedBySlsEqualTheCppReference) {
  constexpr double kLocalTolerance = 1e-2;
  gpu::Context& ctx = gpu::testkit::sharedContext();
  gpu::SamplerCache samplers(ctx);
  const VkSampler nearest = samplers.get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  std::vector<render::LightGpu> lights = threeLights();
  lights[0].radiance.w = lights[1].radiance.w = 0.2f;
  const int order = 4;
  const SphereSet a = bakedSet(order), b = bakedSet(order);
  const SphereSet* sets[] = {&a, &b};
  IntensityPass pass(ctx, sets, order);
  Atlas atlas(ctx, 1.0f);
  pass.setShadowAtlas(atlas.image.view(), atlas.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false);
  Frame fa = randomFrame(a, 31), fb = randomFrame(b, 32);
  for (PosedSphere& p : fb.posed) p.centre += glm::vec3(0.9f, 0.3f, 0.2f);  // b between a and light 0
  Frame all = fa;
  all.posed.insert(all.posed.end(), fb.posed.begin(), fb.posed.end());
  all.indirect.insert(all.indirect.end(), fb.indirect.begin(), fb.indirect.end());
  pass.setSpheres(all.posed, all.indirect);
  pass.setLights(lights, {});
  const float share[2] = {0.8f, 0.6f}, silhouette[2] = {0.7f, 0.9f};
  std::vector<ShadedSphere> shaded;
  std::vector<Light> blockers;
  for (std::size_t i = 0; i < all.posed.size(); ++i) {
    const std::uint32_t object = i < a.spheres.size() ? 0u : 1u;
    shaded.push_back({all.posed[i].centre, all.posed[i].radius, all.posed[i].rotation, object, share[object], silhouette[object]});
    Light l;
    l.sphere = {glm::dvec3(all.posed[i].centre), double(all.posed[i].radius)};
    l.rotation = glm::dmat3(all.posed[i].rotation);
    l.object = int(object);
    blockers.push_back(l);
  }
  ShadeData shade(ctx, order);
  shade.setSpheres(shaded);
  pass.setBlockers(shade, nearest, false, true);  // the lights only, not the indirect light
  ShadowSettings settings;
  settings.order = order;
  settings.objectShare = {share[0], share[1]};
  settings.objectSilhouette = {silhouette[0], silhouette[1]};
  SampleBlockers local{blockers, settings};
  local.localLights = true;
  // Only the local lights blocked: the reference applies probeShadow whenever blockers are listed,
  // so the indirect light is zero on both sides (then its ΔE is 0) and the lights alone compare.
  double moved = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.spheres.size(); ++i) {
    const auto open = intensityReference(a.spheres[i], order, fa.posed[i], lights, {}, {});
    const auto shut = intensityReference(a.spheres[i], order, fa.posed[i], lights, {}, local);
    for (std::size_t k = 0; k < open.size(); ++k)
      moved = std::max(moved, glm::length(open[k] - shut[k])), scale = std::max(scale, glm::length(open[k]));
  }
  std::printf("local lights move object a's intensity by %.4f of its largest coefficient\n", moved / scale);
  EXPECT_GT(moved, 3.0 * kLocalTolerance * scale);  // measured 0.043 of the largest coefficient
  // Zero indirect light on the device too, so both sides are the lights alone.
  for (auto& sh : all.indirect) sh = {};
  for (auto& sh : fa.indirect) sh = {};
  for (auto& sh : fb.indirect) sh = {};
  pass.setSpheres(all.posed, all.indirect);
  const std::vector<glm::vec4> got = runPass(ctx, pass);
  const std::size_t na = a.spheres.size() * 16;
  expectMatches(std::vector<glm::vec4>(got.begin(), got.begin() + std::ptrdiff_t(na)), a, fa, lights, order, local,
                kLocalTolerance);
  expectMatches(std::vector<glm::vec4>(got.begin() + std::ptrdiff_t(na), got.end()), b, fb, lights, order, local,
                kLocalTolerance);
}

// §7.3 hierarchy (hierarchy.hpp): the parents' intensity, formed on the device at the end of pass 1
// (shaders/sl/parent_intensity.comp), equals hierarchy.hpp parentOf — the C++ reference's
// Σ_j (r_j/r_P)² R_j L^c_j in double — over the device's own children (read back, so the bound is
// the float sum's and the parent's fp16 store, not pass 1's). Two sets (objects), every child
// rotated, one pose mirrored (det −1: band l of −Q is (−1)^l Q's, here against −Q's parentOf ×
// (−1)^l); the children's words are unchanged by the second dispatch.
TEST(SlIntensityGpu, ParentsAreParentOfOverTheDevicesChildren) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const std::vector<render::LightGpu> lights = threeLights();
  for (int order : {3, 4}) {
    SCOPED_TRACE("order " + std::to_string(order));
    const SphereSet a = bakedSet(order);
    SphereSet b = bakedSet(order);
    b.spheres.resize(3);
    const SphereSet* sets[] = {&a, &b};
    IntensityPass plain(ctx, sets, order);
    IntensityPass pass(ctx, sets, order, 0.0f, true);
    ASSERT_EQ(pass.sphereCount(), 8u);
    Atlas atlas(ctx, 1.0f);
    for (IntensityPass* p : {&plain, &pass})
      p->setShadowAtlas(atlas.image.view(), atlas.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false);
    Frame fa = randomFrame(a, 31 + std::uint64_t(order)), fb = randomFrame(b, 41 + std::uint64_t(order));
    fb.posed[1].rotation = -fb.posed[1].rotation;  // mirrored
    Frame all = fa;
    all.posed.insert(all.posed.end(), fb.posed.begin(), fb.posed.end());
    all.indirect.insert(all.indirect.end(), fb.indirect.begin(), fb.indirect.end());
    for (IntensityPass* p : {&plain, &pass}) {
      p->setSpheres(all.posed, all.indirect);
      p->setLights(lights, {});
    }
    const std::vector<glm::vec4> want0 = runPass(ctx, plain), got = runPass(ctx, pass);
    for (std::size_t i = 0; i < 8 * 16; ++i) EXPECT_EQ(got[i], want0[i]) << "child word " << i;
    ASSERT_EQ(pass.parents().size(), 2u);
    const std::size_t nc = std::size_t(order) * std::size_t(order);
    for (int o = 0; o < 2; ++o) {
      std::vector<Light> kids;
      const std::size_t first = o == 0 ? 0 : 5, count = o == 0 ? 5 : 3;
      for (std::size_t i = first; i < first + count; ++i) {
        Light l;
        l.object = o;
        l.sphere = {glm::dvec3(all.posed[i].centre), double(all.posed[i].radius)};
        l.rotation = glm::dmat3(all.posed[i].rotation);
        const bool mirrored = glm::determinant(l.rotation) < 0.0;
        if (mirrored) l.rotation = -l.rotation;
        for (std::size_t k = 0; k < nc; ++k) {
          const int band = k < 1 ? 0 : (k < 4 ? 1 : (k < 9 ? 2 : 3));
          l.intensity.push_back(glm::dvec3(glm::vec3(got[i * 16 + k])) * (mirrored && band % 2 == 1 ? -1.0 : 1.0));
        }
        kids.push_back(l);
      }
      const Light want = parentOf(kids);
      const PosedSphere& parent = pass.parents()[std::size_t(o)];
      EXPECT_LT(glm::length(glm::dvec3(parent.centre) - want.sphere.centre), 1e-6 * want.sphere.radius) << o;
      EXPECT_NEAR(parent.radius, want.sphere.radius, 1e-6 * want.sphere.radius) << o;
      double scale = 0.0;
      for (const glm::dvec3& w : want.intensity) scale = std::max({scale, std::abs(w.r), std::abs(w.g), std::abs(w.b)});
      ASSERT_GT(scale, 1e-3) << "parent " << o << " receives no light: the fixture tests nothing";
      for (std::size_t k = 0; k < 16; ++k)
        for (int c = 0; c < 3; ++c) {
          const double g = got[(8 + std::size_t(o)) * 16 + k][c];
          if (k >= nc) {
            EXPECT_EQ(g, 0.0) << "parent " << o << " coefficient " << k;
            continue;
          }
          // Float rotation sums of ≤ 7 terms per child (1e-6 of the largest coefficient is ~100× their
          // rounding) plus the fp16 store.
          EXPECT_NEAR(g, want.intensity[k][c], 1e-6 * scale + kIntensityHalfRelative * std::abs(want.intensity[k][c]) + 0x1p-25)
              << "parent " << o << " coefficient " << k << " channel " << c;
        }
    }
  }
}
