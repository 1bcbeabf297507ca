#pragma once
// RTF precompute (Pan et al. 2007, §3.2 and §4) for ONE rigid object in its local frame:
//  1. proxies χ_1..χ_m: k-means centres of the object's vertices (§3.2);
//  2. per-vertex transfer (Eq. 8, self-shadowing and self-interreflection) by Monte Carlo as in
//     Sloan et al. 2002 §5, with the direct term weighted by the inverse-distance weights w_k(p)
//     (Eq. 3). Diffuse only, so instead of the operator T_{p,k} (16×16) we keep its product with
//     the diffuse reflection row h_p^i = ρ_p/π ∫ y_i(s)(s·n_p)₊ ds (which does not depend on the
//     view direction ω): t_{p,k}^j = Σ_i h_p^i T^{ij}_{p,k}, so the outgoing radiance is
//     I_p = Σ_k Σ_j t_{p,k}^j l_{k,j} (RGB: ρ is RGB). Estimator (cosine-weighted rays, pdf cos/π):
//       bounce 0: t⁰_{p,k}^j = ρ_p w_k(p) (1/S) Σ_{rays that escape} y_j(s)
//       bounce b: t^b_{p,k}   = ρ_p (1/S) Σ_{rays that hit O's front faces} t^{b−1}_{x,k}
//     t = Σ_{b ≤ selfBounces} t^b, t_x at the hit x interpolated over its triangle's corners with
//     Embree's barycentrics, t_x = Σ_c b_c t_{v_c}, as the rasteriser interpolates per-vertex
//     transfer (until session 12: the nearest vertex's t);
//  3. at every sample q on the concentric spheres (field.hpp) the ITF (Eq. 6–7), over the texel
//     directions ω of one cube map (face size raysPerAxis; the paper's 6×64×64, §4) weighted by
//     their exact solid angles Δω: M^{ij}_{q,k} = Σ_{rays hitting p} Δω y_i(ω) t_{p,k}^j (t_p
//     interpolated over p's triangle as in 2.), and the
//     OOF V_q^i = Σ_{rays that miss} Δω y_i(ω). A sample inside the object (most hits are back
//     faces) gets M = 0 and V = 0 (all light is blocked there);
//  4. CPCA of the ITF vectors (Eq. 9, cpca.hpp), rounded to fp16 as the file stores it, its
//     Frobenius error after the rounding and the stored compression ratio.
// Deterministic: vertex v draws from Pcg32::fromIndex(v); the field's directions are fixed.
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/rtf/field.hpp"
#include "engine/ref/scene_bvh.hpp"

namespace bounce::gi::rtf {

// k-means (Lloyd, farthest-point seeds, deterministic) over `points`: min(m, distinct) centres.
std::vector<glm::vec3> kmeans(std::span<const glm::vec3> points, int m, int iterations = 16);

// Eq. 3: w_k = |p − χ_k|⁻¹ / Σ_i |p − χ_i|⁻¹. When p lies on proxies (distance ≤ 1e-6·scale, the
// limit of Eq. 3 as the distance → 0), the weight is shared equally by those proxies, 0 elsewhere.
std::vector<float> proxyWeights(glm::vec3 p, std::span<const glm::vec3> proxies, float scale);

struct BakeStats {
  double frobenius = 0.0;       // CPCA error (relative Frobenius norm)
  double ratio = 0.0;           // CPCA compression ratio as stored: fp32 bytes before / bytes after (cpca.hpp storedRatio)
  double rawMB = 0.0;           // uncompressed ITF, float32, MB (10⁶ bytes)
  double compressedMB = 0.0;    // CPCA basis and per-sample α (fp16) + cluster id (uint32), as stored
  double seconds = 0.0;
  std::size_t insideSamples = 0;
};

struct BakeResult {
  Field field;
  BakeStats stats;
  std::vector<float> itf;  // uncompressed M, sample-major (itfIndex layout), kept for tests
};

// The albedo each vertex's transfer carries (RGB, vertices of all meshes in order): the material's
// factor, or for a textured material the texture's hat-weighted mean over the triangles around the
// vertex (bake.cpp meshAlbedo: Σ_v ρ_v ∫ b_v dA = ∫ ρ dA), each clamped to [0, 1] as gbuffer.frag.
std::vector<glm::vec3> vertexAlbedo(const ref::SceneDesc& object);

// Vertex transfer t_{p,k}^j (RGB), [vertex · m·16 + k·16 + j], vertices of all meshes in order.
std::vector<glm::vec3> vertexTransfer(const ref::SceneDesc& object, std::span<const glm::vec3> proxies,
                                      float radius, const FieldSettings& settings);

BakeResult bake(const ref::SceneDesc& object, const FieldSettings& settings);

// Cache key: every mesh, material and texture byte of `object` plus the settings and format version.
std::string cacheKey(const ref::SceneDesc& object, const FieldSettings& settings);
std::filesystem::path cachePath(const ref::SceneDesc& object, const FieldSettings& settings,
                                const std::filesystem::path& cacheDir);
// The field from `cacheDir`/rtf-<key>.field, baking and storing it on a miss (a corrupt file is
// rebaked with a warning).
Field bakeCached(const ref::SceneDesc& object, const FieldSettings& settings, const std::filesystem::path& cacheDir,
                 bool* fromCache = nullptr);

}  // namespace bounce::gi::rtf
