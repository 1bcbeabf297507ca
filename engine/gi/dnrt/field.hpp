#pragma once
// A baked DNRT transfer field: the coefficients m_j = t_j − k_j (paper Eq. 8, 13, §5.1.2) on a
// regular N³ grid around one object, in the object's LOCAL frame and in units of its bounding
// radius R (so one field serves the object at any position, rotation and uniform scale).
//
// Geometry (all in units of R, relative to the bounding-sphere centre o):
//  - the INNER volume is the cube [−inner, +inner]³; grid vertex (x, y, z) sits at
//    −inner + 2·inner·(x, y, z)/(N−1) (vertex-centred: the outermost vertices lie on the faces);
//  - the OUTER volume is the cube [−outer, +outer]³, outer > inner: across the shell between them the
//    inner-boundary value fades to zero (evaluate.hpp, §5.2.2);
//  - 3D-texture coordinate of a point q: uvw = (g + ½)/N with g = (q/inner + 1)/2 · (N−1), so texel
//    centres coincide with grid vertices and hardware trilinear filtering interpolates them.
//
// Storage (paper Table 2): RGBA8 UNORM 3D textures, x fastest, then y, then z. 4 SH → 3 textures,
// texture c ∈ {R,G,B} holds (m_0, m_1, m_2, m_3) of channel c; 9 SH → 7 textures, 3 + c holds
// (m_4, m_5, m_6, m_7) of channel c and texture 6 holds (m_8.r, m_8.g, m_8.b, unused). The paper's
// last image is RGB24; RGBA8 here because 3-component 8-bit formats are rarely sampleable in Vulkan.
// Each (texture, component) slot has its own range [lo, hi] (the header): value = lo + (hi−lo)·byte/255,
// a linear map, so filtering the bytes and then decoding equals decoding then filtering.
#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::gi::dnrt {

// How k_j (anti-radiance, Eq. 13) approximates the radiance the object blocks.
enum class AntiRadiance : std::uint32_t {
  Paper = 0,     // Eq. 12: L_init(ω) ≈ I(ω)/π, the irradiance at normal ω over π
  Improved = 1,  // App. B.2: L_init(ω) ≈ radiance recovered from the c_j, band l divided by Â_l
};

struct FieldSettings {
  int shCount = 4;         // 4 (bands 0–1) or 9 (bands 0–2)
  int grid = 32;           // N: 16, 32 or 64 (tests also use small values ≥ 2)
  float innerExtent = 3.0f;  // half-size of the inner cube, in units of R (paper: unspecified)
  float outerExtent = 6.0f;  // half-size of the outer cube, in units of R; > innerExtent
  int samplesPerAxis = 16;   // rays per vertex = samplesPerAxis² (stratified, cosine-weighted)
  AntiRadiance antiRadiance = AntiRadiance::Paper;
  // The anti-radiance alone: m_j = −k_j (t_j left out). Added with the lights' c_j negated, it cancels
  // the LIGHTS' part of the anti-radiance when the lights' occlusion is already drawn elsewhere (the direct
  // pass's shadow maps, and the relit probes for its bounce): README "DNRT with the relit probes,
  // session 10". Stored in the file as bit 8 of the anti-radiance word (older files: 0).
  bool occlusionOnly = false;
};

// Throws InternalError when a setting is out of range (callers validate user input first).
void checkSettings(const FieldSettings& s);
// Number of RGBA8 textures for an SH count: 3 (4 SH) or 7 (9 SH).
int textureCount(int shCount);

struct Range {
  float lo = 0.0f, hi = 0.0f;
};

// The range the bake's estimator (bake.hpp) confines m_j to, whatever the object: with S rays,
// t_j = Σ_hits Y_j(n_s) ρ_s / (π S) and k_j = s_l Σ_hits Y_j(ω) / (π S) (s_l = π/Â_l in the
// improved mode, 1 in the paper's), at most S hits and ρ_s in [0, 1], so
//   m_0 ∈ [−Y_00/π, 0]   (one hit adds Y_00 (ρ_s − 1) ≤ 0),
//   |m_j| ≤ (1 + s_l) max|Y_j| / π   for j ≥ 1 (max|Y_j| over the sphere: 0.4886 for l = 1;
//   0.5463 for j = 4, 5, 7, 8; 0.6308 for j = 6).
// A baked range outside it means a bug, not an unusual object (bake() warns).
Range analyticRange(int j, AntiRadiance mode);
// The paper's Table 1 range for m_j, j < 9. Every analyticRange lies inside it (the paper's
// bounds are 2·(SH normalisation constant of Y_j), looser than ours by about π).
Range table1Range(int j);

// Where coefficient j, channel c lives: texture index and component (Table 2).
struct Slot {
  int texture = 0, component = 0;
};
Slot slotOf(int j, int channel);

struct Field {
  FieldSettings settings;
  glm::vec3 centre{0.0f};  // o in the object's local frame (metres of the baked mesh)
  float radius = 1.0f;     // R in the same units
  // ranges[texture·4 + component]
  std::vector<Range> ranges;
  // textures[t]: N³·4 bytes
  std::vector<std::vector<std::uint8_t>> textures;

  int n() const { return settings.grid; }
  std::size_t vertexCount() const { return std::size_t(n()) * n() * n(); }
  std::size_t vertexIndex(int x, int y, int z) const { return (std::size_t(z) * n() + y) * n() + x; }
  // Decoded m_j (RGB) at one vertex: out.size() >= shCount.
  void decodeVertex(std::size_t vertex, std::span<glm::vec3> out) const;
};

// True when each of the field's slot ranges lies inside analyticRange of its coefficient (up to
// float rounding of the estimator's sum: 1e-6).
bool rangesWithinAnalyticBound(const Field& field);

// Unquantised coefficients: values[vertex · shCount + j] = m_j (RGB), vertex as Field::vertexIndex.
// Quantises with per-slot ranges taken from the data (min/max), so nothing saturates.
Field quantize(const FieldSettings& settings, glm::vec3 centre, float radius, std::span<const glm::vec3> values);

// Largest |decoded − exact| over every vertex, coefficient and channel, and the bound it must
// respect: max over slots of (hi − lo)/510 (half a quantisation step).
struct QuantizationError {
  float maxAbs = 0.0f;
  float bound = 0.0f;
};
QuantizationError quantizationError(const Field& field, std::span<const glm::vec3> values);

// Versioned binary file ("BDNRTFLD", version, settings, centre, radius, ranges, textures, then a
// 64-bit checksum of every byte before it). load validates every count and range and the checksum
// and throws InputError naming the file when it is malformed or corrupt.
std::vector<std::uint8_t> serialize(const Field& field);
Field deserialize(std::span<const std::uint8_t> bytes, const std::string& fileName);
void save(const Field& field, const std::filesystem::path& path);
Field load(const std::filesystem::path& path);

}  // namespace bounce::gi::dnrt
