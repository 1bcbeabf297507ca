// The ξ pass's body, compiled twice: xi.comp (one atomicMax a lane) and xi_subgroup.comp (the ranges reduced
// over the subgroup first), XiPass picks by the device.
// RTF caches (Pan et al. 2007, §5 "Caching RTF eigens" and "Caching RTF samples") as one
// per-frame compute pass in three dispatches (push constant `stage`), engine/gi/rtf/xi_pass.hpp:
//  stage 0, Eq. 12: u_{h,e,i} = Σ_k Σ_j E_{he,k}[i][j] L_{k,j}  (per RGB channel), one invocation
//           per (cluster h, component e = 0 (mean) … n_e), all 16 output coefficients i;
//  stage 1, Eq. 11: ξ_{r,i} = u_{h(r),0,i} + Σ_e α_e(r) u_{h(r),e,i}, one invocation per sample r
//           (all 16 coefficients i), stored in the ξ image when kKeepXi; with it X (below) and its range;
//  stage 2: X encoded into the 8-bit image the shading step reads (below), in two variants: X off the
//           objects and X on them, which differ only in w (the interreflected light's factor, overlap.hpp);
//           one invocation per sample.
// Data (std430, bytes), as the field file stores it (cpca.hpp quantize / storedParts), with
// n₈ = byteComponents and n_h = n_e − n₈: basis = n_c·(n_h+1)·D halves (per cluster the mean and
// E_1..E_{n_h}), D = m·16·16·3, element ((k·16 + i)·16 + j)·3 + c of a component (field.hpp
// itfIndex); alpha = N·n_h halves; both two to a uint (packHalf2x16: element 2w in word w's low
// half, xi_pass.cpp halfWords): half the bytes to upload and read of fp32 buffers, same values;
// basisCodes = n_c·n₈·D and alphaCodes = N·n₈ signed 8-bit codes, four to a uint (xi_pass.cpp
// byteWords); scales = n_c·n₈ row scales then N sample scales: E_h(n_h+t) = scales[h·n₈ + t−1]·code,
// α_(n_h+t)(r) = scales[n_c·n₈ + r]·code (the decoded values of the C++ Cpca, evaluate.cpp);
// cluster = uint[N]; light = vec4[m·16] (rgb: L_{k,j}, proxies' light in the object's frame);
// eigen = vec4[n_c·(n_e+1)·16] (rgb: u).
// ξ image: rgba32f 2D array, layer = sphere·16 + i, texel (face·n_r + x, y) for sample
// r = (sphere·6 + face)·n_r² + y·n_r + x (field.hpp's sample order). SSBOs are fine here: this is a
// compute pass (DESIGN machine facts forbid them in fragment shaders, which read the image).
layout(local_size_x = 64) in;

// Specialization (xi_pass.cpp), one pipeline each: llvmpipe runs an untaken branch in full.
// kKeepXi: stage 1 also stores ξ (16 rgba32f texels a sample) in the ξ image. Only tests read it (the
// shading step reads X); frames skip the stores: ≈ 12 % of `rtf.bounce` on cornell-5 (README "RTF's
// nearer-object occlusion per receiver, session 26").
layout(constant_id = 0) const bool kKeepXi = true;
// RTF_XI_SUBGROUP_MAX (xi_subgroup.comp): each slot's range is reduced over the subgroup first (subgroupMax of
// the same float bits), so one lane of 8 (llvmpipe's subgroup) does the 27 atomicMax, not every lane; the
// maximum is the same (≈ 3–5 % of `rtf.bounce` on llvmpipe). A separate module, not a specialization constant:
// the subgroup capability must not appear in the module a device without subgroup arithmetic gets (xi.comp;
// XiPass asks the device which).

layout(std430, binding = 0) readonly buffer Basis { uint basis[]; };  // packHalf2x16 words
layout(std430, binding = 1) readonly buffer Alpha { uint alpha[]; };  // packHalf2x16 words
layout(std430, binding = 2) readonly buffer Cluster { uint cluster[]; };
layout(std430, binding = 3) readonly buffer Light { vec4 light[]; };
layout(std430, binding = 4) buffer Eigen { vec4 eigen[]; };
layout(rgba32f, binding = 5) uniform writeonly image2DArray xi;
// The shading step folded per sample (engine/gi/rtf/node.hpp): for i < 9,
//   X_i = Â_l(i)/π · ξ_i − Σ_j T'_ij (u − V)_j
// with V the sample's OOF (oof = float[N·16]), u the SH of V ≡ 1 and T'_ij = Â_l(i)/π · T_ij the
// product matrix of the indirect light blocked by the object (light[m·16 + j·9 + i].rgb, after the
// proxies' light). Both parts are linear in what Eq. 10 interpolates, so the shading pass looks X up
// with the same trilinear weights (the fade included: u − V fades to 0 with them) and only evaluates
// Σ_i y_i(n) X_i.
// Stored as RGBA8 UNORM (llvmpipe filters 8-bit unorm texels on its fast fixed-point path; a float
// texel goes through the general one, DESIGN.md "What costs what"), as Y = r_s² X (the sample's
// sphere radius in η squared: xi_pass.hpp netScale), 27 values in 7 texels in
// DNRT's Table 2 order (rtfNetSlot): texel k < 3 holds channel k's Y_0..3, 3 ≤ k < 6 channel
// (k−3)'s Y_4..7, texel 6 Y_8.rgb. Each of the 28 slots has its own scale m = max |Y| over the
// samples this frame (range[], atomicMax of the float bits: non-negative floats order as uints), and
// holds t = Y/(2m) + ½ rounded to 1/255, so Y = m(2t − 1) to ½·2m/255. Image: 3D, texel
// (face·n_r + x, y, k·spheres + sphere): one coefficient group's spheres are consecutive slices, so
// one trilinear fetch is Eq. 10's whole lookup for 4 values (rtf.frag). Two variants (overlap.hpp): texels
// k < 7 hold X off the objects (w_off, scale.w), texels 7 ≤ k < 14 the same slots of X on them (w_on,
// onObjects[]); they share each slot's m (the max over both), so rtf.frag decodes either with one range.
layout(std430, binding = 6) readonly buffer Oof { float oof[]; };
layout(rgba8, binding = 7) uniform writeonly image3D net;
layout(std430, binding = 8) buffer Range { uint range[28]; };  // float bits of max |Y| per slot; 0 before stage 1
layout(std430, binding = 9) buffer Net { vec4 netValue[]; };    // Y = r_s² X per (sample, variant, i < 9), rgb: [(r·2 + v)·9 + i]
// Per sample (overlap.hpp sharedOcclusion's scale), rgb: the factor of the blocked term (the share of the
// directions this object hides that no other object's term already takes off); w = w_off: the factor of the
// interreflected term for receivers off the rtf objects (the share of this object's light the nearer objects
// let through, Algorithm 1's V_{<i}; OnObjects holds w_on). 1 where one object acts.
layout(std430, binding = 10) readonly buffer BlockedScale { vec4 blockedScale[]; };
layout(std430, binding = 11) readonly buffer BasisCodes { uint basisCodes[]; };  // 4 codes a word
layout(std430, binding = 12) readonly buffer AlphaCodes { uint alphaCodes[]; };  // 4 codes a word
layout(std430, binding = 13) readonly buffer Scales { float scales[]; };
// Per sample: w for receivers on an rtf object's surface (overlap.hpp w_on; XiPass::setBlockedScale), the
// on-object variant's factor of the interreflected term in place of BlockedScale's w.
layout(std430, binding = 14) readonly buffer OnObjects { float onObjects[]; };

// Code n of a 4-to-a-word buffer word, sign-extended (two's complement int8).
float codeAt(uint word, uint n) { return float(bitfieldExtract(int(word), int(8u * (n & 3u)), 8)); }

// α_e(r), e ≤ n_h, at n = r·n_h + e − 1 (n_h may be odd: a row can start in a word's high half).
float alphaAt(uint n) {
  vec2 pair = unpackHalf2x16(alpha[n >> 1u]);
  return (n & 1u) == 0u ? pair.x : pair.y;
}

// Slot (texel k · 4 + component) of channel c's coefficient i (Table 2 order above).
uint rtfNetSlot(uint c, uint i) { return i < 8u ? ((i / 4u) * 3u + c) * 4u + i % 4u : 24u + c; }

layout(push_constant) uniform Push {
  uint stage;
  uint proxies;     // m
  uint clusters;    // n_c
  uint components;  // n_e
  uint samples;     // N
  uint faceSize;    // n_r
  uint byteComponents;  // n₈: the last n₈ of the n_e components in 8-bit codes
  float innerRadius;    // η, the innermost sphere's radius
  float outerRadius;    // η, the outermost's
} pc;

// Y = r_s² X is what the 8 bits hold (xi_pass.hpp netScale says why; rtf.frag divides it out again):
// sphere s's squared radius in η², as field.cpp sphereRadius computes it.
float netScale(uint sphere, uint spheres) {
  float r = pc.innerRadius + (pc.outerRadius - pc.innerRadius) * float(sphere) / float(spheres - 1u);
  return r * r;
}

// Stage 2: after every X and its slot's range are known, one invocation per sample r, all 14 texels: the
// two variants (0: off the objects, 1: on them) of 7 texels each. One invocation per (sample, texel) cost
// llvmpipe more in workgroups launched than in the encoding (≈ 2 ms an object at cornell-5's 1296 samples,
// README "RTF's nearer-object occlusion per receiver, session 26"). Constant trip counts: unrolled.
void encode(uint r) {
  if (r >= pc.samples) return;
  uint n2 = pc.faceSize * pc.faceSize, per = 6u * n2;
  uint sphere = r / per, rest = r % per, face = rest / n2;
  uint px = rest % pc.faceSize, py = (rest % n2) / pc.faceSize;
  uint spheres = pc.samples / per;
  for (uint variant = 0u; variant < 2u; ++variant)
    for (uint kk = 0u; kk < 7u; ++kk) {
      vec4 v = vec4(128.0 / 255.0);  // slot 27 (texel 6's w) holds nothing: m = 0, so X = 0
      for (uint comp = 0u; comp < 4u; ++comp) {
        uint slot = kk * 4u + comp;
        if (slot < 27u) {
          uint c = kk < 6u ? kk % 3u : comp, i = kk < 6u ? (kk / 3u) * 4u + comp : 8u;
          float m = uintBitsToFloat(range[slot]);
          float enc = m > 0.0 ? netValue[(r * 2u + variant) * 9u + i][c] / (2.0 * m) + 0.5 : 0.5;
          v[comp] = roundEven(clamp(enc, 0.0, 1.0) * 255.0) / 255.0;  // exact in UNORM8: no conversion rounding left
        }
      }
      imageStore(net, ivec3(int(face * pc.faceSize + px), int(py), int((variant * 7u + kk) * spheres + sphere)), v);
    }
}

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (pc.stage == 2u) {
    encode(t);
    return;
  }
  if (pc.stage == 0u) {
    // One invocation per (cluster h, component e), all 16 output coefficients i: each proxy-light
    // coefficient is read once, not once per i (a storage-buffer read per lane on llvmpipe). Every u_i is
    // summed over k and j in the same order as one invocation per (h, e, i) did, so the values are the same.
    uint count = pc.clusters * (pc.components + 1u);
    if (t >= count) return;
    uint he = t;
    uint D = pc.proxies * 768u;
    uint nh = pc.components - pc.byteComponents, h = he / (pc.components + 1u), e = he % (pc.components + 1u);
    vec3 u[16];
    for (uint i = 0u; i < 16u; ++i) u[i] = vec3(0.0);
    // do…while with a guarded body: llvmpipe runs a `for` body once more with every lane masked
    // (README "Loop bodies III"): with one proxy, 2 bodies of 16·16 multiply-adds, not 1.
    uint k = 0u;
    if (e > nh) {  // an 8-bit row: Σ code·L, then × the row's scale
      uint row = (h * pc.byteComponents + e - nh - 1u) * D;
      do {
        if (k < pc.proxies)
          for (uint j = 0u; j < 16u; ++j) {
            vec3 L = light[k * 16u + j].rgb;
            for (uint i = 0u; i < 16u; ++i) {
              uint n = row + (k * 16u + i) * 48u + j * 3u;  // element (j, c) of the row's (k, i) block
              vec3 q = vec3(codeAt(basisCodes[n >> 2u], n), codeAt(basisCodes[(n + 1u) >> 2u], n + 1u),
                            codeAt(basisCodes[(n + 2u) >> 2u], n + 2u));
              u[i] += q * L;
            }
          }
        ++k;
      } while (k < pc.proxies);
      float scale = scales[h * pc.byteComponents + e - nh - 1u];
      for (uint i = 0u; i < 16u; ++i) eigen[he * 16u + i] = vec4(scale * u[i], 0.0);
      return;
    }
    uint hh = h * (nh + 1u) + e;  // the row among the half rows
    do {
      if (k < pc.proxies)
        // E[i][j].rgb for j = 2jj, 2jj + 1: 6 halves in 3 words (the row of 48 halves starts at an
        // even element: D and 48 are even).
        for (uint jj = 0u; jj < 8u; ++jj) {
          vec3 L0 = light[k * 16u + 2u * jj].rgb, L1 = light[k * 16u + 2u * jj + 1u].rgb;
          for (uint i = 0u; i < 16u; ++i) {
            uint w = (hh * D + (k * 16u + i) * 48u) / 2u + jj * 3u;
            vec2 a = unpackHalf2x16(basis[w]), b = unpackHalf2x16(basis[w + 1u]), c = unpackHalf2x16(basis[w + 2u]);
            u[i] += vec3(a.x, a.y, b.x) * L0;
            u[i] += vec3(b.y, c.x, c.y) * L1;
          }
        }
      ++k;
    } while (k < pc.proxies);
    for (uint i = 0u; i < 16u; ++i) eigen[he * 16u + i] = vec4(u[i], 0.0);
  } else {
    // One invocation per sample r, all 16 coefficients: the sample's cluster, α, OOF and scale are read
    // once, not once per coefficient (llvmpipe reads a storage buffer per lane with a bounds check; one
    // invocation per (r, i) read each α 16 times and each OOF value 9 times). Every x_i and X_i is summed in
    // the same order as before, so the values are the same.
    if (t >= pc.samples) return;
    uint r = t;
    uint base = cluster[r] * (pc.components + 1u) * 16u;
    vec3 x[16];
    for (uint i = 0u; i < 16u; ++i) x[i] = eigen[base + i].rgb;
    uint nh = pc.components - pc.byteComponents;
    uint e = 1u;
    do {  // do…while, guarded, as stage 0's loop
      if (e <= nh) {
        float a = alphaAt(r * nh + e - 1u);
        for (uint i = 0u; i < 16u; ++i) x[i] += a * eigen[base + e * 16u + i].rgb;
      }
      ++e;
    } while (e <= nh);
    if (pc.byteComponents > 0u) {  // α = scale·code: the products in fp32 as the C++ decode (field.cpp)
      float s = scales[pc.clusters * pc.byteComponents + r];
      e = nh + 1u;  // the loop above ran its body once even for n_h = 0
      do {
        uint n = r * pc.byteComponents + e - nh - 1u;
        if (e <= pc.components) {
          float a = s * codeAt(alphaCodes[n >> 2u], n);
          for (uint i = 0u; i < 16u; ++i) x[i] += a * eigen[base + e * 16u + i].rgb;
        }
        ++e;
      } while (e <= pc.components);
    }
    uint n2 = pc.faceSize * pc.faceSize, per = 6u * n2;
    uint sphere = r / per, rest = r % per, face = rest / n2;
    uint px = rest % pc.faceSize, py = (rest % n2) / pc.faceSize;
    ivec2 texel = ivec2(int(face * pc.faceSize + px), int(py));
    if (kKeepXi)
      for (uint i = 0u; i < 16u; ++i) imageStore(xi, ivec3(texel, int(sphere * 16u + i)), vec4(x[i], 0.0));
    float on = onObjects[r];  // w on the objects' surfaces (scale.w off them)
    float notV[16];
    for (uint j = 0u; j < 16u; ++j) notV[j] = (j == 0u ? 3.5449077018110318 : 0.0) - oof[r * 16u + j];  // u_0 = 2√π
    vec4 scale = blockedScale[r];
    float r2 = netScale(sphere, pc.samples / per);
    uint T = pc.proxies * 16u;
    const float kInvPi = 0.31830988618379067;
    for (uint i = 0u; i < 9u; ++i) {
      float a = (i == 0u ? 3.14159265358979324 : (i < 4u ? 2.09439510239319549 : 0.78539816339744831)) * kInvPi;
      vec3 blocked = vec3(0.0);
      for (uint j = 0u; j < 16u; ++j) blocked += notV[j] * light[T + j * 9u + i].rgb;
      blocked *= scale.rgb;
      // w: the share of ξ the nearer objects let through (overlap.hpp), off and on the objects' surfaces.
      vec3 X = (a * x[i] * scale.w - blocked) * r2;  // Y, the value the 8 bits hold
      vec3 Xon = (a * x[i] * on - blocked) * r2;
      netValue[(r * 2u) * 9u + i] = vec4(X, 0.0);
      netValue[(r * 2u + 1u) * 9u + i] = vec4(Xon, 0.0);
      for (uint c = 0u; c < 3u; ++c) {
        uint bits = floatBitsToUint(max(abs(X[c]), abs(Xon[c])));
#ifdef RTF_XI_SUBGROUP_MAX
        bits = subgroupMax(bits);
        if (subgroupElect()) atomicMax(range[rtfNetSlot(c, i)], bits);
#else
        atomicMax(range[rtfNetSlot(c, i)], bits);
#endif
      }
    }
  }
}

