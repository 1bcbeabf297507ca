#pragma once
// The baked irradiance volume (effect `probes`): a regular grid of light probes over the level's
// static bounds, each with radiance SH (order 2 or 3, RGB) and visibility moments for leak
// control, plus the CPU lookups DNRT and dynamic-object lighting use.
//
// Lookup weights (trilinear × backface × Chebyshev visibility, normalised) come from
// shaders/probes/probe_weights.glsl, compiled here as C++: the CPU API and the GPU node use the
// same code. Irradiance is E(n) = Σ_k w_k Σ_lm Â_l L^k_lm Y_lm(n) (sh::evalIrradiance).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/math/oct_map.hpp"

namespace bounce::gi::probes {

// Visibility bins per probe (probe_weights.glsl PROBE_VIS_RES², equal-area cylindrical map).
inline constexpr int kVisRes = 8;
inline constexpr int kVisBins = kVisRes * kVisRes;

// Visibility bin of a unit direction (probe_weights.glsl probeVisBin).
int visBin(const glm::vec3& dir);

// Probe (i, j, k) sits at origin + spacing·(i, j, k).
struct ProbeGrid {
  glm::vec3 origin{0.0f};
  float spacing = 0.1f;  // metres
  glm::ivec3 count{1};
  std::size_t probeCount() const { return std::size_t(count.x) * count.y * count.z; }
  glm::vec3 position(std::size_t index) const;
};

// Receiver offsets, as fractions of the spacing (DDGI §4: moving the lookup point off the surface
// keeps a receiver from being shadowed by its own surface in the visibility test).
struct LookupBias {
  float normal = 0.1f;  // along the surface normal
  float view = 0.2f;    // towards the eye (GPU node only; the CPU API has no eye)
};

struct ProbeVolume {
  ProbeGrid grid;
  int order = 3;                     // SH order: 2 (4 coefficients) or 3 (9)
  std::vector<glm::vec3> sh;         // probeCount × order² RGB radiance coefficients (windowed)
  std::vector<glm::vec2> moments;    // probeCount × kVisBins: mean and mean-square hit distance (m, m²)
  std::vector<std::uint32_t> valid;  // probeCount: 1 usable, 0 inside geometry (weight 0)
  // Per probe a math::kOctMapRes² octahedral map of the static radiance (issue 13, README "SL's
  // blocked light read from the probes' direction maps, session 19"): texel t of probe i, channel c
  // at [(i · kOctMapTexels + t) · 3 + c], fp16 (glm::packHalf1x16), W/(m²·sr). Built by the bake from
  // the same rays as the SH (bake.hpp); empty when a volume has none (hand-made volumes), and then
  // radianceAt() evaluates the SH at the texels instead. SL pass 2 reads it at each SL
  // ("blocked_read": "map"): the order-3 SH spreads the floor's bright half over the horizon, where
  // the directions an SL blocks lie (README "SL's blocked light on the characters' floor, session 18").
  std::vector<std::uint16_t> dirMap;
  LookupBias bias;

  int coeffs() const { return order * order; }
  // σ² floor of the Chebyshev test: (1% of the spacing)², so a bin with one ray (σ = 0) still
  // gives a smooth, not a hard, cut.
  float minVariance() const { return 1e-4f * grid.spacing * grid.spacing; }

  // The 8 probes around `pos` and their normalised weights for a receiver with unit normal
  // `normal` (zero vector: no backface term, e.g. a point in the air); `view` is the unit vector
  // to the eye or zero. Weights are all 0 when no valid probe surrounds the point.
  void weights(const glm::vec3& pos, const glm::vec3& normal, const glm::vec3& view, int probe[8],
               float weight[8]) const;

  // Weighted radiance SH (order² RGB coefficients) at `pos`: DNRT's c_j. `normal` as above.
  std::vector<glm::vec3> radianceSH(const glm::vec3& pos, const glm::vec3& normal = glm::vec3(0.0f)) const;
  // One lookup (weights() once) for both stores: the weighted radiance SH into `sh` (order² RGB) and,
  // when `map` is not null, the same weights' blend of the probes' direction maps into it
  // (math::kOctMapTexels RGB radiance): SL's pass 1 at each posed SL centre (incident::ProbeSource).
  // Without baked maps the blended SH evaluated at each texel's centre direction.
  void radianceAt(const glm::vec3& pos, const glm::vec3& normal, std::vector<glm::vec3>& sh, std::vector<glm::vec3>* map) const;
  bool hasDirMap() const { return !dirMap.empty() && dirMap.size() == grid.probeCount() * math::kOctMapTexels * 3; }
  // Texel t of probe i's direction map (RGB, W/(m²·sr)); needs hasDirMap().
  glm::vec3 dirMapTexel(std::size_t probe, int texel) const;
  // Irradiance E(n) (W/m² in the renderer's linear units) at a surface point with unit normal n.
  glm::vec3 irradiance(const glm::vec3& pos, const glm::vec3& normal, const glm::vec3& view = glm::vec3(0.0f)) const;
};

// Versioned binary format: magic "BPRB", format version, header, arrays, FNV/splitmix checksum of
// everything before it. load() validates sizes, counts, order, finiteness and the checksum and
// throws InputError naming `name` on any mismatch.
// 2: the direction maps (dirMap; header field dirMapRes, 0 when the volume has none).
inline constexpr std::uint32_t kProbeFormatVersion = 2;
std::vector<std::uint8_t> serialize(const ProbeVolume& volume);
ProbeVolume deserialize(std::span<const std::uint8_t> bytes, const std::string& name);

}  // namespace bounce::gi::probes
