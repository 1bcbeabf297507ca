// The SLs' soft shadow on the probes' light in GLSL (shaders/sl/probe_shadow.glsl with the probes'
// radiance read by shaders/probes/probe_sh.glsl, run per receiver by probe_shadow_selftest.comp)
// against its C++ reference sl::probeShadow with the probe volume's CPU lookup, at SH orders 3 and
// 4: receivers on a plane under two objects (overlapping spheres), inside / on / crossing a sphere,
// and under a dense cluster that needs the hybrid exp's squarings; then the closed form through the
// GPU path (one sphere over a plane under a uniform probe volume darkens by sin²θ cos β).
#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/gi/probes/node.hpp"
#include "engine/gi/sl/probe_shadow.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/math/sh_exp.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

// fp32 against double, relative to E_u (the light there is to take away) plus 1e-6 absolute: the
// same steps; the differences are float rounding in the tables' interpolation, the rotated ZH, the
// exp (its e^{f_0 Y_00} amplifies a relative error of f_0 by up to ~10 in dense clusters) and the
// probe weights. Measured worst: printed.
constexpr double kTolerance = 5e-4;  // measured worst 5.8e-5 (printed)

struct Receiver {
  glm::vec4 p, n, v;
};

struct Fixture {
  std::vector<Light> lights;
  std::vector<ShadedSphere> shaded;
  std::vector<double> shares;  // per object (missing: 1)
  float share(int object) const { return std::size_t(object) < shares.size() ? float(shares[std::size_t(object)]) : 1.0f; }
  std::vector<double> silhouettes;  // per object: the sets' shadow scales (missing: 1)
  float silhouette(int object) const {
    return std::size_t(object) < silhouettes.size() ? float(silhouettes[std::size_t(object)]) : 1.0f;
  }
};

void addSphere(Fixture& f, glm::vec3 c, float r, int object) {
  Light l;
  l.sphere = {glm::dvec3(c), double(r)};
  l.intensity.assign(16, glm::dvec3(0.0));
  l.object = object;
  f.lights.push_back(l);
  f.shaded.push_back({c, r, glm::mat3(1.0f), std::uint32_t(object), f.share(object), f.silhouette(object)});
}

// Two objects above z = 0 (a chain of overlapping spheres and a cluster of three), as SlShadeGpu's,
// with their union shares and their sets' shadow scales (bounce_scale.hpp).
void addTwoObjects(Fixture& f) {
  f.shares = {0.55, 0.8};
  f.silhouettes = {0.45, 0.7};
  addSphere(f, {-0.3f, 0.0f, 0.6f}, 0.25f, 0);
  addSphere(f, {-0.1f, 0.1f, 0.75f}, 0.2f, 0);
  addSphere(f, {0.1f, 0.15f, 0.9f}, 0.18f, 0);
  addSphere(f, {0.3f, 0.1f, 1.05f}, 0.15f, 0);
  addSphere(f, {0.5f, -0.6f, 0.4f}, 0.2f, 1);
  addSphere(f, {0.7f, -0.5f, 0.45f}, 0.15f, 1);
  addSphere(f, {0.55f, -0.3f, 0.7f}, 0.12f, 1);
}

// A 5×5×4 volume over [−1, 1]² × [−0.2, 1]: smooth, non-negative radiance lobes varying over the grid
// (so the trilinear lookup matters), every probe valid, moments far beyond any receiver (Chebyshev 1).
gi::probes::ProbeVolume volume(int order) {
  gi::probes::ProbeVolume v;
  v.order = order;
  v.grid.origin = glm::vec3(-1.0f, -1.0f, -0.2f);
  v.grid.spacing = 0.5f;
  v.grid.count = glm::ivec3(5, 5, 4);
  math::Pcg32 rng(21);
  const std::size_t probes = v.grid.probeCount();
  for (std::size_t p = 0; p < probes; ++p) {
    const glm::vec3 d = glm::normalize(glm::vec3(math::uniformSphere(rng.next2D())) + glm::vec3(0, 0, 0.8f));
    const auto y = sh::evalBasis<float>(order, d);
    const glm::vec3 tint(0.6f + 0.4f * rng.nextFloat(), 0.5f + 0.3f * rng.nextFloat(), 0.3f + 0.3f * rng.nextFloat());
    for (int i = 0; i < order * order; ++i) {
      const float band = i == 0 ? 0.0f : (i < 4 ? 1.4f : 0.5f);  // a wide lobe towards d on a constant
      glm::vec3 c = tint * band * y[std::size_t(i)];
      if (i == 0) c = tint * 3.5449077f;  // constant radiance 1 (× tint)
      v.sh.push_back(c);
    }
    v.valid.push_back(1);
    for (int b = 0; b < gi::probes::kVisBins; ++b) v.moments.push_back(glm::vec2(100.0f, 10000.0f));
  }
  return v;
}

// L at (p, n, v) as probe_sh.glsl computes it, through the volume's CPU weights (probe_weights.glsl
// compiled as C++).
std::vector<glm::dvec3> cpuRadiance(const gi::probes::ProbeVolume& vol, const Receiver& r) {
  int probe[8];
  float weight[8];
  vol.weights(glm::vec3(r.p), glm::vec3(r.n), glm::vec3(r.v), probe, weight);
  std::vector<glm::dvec3> L(std::size_t(vol.coeffs()), glm::dvec3(0.0));
  for (int k = 0; k < 8; ++k)
    for (int i = 0; i < vol.coeffs(); ++i) L[std::size_t(i)] += double(weight[k]) * glm::dvec3(vol.sh[std::size_t(probe[k]) * vol.coeffs() + i]);
  return L;
}

struct Output {
  glm::vec3 delta, unshadowed;
};

// `sphereL` (empty, or one per sphere): "blocked_light": "sphere" with these radiance SH at the SLs;
// `maps` (empty, or one per sphere): "blocked_read": "map" with these direction maps instead.
std::vector<Output> runShader(gpu::Context& ctx, const Fixture& f, const gi::probes::ProbeVolume& vol,
                              std::span<const Receiver> receivers, int order,
                              std::span<const gi::incident::RadianceSH> sphereL = {},
                              std::span<const gi::incident::DirectionMap> maps = {}) {
  ShadeData data(ctx, order, std::uint32_t(maps.size()));  // the map layout's block for these SLs, else the SH's
  data.setSpheres(f.shaded, {}, sphereL, maps);
  gpu::Buffer intensity(ctx, {kIntensityBlockBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.test.intensity"});
  std::memset(intensity.mapped(), 0, intensity.size());
  const auto sh = gi::probes::uploadSh(ctx, vol);
  const auto moments = gi::probes::uploadMoments(ctx, vol);
  std::vector<std::uint8_t> in(16 + receivers.size_bytes(), 0);
  const std::uint32_t count = std::uint32_t(receivers.size());
  std::memcpy(in.data(), &count, 4);
  std::memcpy(in.data() + 16, receivers.data(), receivers.size_bytes());
  gpu::Buffer inBuf(ctx, {in.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.test.receivers"});
  std::memcpy(inBuf.mapped(), in.data(), in.size());
  gpu::Buffer outBuf(ctx, {receivers.size() * 32, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Readback, "sl.test.out"});
  std::vector<gpu::Binding> b = ShadeData::bindings(0);
  b.push_back({3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
  b.push_back({4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
  b.push_back({5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  b.push_back({6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  b.push_back({7, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER});
  gpu::DescriptorSetLayout layout(ctx, b, "sl.shadow.test");
  gpu::PipelineLayout pipelineLayout(ctx, {layout}, {{VK_SHADER_STAGE_ALL, 0, sizeof(gi::probes::ProbePush)}},
                                     "sl.shadow.test");
  gpu::SpecConstants spec = ShadeData::specialization(order, Blocking::PerSphere, std::uint32_t(f.shaded.size()));
  spec.push_back(std::uint32_t(vol.coeffs()));
  spec.push_back(sphereL.empty() && maps.empty() ? 0u : 1u);  // kBlockedAtSphere
  spec.push_back(maps.empty() ? 0u : 1u);                      // kBlockedMap
  gpu::Pipeline pipeline = gpu::createComputePipeline(
      ctx, pipelineLayout, gpu::ShaderModule(ctx, "sl/probe_shadow_selftest.comp.spv"), "sl.shadow.test", nullptr, spec);
  gpu::SamplerCache samplers(ctx);
  gpu::SamplerDesc nearest;
  nearest.filter = VK_FILTER_NEAREST;
  nearest.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  const VkSampler point = samplers.get(nearest);
  gpu::DescriptorAllocator descriptors(ctx);
  VkDescriptorSet set = descriptors.allocate(layout);
  gpu::DescriptorWriter w;
  data.write(w, 0, intensity, point);
  data.writeIndirect(w, 7);
  w.sampledImage(3, sh->view(), point).sampledImage(4, moments->view(), point).buffer(5, inBuf).buffer(6, outBuf).update(ctx, set);
  const gi::probes::ProbePush push = gi::probes::probePush(vol, 0.0f);
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    pipeline.bindSet(cmd, 0, set);
    pipeline.push(cmd, push);
    vkCmdDispatch(cmd, (count + 63) / 64, 1, 1);
  });
  const auto bytes = gpu::readback(ctx, outBuf);
  std::vector<glm::vec4> raw(2 * std::size_t(count));
  std::memcpy(raw.data(), bytes.data(), raw.size() * sizeof(glm::vec4));
  std::vector<Output> out;
  for (std::uint32_t i = 0; i < count; ++i) out.push_back({glm::vec3(raw[2 * i]), glm::vec3(raw[2 * i + 1])});
  return out;
}

Receiver receiver(glm::vec3 p, glm::vec3 n) {
  return {glm::vec4(p, 0.0f), glm::vec4(glm::normalize(n), 0.0f),
          glm::vec4(glm::normalize(glm::vec3(0.3f, -0.8f, 1.0f)), 0.0f)};
}

// 12 × 12 receivers facing +z over the floor square [-0.9, 0.9]² at z = 0.
std::vector<Receiver> floorGrid() {
  std::vector<Receiver> r;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) r.push_back(receiver({-0.9f + 1.8f * x / 11.0f, -0.9f + 1.8f * y / 11.0f, 0.0f}, {0, 0, 1}));
  return r;
}

// Compares every receiver; returns the worst |GPU − C++| / (|E_u| + 1e-6) and how many are shadowed.
double expectMatches(const Fixture& f, const gi::probes::ProbeVolume& vol, std::span<const Receiver> r,
                     const std::vector<Output>& gpu, int order, int* shadowed,
                     std::span<const gi::incident::RadianceSH> sphereL = {},
                     std::span<const gi::incident::DirectionMap> maps = {}) {
  ShadowSettings s;
  s.order = order;
  s.objectShare = f.shares;
  s.objectSilhouette = f.silhouettes;
  if (!sphereL.empty()) {
    // The reference reads the same fp16 values the shader reads (ShadeData packs them): the test
    // compares the arithmetic, not the block's rounding.
    s.blocked = BlockedLight::Sphere;
    for (const gi::incident::RadianceSH& sh : sphereL) {
      std::vector<glm::dvec3> c;
      for (const glm::vec3& v : sh) c.push_back(glm::dvec3(glm::unpackHalf(glm::packHalf(v))));
      s.sphereRadiance.push_back(c);
    }
  }
  if (!maps.empty()) {  // the same RGB9E5 rounding as ShadeData's map layout
    s.blocked = BlockedLight::Sphere;
    s.read = BlockedRead::Map;
    for (const gi::incident::DirectionMap& m : maps) {
      std::vector<glm::dvec3> c;
      for (const glm::vec3& v : m) c.push_back(glm::dvec3(glm::unpackF3x9_E1x5(glm::packF3x9_E1x5(v))));
      s.sphereMap.push_back(c);
    }
  }
  double worst = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const auto L = cpuRadiance(vol, r[i]);
    const ProbeShadow ref = probeShadow(f.lights, glm::dvec3(r[i].p), glm::dvec3(r[i].n), L, s);
    const double scale = glm::length(ref.unshadowed) + 1e-6;
    *shadowed += glm::length(ref.delta) > 1e-2 * scale;
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(gpu[i].delta[c])) << "receiver " << i;
      const double err = std::abs(double(gpu[i].delta[c]) - ref.delta[c]);
      worst = std::max({worst, err / scale, std::abs(double(gpu[i].unshadowed[c]) - ref.unshadowed[c]) / scale});
      EXPECT_LE(err, kTolerance * scale) << "receiver " << i << " channel " << c << ": GPU " << gpu[i].delta[c] << " C++ "
                                        << ref.delta[c];
      EXPECT_NEAR(gpu[i].unshadowed[c], ref.unshadowed[c], kTolerance * scale) << "receiver " << i;
    }
  }
  return worst;
}

}  // namespace

TEST(SlProbeShadowGpu, GlslEqualsProbeShadowOnAPlaneInsideAndUnderACluster) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  Fixture f;
  addTwoObjects(f);  // the column below adds objects with share 1 and shadow scale 1
  // A dense column of 16 large spheres over (−0.6, 0.6): the summed logs need squarings there.
  for (int i = 0; i < 16; ++i) {
    const float a = 0.5236f * std::sqrt((float(i) + 0.5f) / 16.0f), phi = 2.39996f * float(i);
    const glm::vec3 d(std::sin(a) * std::cos(phi), std::sin(a) * std::sin(phi), std::cos(a));
    addSphere(f, glm::vec3(-0.6f, 0.6f, 0.0f) + d * (0.35f + 0.01f * float(i)), 0.28f, 2 + i);
  }
  std::vector<Receiver> r = floorGrid();
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) r.push_back(receiver({-0.7f + 0.2f * x / 3.0f, 0.5f + 0.2f * y / 3.0f, 0.0f}, {0, 0, 1}));
  // Inside sphere 0 (t = 0.8, 0.6, 0.3 of its radius), on it and just outside, with tilted normals.
  const glm::vec3 c(f.shaded[0].centre);
  const float r0 = f.shaded[0].radius;
  const glm::vec3 toward = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
  for (float t : {0.8f, 0.6f, 0.3f, 1.0f, 1.02f})
    for (const glm::vec3& n : {glm::vec3(0, 0, 1), glm::vec3(1, 0, 1), -toward}) r.push_back(receiver(c + toward * (t * r0), n));
  {  // the column's summed log at its foot is beyond the OL range: squarings are exercised
    std::vector<double> sum(16, 0.0);
    const sh::ExpTables& t = sh::expTables(4);
    const glm::dvec3 foot(-0.6, 0.6, 0.0);
    for (const Light& l : f.lights) {
      const glm::dvec3 to = l.sphere.centre - foot;
      if (to.z - l.sphere.radius < 0.0) continue;
      const auto g = t.logBlocker(std::asin(l.sphere.radius / glm::length(to)), glm::normalize(to));
      for (std::size_t k = 0; k < 16; ++k) sum[k] += g[k];
    }
    int squarings = 0;
    sh::expHybrid(sum, &squarings);
    ASSERT_GT(squarings, 0);
  }
  for (int order : {3, 4})
    for (int probeOrder : {2, 3}) {
      const gi::probes::ProbeVolume vol = volume(probeOrder);
      int shadowed = 0;
      const double worst = expectMatches(f, vol, r, runShader(ctx, f, vol, r, order), order, &shadowed);
      EXPECT_GT(shadowed, int(r.size()) / 4);  // the fixture shadows a good share of the receivers
      std::printf("order %d, probes order %d: worst |GPU - C++| / |E_u| = %.3g; %d of %zu receivers shadowed by > 1%%\n",
                  order, probeOrder, worst, shadowed, r.size());
    }
}

// Through the GPU path, a uniform probe volume and one sphere (radius 0.2 m at heights 0.25–1.6 m,
// angles β up to 0.9 rad from the normal): E_s/E_u = 1 − sin²θ cos β, the closed form, within float
// rounding (the Ratio form is exact there).
TEST(SlProbeShadowGpu, OneSphereDarkensAReceiverByTheCapsClosedForm) {
  constexpr double kFloatTol = 2e-4;  // of E_u: fp32 trigonometry and table interpolation
  gpu::Context& ctx = gpu::testkit::sharedContext();
  gi::probes::ProbeVolume vol = volume(3);
  for (std::size_t i = 0; i < vol.sh.size(); ++i) vol.sh[i] = i % 9 == 0 ? glm::vec3(2.0f * 3.5449077f) : glm::vec3(0.0f);
  Fixture f;
  addSphere(f, {0.0f, 0.0f, 0.0f}, 0.2f, 0);
  std::vector<Receiver> r;
  std::vector<double> want;
  for (float d : {0.25f, 0.4f, 0.8f, 1.6f})
    for (float beta : {0.0f, 0.4f, 0.9f}) {
      const double theta = std::asin(0.2 / d);
      if (beta + theta >= 0.5 * math::kPi) continue;
      // The receiver sits at −d·(sin β, 0, cos β) from the sphere with normal +Z.
      r.push_back(receiver({-d * std::sin(beta), 0.0f, -d * std::cos(beta)}, {0, 0, 1}));
      want.push_back(-std::sin(theta) * std::sin(theta) * std::cos(beta));
    }
  for (int order : {3, 4}) {
    const std::vector<Output> out = runShader(ctx, f, vol, r, order);
    double worst = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      EXPECT_NEAR(out[i].unshadowed.x, 2.0 * math::kPi, 1e-4);
      const double got = out[i].delta.x / out[i].unshadowed.x;
      worst = std::max(worst, std::abs(got - want[i]));
      EXPECT_NEAR(got, want[i], kFloatTol) << "order " << order << " receiver " << i;
    }
    std::printf("order %d: one sphere's darkening on the GPU, worst |ΔE/E_u − closed form| = %.2e\n", order, worst);
  }
}

// "blocked_light": "sphere" (probe_shadow.hpp BlockedLight::Sphere) in GLSL against the C++ reference:
// the first test's two overlapping objects (union shares, shadow scales) over a plane, each SL with its
// own radiance SH (a lobe towards a different direction per SL, non-negative), so the blocked light
// differs from the receiver's; at SH orders 3 and 4.
TEST(SlProbeShadowGpu, GlslEqualsProbeShadowWithTheBlockedLightReadAtTheSpheres) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  Fixture f;
  addTwoObjects(f);
  std::vector<gi::incident::RadianceSH> sphereL;
  for (std::size_t i = 0; i < f.shaded.size(); ++i) {
    const glm::vec3 d = glm::vec3(math::fibonacciSphere(int(i), int(f.shaded.size())));
    const auto y = sh::evalBasis<float>(3, d);
    gi::incident::RadianceSH sh{};
    for (int k = 0; k < 9; ++k) {
      const float band = k == 0 ? 0.0f : (k < 4 ? 1.4f : 0.5f);  // a wide lobe towards d on a constant
      sh[std::size_t(k)] = glm::vec3(1.0f + 0.3f * float(i), 0.8f, 0.5f) * band * y[std::size_t(k)];
    }
    sh[0] = glm::vec3(1.0f + 0.3f * float(i), 0.8f, 0.5f) * 3.5449077f * 1.5f;
    sphereL.push_back(sh);
  }
  std::vector<Receiver> r = floorGrid();
  for (int order : {3, 4}) {
    const gi::probes::ProbeVolume vol = volume(3);
    int shadowed = 0;
    const double worst = expectMatches(f, vol, r, runShader(ctx, f, vol, r, order, sphereL), order, &shadowed, sphereL);
    EXPECT_GT(shadowed, int(r.size()) / 4);
    std::printf("blocked light at the spheres, order %d: worst |GPU - C++| / |E_u| = %.3g; %d of %zu receivers shadowed by > 1%%\n",
                order, worst, shadowed, r.size());
  }
}

// "blocked_read": "map" (probe_shadow.hpp BlockedRead::Map) in GLSL against the C++ reference: the
// same objects and receivers, each SL with a direction map whose neighbouring texels differ by up to
// 2× (a pattern over the texel index, brighter per SL), so a read from the wrong texel, the wrong SL
// or the wrong channel fails; the shader and the reference pick the texel with the same function
// (common/oct_map.glsl, math::octTexel). At SH orders 3 and 4 (the visibility's order).
TEST(SlProbeShadowGpu, GlslEqualsProbeShadowWithTheBlockedLightReadFromDirectionMaps) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  Fixture f;
  addTwoObjects(f);
  std::vector<gi::incident::DirectionMap> maps(f.shaded.size());
  for (std::size_t i = 0; i < maps.size(); ++i)
    for (int t = 0; t < math::kOctMapTexels; ++t) {
      const float wave = 0.75f + 0.25f * std::sin(0.9f * float(t) + float(i));
      maps[i][std::size_t(t)] = glm::vec3(1.0f + 0.3f * float(i), 0.8f, 0.5f) * wave * (t % 3 == 0 ? 1.0f : 0.6f);
    }
  std::vector<Receiver> r = floorGrid();
  for (int order : {3, 4}) {
    const gi::probes::ProbeVolume vol = volume(3);
    int shadowed = 0;
    const double worst = expectMatches(f, vol, r, runShader(ctx, f, vol, r, order, {}, maps), order, &shadowed, {}, maps);
    EXPECT_GT(shadowed, int(r.size()) / 4);
    std::printf("blocked light from direction maps, order %d: worst |GPU - C++| / |E_u| = %.3g; %d of %zu receivers shadowed by > 1%%\n",
                order, worst, shadowed, r.size());
  }
}

// The SlIndirect block is sized per "blocked_read" (shade.hpp indirectBlockBytes; sl_data.glsl sizes
// its array by the same rule from kBlockedMap and kSpheres): the SH layout 8 KiB (128 SLs · 16 words)
// whatever the SL count, the maps 1 KiB (256 RGB9E5 words) per SL rounded up to 8 SLs as pass 2's
// kSpheres. The buffer and the descriptor range are that size; lavapipe's maxUniformBufferRange
// holds the largest map block (64 SLs), Vulkan's guaranteed 16 KiB holds 16 SLs' maps.
TEST(SlProbeShadowGpu, IndirectBlockIsSizedPerBlockedRead) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  struct Case {
    std::uint32_t mapped;
    std::size_t bytes;
  };
  for (const Case c : {Case{0, 8192}, Case{1, 8192}, Case{8, 8192}, Case{12, 16384}, Case{32, 32768}, Case{64, 65536}}) {
    EXPECT_EQ(indirectBlockBytes(c.mapped), c.bytes) << c.mapped << " mapped SLs";
    ShadeData data(ctx, 4, c.mapped);
    EXPECT_EQ(data.indirectBytes(), c.bytes) << c.mapped << " mapped SLs";
  }
  // The characters level ships 2 × 16 SLs with the maps: 32 KiB, within this device's range.
  EXPECT_GE(ctx.limits().maxUniformBufferRange, indirectBlockBytes(32));
  // SH layout: setSpheres writes the block without reading past it (128 SLs, the pass's limit).
  ShadeData sh(ctx, 4);
  std::vector<ShadedSphere> spheres(kMaxShadedSpheres);
  std::vector<gi::incident::RadianceSH> indirect(kMaxShadedSpheres);
  sh.setSpheres(spheres, {}, indirect);
  EXPECT_EQ(sh.indirectBytes(), std::size_t(kMaxShadedSpheres) * kIndirectWordsPerSl * 4);
  // More maps than the block was made for is an internal error, not a write past it.
  ShadeData mapped(ctx, 4, 8);
  std::vector<gi::incident::DirectionMap> maps(9);
  EXPECT_THROW(mapped.setSpheres(std::span(spheres).first(9), {}, std::span(indirect).first(9), maps), InternalError);
}
