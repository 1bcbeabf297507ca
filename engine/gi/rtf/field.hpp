#pragma once
// A baked radiance transfer field (RTF; Pan et al. 2007, §3.3) of ONE rigid object, in the
// object's local frame and in units of its bounding radius η (so one field serves the object at
// any position, rotation and uniform scale). Diffuse transfer only (the paper's glossy half is not
// built).
//
// Samples (§6, as the shadow fields of Zhou et al. 2005): `spheres` concentric spheres about the
// bounding-sphere centre o, radii uniformly spaced from innerRadius·η to outerRadius·η (paper:
// 16 spheres from 0.1η to 8η); on each, 6·n_r² directions through the texel centres of a cube map
// of face size n_r (paper n_r = 16 for diffuse objects). Sample index
//   s = (sphere·6 + face)·n_r² + y·n_r + x,  position o + r_sphere·cubeTexelDirection(face, x, y).
//
// Per sample the field holds
//  - the ITF matrices M_{q,k} (Eq. 6–7), 4th-order SH (16×16) per proxy k and RGB channel, CPCA
//    compressed (Eq. 9, cpca.hpp): the sample vector is laid out d = ((k·16 + i)·16 + j)·3 + c,
//    i the output (incident-at-q) coefficient, j the proxy-light coefficient, c the channel;
//    the radiance arriving at q from direction ω is I_q(ω) = Σ_i (Σ_k Σ_j M^{ij}_{q,k} l_{k,j}) y_i(ω)
//    (Eq. 5), ω pointing from q towards the object;
//  - the object occlusion field (OOF, Zhou et al. 2005): the SH projection (16 coefficients, not
//    compressed) of the visibility V_q(ω) = 1 where the ray from q along ω misses the object.
//
// File (version 3): "BRTFFLD\0", version, settings, centre, radius, proxies, CPCA (cpca.hpp quantize:
// the means and the first ne − n₈ basis rows as fp16, the last n₈ rows as int8 codes, their fp32
// scales, per-sample cluster id as uint32, the first ne − n₈ α as fp16, the last n₈ as int8 codes,
// the per-sample fp32 scales), OOF (fp32), the CPCA error
// measured after that rounding, then a 64-bit checksum of every byte before it. load validates
// every count, index and value (an inf or NaN half included) and throws InputError naming the file.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/rtf/cpca.hpp"

namespace bounce::gi::rtf {

inline constexpr int kShOrder = 4;  // the paper's 4th-order SH
inline constexpr int kShCount = kShOrder * kShOrder;

struct FieldSettings {
  int proxies = 16;            // m, k-means centres over the vertices (§3.2; paper 8–24)
  int spheres = 16;            // concentric spheres (paper 16), ≥ 2
  int faceSize = 16;           // n_r: 6·n_r² samples per sphere (paper 16)
  float innerRadius = 0.1f;    // innermost sphere, units of η (paper 0.1)
  float outerRadius = 8.0f;    // outermost sphere, units of η (paper 8)
  int raysPerAxis = 16;        // ITF/OOF projection at a sample: a cube map of this face size, 6·n² rays (paper 64)
  int vertexRaysPerAxis = 16;  // vertex transfer (Eq. 8): vertexRaysPerAxis² cosine-weighted rays
  int selfBounces = 2;         // self-interreflection bounces in the vertex transfer (Eq. 8)
  int clusters = 32;           // CPCA n_c (paper 32)
  int components = 16;         // CPCA n_e (paper 16)
  int byteComponents = 0;      // n₈: the last n₈ components stored in 8 bits (cpca.hpp quantize), 0..components
};
// Throws InternalError when a setting is out of range (callers validate user input first).
void checkSettings(const FieldSettings& s);

// Radius of sphere `index` in units of η.
float sphereRadius(const FieldSettings& s, int index);
int samplesPerSphere(const FieldSettings& s);
std::size_t sampleCount(const FieldSettings& s);
// Unit direction (local frame) of sample `index`'s ray from o: cubeTexelDirection(face, x, y) of the
// header's sample order; the sample lies on sphere index / samplesPerSphere.
glm::vec3 sampleDirection(const FieldSettings& s, std::size_t index);
// Sample `index`'s offset from o in units of η: sphereRadius · sampleDirection.
glm::vec3 samplePosition(const FieldSettings& s, std::size_t index);
// Dimension of one sample's ITF vector: proxies · 16 · 16 · 3.
std::size_t itfDimension(const FieldSettings& s);
inline std::size_t itfIndex(int k, int i, int j, int c) { return ((std::size_t(k) * kShCount + i) * kShCount + j) * 3 + c; }

struct Field {
  FieldSettings settings;
  glm::vec3 centre{0.0f};  // o in the object's local frame (metres of the baked mesh)
  float radius = 1.0f;     // η in the same units
  std::vector<glm::vec3> proxies;  // χ_k, local frame, metres
  Cpca itf;                        // M_{q,k} of every sample, compressed
  std::vector<float> oof;          // oof[s·16 + i]
  double frobenius = 0.0;          // CPCA error of itf (fp16-rounded) against the uncompressed bake (relative)
};

std::vector<std::uint8_t> serialize(const Field& field);
Field deserialize(std::span<const std::uint8_t> bytes, const std::string& fileName);
void save(const Field& field, const std::filesystem::path& path);
Field load(const std::filesystem::path& path);

}  // namespace bounce::gi::rtf
