#include "engine/gi/probes/node.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.hpp"
#include "engine/math/sh.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::gi::probes {
namespace glsl {
using namespace glm;
#include "shaders/probes/probe_tiles.glsl"
}  // namespace glsl
namespace {

constexpr int kProbeTile = glsl::PROBE_TILE;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;  // "gbuffer.depth" (gbuffer_pass.cpp)
// The depth's layout in a split pass (FusedDnrt::split): tested as a read-only attachment and sampled.
constexpr VkImageLayout kDepthReadOnly = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
// tiles.comp's workgroup: PROBE_TILE × PROBE_TILE/2 invocations writing two rows each, within the
// 128 every Vulkan device allows (maxComputeWorkGroupInvocations' required minimum).
static_assert(kProbeTile % 2 == 0 && kProbeTile * (kProbeTile / 2) <= 128, "tiles.comp's workgroup");

// Probe p = x + count.x·row of the volume in texel row `row`, `slots` texels per probe in that row
// (probes.frag probeTexel). Throws when the layout exceeds the device's 2D image size.
gpu::ImageDesc probeImageDesc(gpu::Context& ctx, const ProbeGrid& g, std::uint32_t slots, VkFormat format,
                              const char* name) {
  gpu::ImageDesc d;
  d.format = format;
  d.width = slots * std::uint32_t(g.count.x);
  d.height = std::uint32_t(g.count.y) * std::uint32_t(g.count.z);
  // TRANSFER_DST: the upload, and pass probes.relight's per-frame copy into the SH image;
  // TRANSFER_SRC: tests read it back.
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.name = name;
  const std::uint32_t limit = ctx.limits().maxImageDimension2D;
  if (d.width > limit || d.height > limit)
    throw InternalError(std::string("probes: ") + name + " image " + std::to_string(d.width) + "x" +
                        std::to_string(d.height) + " exceeds the device's " + std::to_string(limit) +
                        " (fewer probes per axis: a larger spacing)");
  return d;
}

// SH texels per probe: 3 floats a coefficient, then the valid flag, 4 floats a texel (probes.frag kTexels).
std::uint32_t shTexels(const ProbeVolume& v) { return std::uint32_t(3 * v.coeffs() + 4) / 4; }

// SH texels, probe-major: probe p's texel t at 4·(t + shTexels·p), packing L_0.rgb, L_1.rgb, …,
// valid, as probe_sh.glsl reads them (the row-major image layout, and the uniform block's).
std::vector<float> shTexelFloats(const ProbeVolume& v) {
  const std::size_t probes = v.grid.probeCount(), coeffs = std::size_t(v.coeffs()), stride = 4 * shTexels(v);
  std::vector<float> floats(probes * stride, 0.0f);
  for (std::size_t p = 0; p < probes; ++p) {
    float* out = floats.data() + p * stride;
    for (std::size_t i = 0; i < coeffs; ++i)
      for (int ch = 0; ch < 3; ++ch) out[3 * i + std::size_t(ch)] = v.sh[p * coeffs + i][ch];
    out[3 * coeffs] = v.valid[p] != 0 ? 1.0f : 0.0f;
  }
  return floats;
}

// The uniform block's texels per probe (probe_sh.glsl kPackedTexels): 8 words, of which order 3
// uses 8 and order 2 uses 5 (shPackedWords).
constexpr std::uint32_t kPackedTexels = 2;

// The largest finite half; a volume with a larger |value| keeps the image path.
constexpr float kHalfMax = 65504.0f;

// The block's per-probe scale s (shPackedWords): max over i ≥ 1 and channels c of |L_i.c| / |L_0.c|
// with L_0 as the shader reads it (halves); s·|L_0.c| ≥ |L_i.c| for every i, c. Rounded up to a half
// so the shader's s is never below it. NaN when some L_0.c rounds to 0 under a non-zero L_i.c.
float packedShScale(const ProbeVolume& v, std::size_t p) {
  const std::size_t coeffs = std::size_t(v.coeffs());
  const glm::vec3 l0 = glm::unpackHalf(glm::packHalf(v.sh[p * coeffs]));
  float s = 0.0f;
  for (std::size_t i = 1; i < coeffs; ++i)
    for (int c = 0; c < 3; ++c) {
      const float l = std::abs(v.sh[p * coeffs + i][c]);
      if (l == 0.0f) continue;
      if (l0[c] == 0.0f) return std::numeric_limits<float>::quiet_NaN();
      s = std::max(s, l / std::abs(l0[c]));
    }
  std::uint16_t h = glm::packHalf1x16(s);
  if (glm::unpackHalf1x16(h) < s) ++h;  // s ≥ 0: the next half up
  return glm::unpackHalf1x16(h);
}

// probe_sh.glsl's ProbeShBlock: per probe kPackedTexels texels (8 words), probe p's word j at
// 4·kPackedTexels·p + j:
//   word 0: packHalf2x16(L_0.r, L_0.g), word 1: packHalf2x16(L_0.b, s) (s: packedShScale);
//   words 2…: the 3·(coeffs − 1) fractions L_i.c / (s·L_0.c) (i ≥ 1; value 3·(i − 1) + c), as
//   packSnorm4x8 bytes (round(127·x)), 4 a word, low byte first: order 3: 6 words, order 2: 3.
// 8 words a probe at order 3 instead of 16 as halves: on llvmpipe an indexed uniform array is a
// per-lane load per scalar, and the SH loads were ~0.75 of the lighting pass (README "DNRT and
// probes cost, session 8"). The error this costs is packedShIrradianceError's.
// Then, after the last probe's texels, the valid flags as bits: probe p's is bit p % 32 of the
// first word of texel kPackedTexels·probes + p / 32 (probeValid reads that one word; reading a
// texel cost ~0.25 of the lighting pass, this ~0.1). Empty (the image path) when L_0 is past
// kHalfMax or s is not a finite half (an L_0.c of 0 under a non-zero L_i.c; a baked volume has
// none: its radiance is non-negative, so s ≤ √5, packedShIrradianceError).
std::vector<std::uint32_t> shPackedWords(const ProbeVolume& v) {
  const std::size_t probes = v.grid.probeCount(), coeffs = std::size_t(v.coeffs()), stride = 4 * kPackedTexels;
  std::vector<std::uint32_t> words(probes * stride + 4 * ((probes + 31) / 32), 0u);
  for (std::size_t p = 0; p < probes; ++p)
    if (v.valid[p] != 0) words[probes * stride + 4 * (p / 32)] |= 1u << (p % 32);
  for (std::size_t p = 0; p < probes; ++p) {
    const glm::vec3 l0 = v.sh[p * coeffs];
    const float s = packedShScale(v, p);
    if (!(glm::all(glm::lessThanEqual(glm::abs(l0), glm::vec3(kHalfMax))) && s <= kHalfMax)) return {};
    const glm::vec3 l0h = glm::unpackHalf(glm::packHalf(l0));
    std::uint32_t* out = words.data() + p * stride;
    out[0] = glm::packHalf2x16(glm::vec2(l0.x, l0.y));
    out[1] = glm::packHalf2x16(glm::vec2(l0.z, s));
    float f[24] = {};
    for (std::size_t i = 1; i < coeffs; ++i)
      for (int c = 0; c < 3; ++c) {
        const float d = s * l0h[c];
        f[3 * (i - 1) + std::size_t(c)] = d != 0.0f ? v.sh[p * coeffs + i][c] / d : 0.0f;
      }
    for (std::size_t w = 0; 4 * w < 3 * (coeffs - 1); ++w)
      out[2 + w] = glm::packSnorm4x8(glm::vec4(f[4 * w], f[4 * w + 1], f[4 * w + 2], f[4 * w + 3]));
  }
  return words;
}

// probe_sh.glsl's ProbeMomentsBlock: bin b of probe p at word kVisBins·p + b, packHalf2x16 of
// (mean, σ) with σ = sqrt(max(mean square − mean², 0)) (m). Empty when a value is past kHalfMax.
std::vector<std::uint32_t> momentHalfWords(const ProbeVolume& v) {
  std::vector<std::uint32_t> words(v.moments.size(), 0u);
  for (std::size_t i = 0; i < v.moments.size(); ++i) {
    const double mean = v.moments[i].x, variance = double(v.moments[i].y) - mean * mean;
    const float sigma = float(std::sqrt(std::max(variance, 0.0)));
    if (!(std::abs(v.moments[i].x) <= kHalfMax && sigma <= kHalfMax)) return {};
    words[i] = glm::packHalf2x16(glm::vec2(v.moments[i].x, sigma));
  }
  return words;
}

// The irradiance tiles' image (probe_tiles.glsl probeTileOrigin): a PROBE_TILE² square a probe, in
// the probe images' row layout.
glm::uvec2 tileImageSize(const ProbeGrid& g) {
  return {std::uint32_t(kProbeTile) * std::uint32_t(g.count.x),
          std::uint32_t(kProbeTile) * std::uint32_t(g.count.y) * std::uint32_t(g.count.z)};
}

// probes.frag's ProbeShBlock: 4096 uvec4 = 64 KiB, lavapipe's maxUniformBufferRange (the Vulkan
// minimum is 16 KiB; a device below 64 KiB keeps the image path). 2 texels a probe at either order
// plus a texel per 32 probes' valid bits: 2016 probes (4032 + 63 texels; a 0.125 m grid over
// cornell-1, 9³ = 729, fits).
constexpr VkDeviceSize kShUboBytes = 4096 * 16;
// probes.frag's ProbeMomentsBlock, the same 64 KiB: 256 B a probe, so up to 256 probes (cornell-1's
// 0.25 m volume, 6³ = 216, fits; the 0.125 m one, 9³, keeps the image).
constexpr VkDeviceSize kMomentsUboBytes = 4096 * 16;
// probes.frag's DnrtObjects block: kDnrtClusterBatch (32) DnrtClusterObject records of 240 bytes (std140;
// gi/dnrt/gpu_object.hpp, which this module does not include: DNRT builds on the probes, not back).
constexpr VkDeviceSize kDnrtObjectsBytes = 32 * 240;

}  // namespace

// The bound on |E_block(n) − E_image(n)| per channel that shPackedWords' 8-bit fractions add (the
// L_0 halves round as before, 2⁻¹¹ relative). Each fraction rounds to the nearest of 255 steps of
// s·|L_0.c|/127, so |δL_i.c| ≤ ½·s·|L_0.c|/127. E(n) = Σ_l Â_l Σ_m L_lm Y_lm(n) (sh.glsl
// shIrradiance9; Ramamoorthi & Hanrahan 2001, Â_1 = 2π/3, Â_2 = π/4), and by Cauchy–Schwarz with the
// addition theorem (Σ_m Y_lm(n)² = (2l+1)/4π) Σ_m |Y_lm(n)| ≤ (2l+1)/√(4π), so
//   |δE_c| ≤ ½·s·|L_0.c|/127 · (3·Â_1 + 5·Â_2)/√(4π) = ½·s·|L_0.c|/127 · 1.625·√π  (order 3; order
//   2: the l = 1 term alone, √π).
// The pass mixes 8 probes with weights summing to 1, so the largest probe's bound bounds the pixel's
// E; the pixel gets ρ/π·ao of it (ρ, ao ≤ 1). For a baked volume (radiance ≥ 0, windowed bands
// scaled by ≤ 1) |L_lm| ≤ max|Y_lm|/Y_00 · L_00, i.e. s ≤ √5 (l = 2: Y_20's 0.6308 / 0.2821), so
// |δE_c| ≤ 0.0286 of band 0's π·Y_00·L_0.c at worst. On cornell-1 (0.25 m, order 3) the bound is
// 1.4 % of the probes image's largest value and the largest change measured 0.05 of the bound
// (test ProbeGpu.ShFromTheUniformBlockIsTheImagePathWithinItsRounding).
double packedShIrradianceError(const ProbeVolume& v) {
  const std::size_t coeffs = std::size_t(v.coeffs());
  const double k = 0.5 / 127.0 * (v.order == 3 ? 1.625 : 1.0) * std::sqrt(3.14159265358979323846);
  double worst = 0.0;
  for (std::size_t p = 0; p < v.grid.probeCount(); ++p) {
    if (v.valid[p] == 0) continue;
    const glm::vec3 l0 = glm::unpackHalf(glm::packHalf(v.sh[p * coeffs]));
    const double s = packedShScale(v, p);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, k * s * std::abs(double(l0[c])));
  }
  return worst;
}

std::vector<std::uint32_t> packedShWords(const ProbeVolume& v) { return shPackedWords(v); }

// The tiles' interpolation error (probe_tiles.glsl): E(n) is a polynomial of degree ≤ 2 in n
// (order 3), smooth, but the octahedral map bends it, so rather than a loose derivative bound this
// measures it: for each valid probe, its tile's texel values E(dir(t)) bilinearly interpolated at
// probeTileCoord(n) (what the sampler does; llvmpipe filters RGBA16F with float weights) against
// E(n), at 129² normals spread over the octahedral square (a 128-step lattice with both edges:
// texel centres, edges and the points between, 9 per texel) — the largest |difference| per channel (W/m²). The pass mixes ≤ 8 probes with
// weights summing to 1, so this bounds a pixel's E too (plus the texels' fp16 rounding).
double tileIrradianceError(const ProbeVolume& v) {
  const std::size_t coeffs = std::size_t(v.coeffs());
  constexpr int kTile = glsl::PROBE_TILE, kSamples = 128;
  double worst = 0.0;
  std::vector<glm::vec3> tile(std::size_t(kTile * kTile));
  for (std::size_t p = 0; p < v.grid.probeCount(); ++p) {
    if (v.valid[p] == 0) continue;
    const std::span<const glm::vec3> L(&v.sh[p * coeffs], coeffs);
    for (int y = 0; y < kTile; ++y)
      for (int x = 0; x < kTile; ++x)
        tile[std::size_t(y * kTile + x)] =
            sh::evalIrradiance<glm::vec3, float>(L, glsl::probeTileDirection(glm::ivec2(x, y)));
    for (int j = 0; j <= kSamples; ++j)
      for (int i = 0; i <= kSamples; ++i) {
        const glm::vec3 n = glsl::probeOctDecode(glm::vec2(float(i), float(j)) * (2.0f / kSamples) - 1.0f);
        const glm::vec2 c = glsl::probeTileCoord(n) - 0.5f;  // texel centres at integers
        const glm::ivec2 c0 = glm::clamp(glm::ivec2(glm::floor(c)), glm::ivec2(0), glm::ivec2(kTile - 2));
        const glm::vec2 f = c - glm::vec2(c0);
        const auto at = [&](int dx, int dy) { return tile[std::size_t((c0.y + dy) * kTile + c0.x + dx)]; };
        const glm::vec3 got = glm::mix(glm::mix(at(0, 0), at(1, 0), f.x), glm::mix(at(0, 1), at(1, 1), f.x), f.y);
        const glm::vec3 want = sh::evalIrradiance<glm::vec3, float>(L, n);
        for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::abs(double(got[ch]) - double(want[ch])));
      }
  }
  return worst;
}

// SH texels (t + shTexels·x, row).
std::unique_ptr<gpu::Image> uploadSh(gpu::Context& ctx, const ProbeVolume& v) {
  auto image = std::make_unique<gpu::Image>(ctx, probeImageDesc(ctx, v.grid, shTexels(v), VK_FORMAT_R32G32B32A32_SFLOAT, "probes.sh"));
  const std::vector<float> floats = shTexelFloats(v);
  gpu::upload(ctx, *image, {reinterpret_cast<const std::uint8_t*>(floats.data()), floats.size() * sizeof(float)});
  return image;
}

// Moments texels (bin + kVisBins·x, row) = (mean, mean square).
std::unique_ptr<gpu::Image> uploadMoments(gpu::Context& ctx, const ProbeVolume& v) {
  auto image = std::make_unique<gpu::Image>(
      ctx, probeImageDesc(ctx, v.grid, std::uint32_t(kVisBins), VK_FORMAT_R32G32_SFLOAT, "probes.moments"));
  static_assert(sizeof(glm::vec2) == 8, "RG32F texels");
  gpu::upload(ctx, *image, {reinterpret_cast<const std::uint8_t*>(v.moments.data()), v.moments.size() * sizeof(glm::vec2)});
  return image;
}

ProbePush probePush(const ProbeVolume& v, float flag) {
  const ProbeGrid& g = v.grid;
  return {glm::vec4(g.origin, g.spacing), glm::ivec4(g.count, v.order),
          glm::vec4(g.spacing * v.bias.normal, g.spacing * v.bias.view, v.minVariance(), flag)};
}

ProbeNode::ProbeNode(gpu::Context& ctx, const render::Pipelines& pipelines, ProbeVolume volume, bool shInUbo,
                     bool tiles)
    : volume_(std::move(volume)),
      sh_(uploadSh(ctx, volume_)),
      moments_(uploadMoments(ctx, volume_)),
      setLayout_(ctx,
                 {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {5, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                  {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {7, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                  {8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {11, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                  {12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}},
                 "probes") {
  {
    const std::vector<std::uint32_t> words = shPackedWords(volume_);
    const VkDeviceSize bytes = words.size() * sizeof(std::uint32_t);
    shInUbo_ = shInUbo && !words.empty() && bytes <= kShUboBytes && kShUboBytes <= ctx.limits().maxUniformBufferRange;
    // STORAGE: pass `probes.relight` writes it (relight_pass.hpp); TRANSFER_SRC: tests read it back.
    shUbo_ = gpu::Buffer(ctx, {kShUboBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               gpu::MemoryUsage::GpuOnly, "probes.sh.ubo"});
    if (shInUbo_) gpu::upload(ctx, shUbo_, {reinterpret_cast<const std::uint8_t*>(words.data()), std::size_t(bytes)});
  }
  {
    const std::vector<std::uint32_t> words = momentHalfWords(volume_);
    const VkDeviceSize bytes = words.size() * sizeof(std::uint32_t);
    momentsInUbo_ = shInUbo_ && !words.empty() && bytes <= kMomentsUboBytes &&
                    kMomentsUboBytes <= ctx.limits().maxUniformBufferRange;
    momentsUbo_ = gpu::Buffer(ctx, {kMomentsUboBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    gpu::MemoryUsage::GpuOnly, "probes.moments.ubo"});
    if (momentsInUbo_)
      gpu::upload(ctx, momentsUbo_, {reinterpret_cast<const std::uint8_t*>(words.data()), std::size_t(bytes)});
  }
  {
    // The tiles read the SH from the block only (tiles.comp), and their image must fit a 2D image.
    const glm::uvec2 size = tileImageSize(volume_.grid);
    const std::uint32_t limit = ctx.limits().maxImageDimension2D;
    tiles_ = tiles && shInUbo_ && size.x <= limit && size.y <= limit;
    if (tiles_) {
      tilesSetLayout_ = gpu::DescriptorSetLayout(ctx,
                                                 {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                  {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                                  {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                                                  {3, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                                                  {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                                 "probes.tiles");
      tilesLayout_ = gpu::PipelineLayout(ctx, {tilesSetLayout_}, {{VK_SHADER_STAGE_ALL, 0, sizeof(ProbePush)}},
                                         "probes.tiles");
      gpu::ShaderModule comp(ctx, "probes/tiles.comp.spv");
      tilesPipeline_ = gpu::createComputePipeline(ctx, tilesLayout_, comp, "probes.tiles", nullptr,
                                                  {std::uint32_t(volume_.coeffs())});  // tiles.comp kCoeffs
      buildBakedTiles(ctx);
    }
  }
  layout_ = gpu::PipelineLayout(ctx, {pipelines.frameLayout, setLayout_},
                                {{VK_SHADER_STAGE_ALL, 0, sizeof(ProbePush) + sizeof(FusedDnrtPush)}}, "probes");
  {
    // Binding 9 when no fused DNRT object reads it (probes.frag kDnrt false): one zero texel.
    gpu::ImageDesc d;
    d.type = gpu::ImageType::Tex3D;
    d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    d.width = d.height = d.depth = 1;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    d.name = "probes.no-dnrt";
    noDnrt_ = std::make_unique<gpu::Image>(ctx, d);
    const std::uint8_t zero[8] = {};
    gpu::upload(ctx, *noDnrt_, zero);
    // Bindings 10 and 11 without several fused objects (kDnrt 2 reads them): a zero mask, and zero
    // records as long as the block probes.frag declares (DnrtClusterObject[32], std140).
    noDnrtTiles_ = gpu::Buffer(ctx, {4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "probes.no-dnrt-tiles"});
    noDnrtObjects_ = gpu::Buffer(ctx, {kDnrtObjectsBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload,
                                       "probes.no-dnrt-objects"});
    std::memset(noDnrtTiles_.mapped(), 0, 4);
    std::memset(noDnrtObjects_.mapped(), 0, kDnrtObjectsBytes);
  }
  gpu::ShaderModule vert(ctx, "passes/fullscreen.vert.spv");
  gpu::ShaderModule frag(ctx, "probes/probes.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {render::kLightingHdrFormat};  // "lighting.hdr"
  d.blend = gpu::Blend::Additive;
  specialization_ = {std::uint32_t(volume_.coeffs()), shInUbo_ ? 1u : 0u, momentsInUbo_ ? 1u : 0u,
                     tiles_ ? 1u : 0u};  // probes.frag kCoeffs, kShInUbo, kMomentsInUbo, kTiles
  d.specialization = specialization_;
  d.name = "probes";
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
}

// The baked volume's tiles, once: tiles.comp over the uploaded block into a persistent image the
// probes pass reads every frame while nothing relights the volume (addPasses), instead of
// recomputing the same texels each frame (1.3–1.5 ms on llvmpipe, README "Probes cost, session 11").
void ProbeNode::buildBakedTiles(gpu::Context& ctx) {
  const glm::uvec2 size = tileImageSize(volume_.grid);
  gpu::ImageDesc d;
  d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  d.width = size.x;
  d.height = size.y;
  // STORAGE: tiles.comp writes it; SAMPLED: probes.frag taps it; TRANSFER_SRC: tests read it back.
  d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.name = "probes.tiles.baked";
  bakedTiles_ = std::make_unique<gpu::Image>(ctx, d);
  gpu::DescriptorAllocator descriptors(ctx, "probes.tiles.baked");
  gpu::SamplerCache samplers(ctx);
  VkSampler point = samplers.get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  VkDescriptorSet set = descriptors.allocate(tilesSetLayout_);
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    gpu::transition(cmd, *bakedTiles_, VK_IMAGE_LAYOUT_GENERAL);
    gpu::DescriptorWriter()
        .sampledImage(0, sh_->view(), point)
        .sampledImage(1, moments_->view(), point)
        .buffer(2, shUbo_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kShUboBytes)
        .buffer(3, momentsUbo_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kMomentsUboBytes)
        .storageImage(4, bakedTiles_->view())
        .update(ctx, set);
    tilesPipeline_.bind(cmd);
    tilesPipeline_.bindSet(cmd, 0, set);
    tilesPipeline_.push(cmd, probePush(volume_, 0.0f));
    vkCmdDispatch(cmd, std::uint32_t(volume_.grid.count.x), std::uint32_t(volume_.grid.count.y * volume_.grid.count.z), 1);
    gpu::transition(cmd, *bakedTiles_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  });
}

void ProbeNode::enableRelight(gpu::Context& ctx, RelightData data, const ref::SceneBvh& staticScene) {
  // The block when the pass reads it, and the image on the frames it is read (the pass's source past
  // 2016 probes, and the SL shadow's on the probes' light: addRelightPass).
  relight_ = std::make_unique<RelightPass>(ctx, volume_, std::move(data), shUbo_, sh_.get(), shInUbo_);
  relightScene_ = &staticScene;
  relightBaked_ = volume_.sh;
}

// The probes pass's commands (addPasses): probes.frag over every G-buffer pixel into d.hdr, with the fused
// DNRT term when `fused` is set; `baseline`: pass probes.baseline (setTermBaseline), which leaves
// lastPassSplit_ alone.
void ProbeNode::recordPass(const PassData& d, const rg::PassResources& res, rg::CommandContext& c,
                           const render::PassContext* pc, bool withAo, const std::optional<FusedDnrt>& fused,
                           bool baseline) {
  VkCommandBuffer cmd = pc->cmd(c);
  VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
  VkDescriptorSet set = pc->frame().descriptors->allocate(setLayout_);
  const bool split = fused && fused->split;
  gpu::DescriptorWriter writer;
  render::writeDeferredInputs(writer, d.g, *pc, res, point,
                              split ? kDepthReadOnly : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      .sampledImage(3, sh_->view(), point)
      .sampledImage(4, moments_->view(), point)
      .buffer(5, shUbo_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kShUboBytes)
      .buffer(7, momentsUbo_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kMomentsUboBytes)
      .sampledImage(6, view(withAo ? d.ao : d.g.albedo), point)
      // bilinear: one tap a probe (probe_tiles.glsl); without tiles the shader ignores it
      .sampledImage(8, tiles_ ? view(d.tiles) : sh_->view(),
                    tiles_ ? pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST}) : point)
      // trilinear, as the "dnrt" pass's box draw reads the same volume
      .sampledImage(9, fused ? view(d.dnrt) : noDnrt_->view(),
                    pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST}))
      // the fused term's reduced factor below full resolution, read by texelFetch (probes.frag
      // dnrtReducedQuadTap); the albedo when unread (kDnrtStep 1)
      .sampledImage(12, view(fused && fused->reduced ? d.dnrtReduced : d.g.albedo), point);
  const bool several = fused && fused->bindCluster;
  if (several)
    fused->bindCluster(writer, *pc);
  else
    writer.buffer(10, noDnrtTiles_).buffer(11, noDnrtObjects_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  writer.update(*pc->gpu, set);
  gpu::Image& target = pc->backend->image(res.texture(d.hdr));
  // Additive: keep the direct light. probes.baseline's fresh scratch target has nothing to keep (the graph
  // grants it no read), so it clears: its time leaves out the load of the target, which puts that load on
  // the term's marginal — the bench's figure errs high, never low.
  render::Attachment color{target.view(), res.keepsContents(d.hdr)};
  if (termBaseline_) {
    // Timed against each other (setTermBaseline): neither pass may start before the work ahead of it ends,
    // or on a GPU that overlaps passes its scope would hold only its tail. lavapipe runs them in order anyway.
    const VkMemoryBarrier none{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, 0, 0};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &none, 0,
                         nullptr, 0, nullptr);
  }
  const VkExtent2D extent{target.desc().width, target.desc().height};
  render::Attachment depth{view(d.g.depth)};
  depth.readOnly = true;
  render::beginRendering(*pc->gpu, cmd, extent, {&color, 1}, split ? &depth : nullptr);
  const std::size_t stepIndex = !fused || fused->step == 1u ? 0u : fused->step == 2u ? 1u : 2u;
  if (fused && fused->step != 1u && fused->step != 2u && fused->step != 4u)
    throw InternalError("probes: fused DNRT step " + std::to_string(fused->step) + " (expected 1, 2 or 4)");
  // probes.frag with kDnrt `dnrt` at kDnrtStep `step`; split: drawn as the outer cube (outer_cube.vert)
  // against the depth, `compare` deciding which pixels it shades (FusedDnrt::split).
  const auto make = [&](std::uint32_t dnrt, std::uint32_t step, bool splitDraw, VkCompareOp compare,
                        std::string name) {
    gpu::ShaderModule vert(*pc->gpu, splitDraw ? "probes/outer_cube.vert.spv" : "passes/fullscreen.vert.spv");
    gpu::ShaderModule frag(*pc->gpu, "probes/probes.frag.spv");
    gpu::GraphicsPipelineDesc pd;
    pd.vertex = &vert;
    pd.fragment = &frag;
    pd.colorFormats = {render::kLightingHdrFormat};  // "lighting.hdr"
    pd.blend = gpu::Blend::Additive;
    if (splitDraw) {
      pd.depthFormat = kDepthFormat;
      pd.depthTest = true;
      pd.depthCompare = compare;
    }
    pd.specialization = specialization_;
    pd.specialization.push_back(dnrt);  // kDnrt
    pd.specialization.push_back(step);  // kDnrtStep
    pd.name = std::move(name);
    return gpu::createGraphicsPipeline(*pc->gpu, layout_, pd);
  };
  const std::string stepName = fused && fused->step > 1u ? ".step" + std::to_string(fused->step) : "";
  gpu::Pipeline& fusedPipeline =
      split ? splitFusedPipelines_[stepIndex] : fusedPipelines_[several ? 3u : stepIndex];
  if (fused && fusedPipeline.handle() == VK_NULL_HANDLE)
    fusedPipeline = several ? make(2u, 1u, false, VK_COMPARE_OP_ALWAYS, "probes.fused-dnrt.cluster")
                    : split ? make(1u, fused->step, true, VK_COMPARE_OP_GREATER_OR_EQUAL,
                                   "probes.fused-dnrt.inside" + stepName)
                            : make(1u, fused->step, false, VK_COMPARE_OP_ALWAYS, "probes.fused-dnrt" + stepName);
  if (split && splitPlainPipeline_.handle() == VK_NULL_HANDLE)
    splitPlainPipeline_ = make(0u, 1u, true, VK_COMPARE_OP_LESS, "probes.outside");
  struct {
    ProbePush probes;
    FusedDnrtPush dnrt;
  } push{probePush(volume_, withAo ? 1.0f : 0.0f), fused ? fused->push : FusedDnrtPush{}};
  const auto draw = [&](const gpu::Pipeline& p, std::uint32_t vertices) {
    p.bind(cmd);
    p.bindSet(cmd, 0, pc->frameSet);
    p.bindSet(cmd, 1, set);
    p.push(cmd, push);
    vkCmdDraw(cmd, vertices, 1, 0, 0);
  };
  if (split) {
    // The cube's 36 vertices (outer_cube.vert) twice: the term where the surface is not behind the face the
    // pixel's ray leaves the cube through, then the probes alone where it is. Every pixel once.
    draw(fusedPipeline, 36);
    draw(splitPlainPipeline_, 36);
  } else {
    draw(fused ? fusedPipeline : pipeline_, 3);
  }
  if (!baseline) lastPassSplit_ = split;
  pc->gpu->cmdEndRendering(cmd);
}

void ProbeNode::addPasses(rg::RenderGraph& graph, const render::PassContext* pc) {
  std::optional<rg::Handle<rg::Buffer>> block;  // probes.relight's output, read below: culled with them
  if (relight_) block = addRelightPass(graph, pc);
  auto& bb = graph.blackboard();
  // This frame's irradiance tiles (tiles.comp), after probes.relight rewrote the block (its final
  // barrier makes the block visible to compute reads). A graph texture read only by the probes
  // pass, so it is culled with it.
  struct TilesData {
    rg::Handle<rg::Texture> tiles;
  };
  std::optional<rg::Handle<rg::Texture>> tiles;
  if (tiles_ && !relight_) {
    // Nothing changes the block: the tiles built once (buildBakedTiles), already in
    // SHADER_READ_ONLY with their writes waited for; no probes.tiles pass.
    const glm::uvec2 size = tileImageSize(volume_.grid);
    rg::ResourceState built;
    built.layout = rg::Layout::ShaderReadOnly;
    // graphDot builds the graph without a device: any id names the import there (relight_pass.cpp
    // kGraphDotBlock, the AO node's 1000, Renderer::graphDot's 1–3).
    constexpr rg::PhysicalId kGraphDotTiles = 1002;
    const rg::PhysicalId physical = pc->backend ? pc->backend->importImage(*bakedTiles_) : kGraphDotTiles;
    tiles = graph.importTexture("probes.tiles.baked",
                                rg::TextureDesc{size.x, size.y, 1, 1, 1, rg::Format::RGBA16F, false}, built, physical);
  } else if (tiles_) {
    const glm::uvec2 size = tileImageSize(volume_.grid);
    tiles = graph
                .addPass<TilesData>(
                    "probes.tiles",
                    [&](rg::Builder& b, TilesData& d) {
                      d.tiles = b.write(b.create<rg::Texture>("probes.tiles",
                                                              rg::TextureDesc{size.x, size.y, 1, 1, 1,
                                                                              rg::Format::RGBA16F, false}),
                                        rg::Usage::StorageWrite);
                      if (block) b.read(*block, rg::Usage::UniformBuffer);
                    },
                    [this, pc](const TilesData& d, const rg::PassResources& res, rg::CommandContext& c) {
                      VkCommandBuffer cmd = pc->cmd(c);
                      VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
                      VkDescriptorSet set = pc->frame().descriptors->allocate(tilesSetLayout_);
                      gpu::DescriptorWriter()
                          .sampledImage(0, sh_->view(), point)
                          .sampledImage(1, moments_->view(), point)
                          .buffer(2, shUbo_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kShUboBytes)
                          .buffer(3, momentsUbo_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kMomentsUboBytes)
                          .storageImage(4, pc->backend->image(res.texture(d.tiles)).view())
                          .update(*pc->gpu, set);
                      tilesPipeline_.bind(cmd);
                      tilesPipeline_.bindSet(cmd, 0, set);
                      tilesPipeline_.push(cmd, probePush(volume_, 0.0f));
                      vkCmdDispatch(cmd, std::uint32_t(volume_.grid.count.x),
                                    std::uint32_t(volume_.grid.count.y * volume_.grid.count.z), 1);
                    })
                .tiles;
  }
  // An AO node (ssao/hbao) set before this one publishes "ao.term": the indirect term is then
  // multiplied by it, the way the DNRT paper's baselines use AO (§6.4). Without one, binding 6
  // repeats the albedo and the shader ignores it.
  const bool withAo = bb.contains("ao.term");
  // DNRT's fused mode: its combine pass first, then this pass adds the object's term (probes.frag kDnrt).
  std::optional<FusedDnrt> fused;
  if (fusedDnrt_) fused = fusedDnrt_(graph, *pc);
  // setTermBaseline: the same pass without the term into a scratch target, before the probes pass on even
  // frames and after it on odd ones, so that which of the two finds the G-buffer in the caches evens out.
  const bool withBaseline = termBaseline_ && fused;
  const bool baselineFirst = withBaseline && baselineFrames_++ % 2 == 0;
  const auto addBaseline = [&] {
    graph.addPass<PassData>(
        "probes.baseline",
        [&](rg::Builder& b, PassData& d) {
          d.g = render::readDeferredInputs(b, bb);
          const rg::TextureDesc hdr = b.desc(bb.get<rg::Texture>("lighting.hdr"));
          d.hdr = b.write(b.create<rg::Texture>("probes.baseline", hdr), rg::Usage::ColorAttachment);
          if (withAo) d.ao = b.read(bb.get<rg::Texture>("ao.term"), rg::Usage::SampledFragment);
          if (tiles) d.tiles = b.read(*tiles, rg::Usage::SampledFragment);
          if (block) b.read(*block, rg::Usage::UniformBuffer);
          b.sideEffect();  // nothing reads its target: it exists to be timed
        },
        [this, pc, withAo](const PassData& d, const rg::PassResources& res, rg::CommandContext& c) {
          recordPass(d, res, c, pc, withAo, std::nullopt, true);
        });
  };
  if (baselineFirst) addBaseline();
  const auto& data = graph.addPass<PassData>(
      "probes",
      [&](rg::Builder& b, PassData& d) {
        d.g = render::readDeferredInputs(b, bb);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        if (withAo) d.ao = b.read(bb.get<rg::Texture>("ao.term"), rg::Usage::SampledFragment);
        if (tiles) d.tiles = b.read(*tiles, rg::Usage::SampledFragment);
        if (block) b.read(*block, rg::Usage::UniformBuffer);  // bound either way (with tiles unread)
        if (fused) d.dnrt = b.read(fused->volume, rg::Usage::SampledFragment);
        if (fused && fused->reduced) d.dnrtReduced = b.read(*fused->reduced, rg::Usage::SampledFragment);
        // FusedDnrt::split: the cube's faces are depth-tested against it (read-only, also sampled)
        if (fused && fused->split) b.read(d.g.depth, rg::Usage::DepthRead);
      },
      [this, pc, withAo, fused](const PassData& d, const rg::PassResources& res, rg::CommandContext& c) {
        recordPass(d, res, c, pc, withAo, fused, false);
      });
  bb.put("lighting.hdr", data.hdr);
  if (withBaseline && !baselineFirst) addBaseline();
}

}  // namespace bounce::gi::probes
