// SL pass 2 per receiver (Guerrero, Jeschke, Wimmer 2008, §5.2 and §6–7): the irradiance a receiver
// point p with unit normal n gets from every SL, E(p) = Σ_i L̃_i Ṽ_i (Eq. 14), with L̃_i the average
// radiance (Eq. 16–18, the weight ZH rotated into the SL's local frame, §7.1) and Ṽ_i the
// cosine-weighted SH-exponentiated visibility (Eq. 23–24) in the Ratio form, after the receiver rules.
// The GLSL port of engine/gi/sl/evaluate.cpp (the double-precision reference, whose header derives
// every rule): same steps in the same order, float instead of double. tests/unit/sl compares the two
// through shaders/sl/evaluate_selftest.comp; shaders/sl/sl.frag runs it per pixel.
//
// The includer defines before including this file:
//   const uint kOrder (3 or 4), const bool kPerObject (§7.2 per-object blocking, else per-sphere),
//   const uint kSpheres (≥ the SL count: sizes the per-receiver arrays), const float kInfluence
//   (evaluate.hpp rule 0's F; 0: off) — specialization constants;
//   sampler2D slTables: rgba32f, 256×3, read with texelFetch — row 0 texel i: the blocker log ZH
//     (sh_exp.hpp ExpTables::logTable) at θ_i = i/255 · π/2, row 1: Eq. 16's weight ZH
//     (evaluate.hpp averageRadianceTable) at θ_i, row 2 texel i < 128: the optimal-linear (a, b)
//     at ‖f̂‖ = i/127 · 4 (ExpTables::olTable);
//   uint slCount(); vec4 slSphere(uint i) (world centre, radius, metres); mat3 slRotation(uint i)
//     (SL local → world); uint slObject(uint i); vec2 slIntensityPair(uint i, uint c, uint m)
//     (channel c of L^c_2m, L^c_2m+1, pass 1, fp16);
//     uint slObjectCount() (ids 0 … count − 1); vec4 slObjectCentre(uint o) (mean sphere centre, count);
//   optionally SL_SINGLE_OBJECT (a bool constant): true where every SL that can reach the receiver
//   belongs to one object (sl.frag's tiles of one object), so per-object blocking has no closer
//   object: each SL's Ṽ is its exact open cap, and no log, rotated cap, exp or rank is formed
//   (slIrradianceLive's kOpenOnly; llvmpipe runs every branch written, taken or not).
// Includes sh.glsl and sl/gaunt.glsl (the SH square, generated from sh_product.hpp's tensor).
#ifndef BOUNCE_SL_GLSL
#define BOUNCE_SL_GLSL

#include "sh.glsl"
#include "mask.glsl"

const uint kSlCoeffs = kOrder * kOrder;
#ifdef SL_SINGLE_OBJECT
const bool kSlSingleObject = SL_SINGLE_OBJECT;
#else
const bool kSlSingleObject = false;
#endif
const float kSlPi = 3.14159265358979324;
const float kSlSqrt4Pi = 3.54490770181103205;
const float kSlCullFraction = 0.5;  // evaluate.hpp kCullFraction
const float kSlMinOpen = 1e-9;      // evaluate.cpp kMinOpen
const int kSlThetaEntries = 256;
const int kSlMagEntries = 128;
const float kSlMaxMagnitude = 4.0;
const float kSlBlendStart = 3.0;    // sh_exp.hpp ExpTables::kHybridBlendStart
const float kSlMaxExponent = 80.0;  // e^80 < FLT_MAX: the DC factor stays finite (C++: 700, double)

#include "sl/gaunt.glsl"

// Rules 0 (influence), 1 (containment) and 2 (tangent plane) of evaluate.hpp; false when culled.
bool slAdjust(inout vec3 c, inout float r, vec3 p, vec3 n) {
  float d = length(c - p);
  r = max(0.0, r);
  if (kInfluence > 0.0 && d > 0.5 * kInfluence * r) r *= clamp((kInfluence - d / r) / (0.5 * kInfluence), 0.0, 1.0);
  if (d < r) {
    float t = d / r;
    r = d * clamp((t - kSlCullFraction) / (1.0 - kSlCullFraction), 0.0, 1.0);
  }
  float h = dot(n, c - p);
  if (h < r) {
    float top = h + r;
    if (top <= 0.0) return false;
    float r2 = 0.5 * top;
    c += (r2 - h) * n;
    r = r2;
  }
  return r > 0.0;
}

// SL i as receiver p (normal n) sees it, the opening of every candidate walk (sl, sl.shadow,
// sl.local): its centre and radius after the receiver rules in cr, its distance in d; false when a
// rule culls it or its centre sits at p.
bool slSeenFrom(uint i, vec3 p, vec3 n, out vec4 cr, out float d) {
  vec4 sp = slSphere(i);
  vec3 c = sp.xyz;
  float r = sp.w;
  bool kept = slAdjust(c, r, p, n);
  cr = vec4(c, r);
  d = length(c - p);
  return kept && d > 0.0;
}

// Linear interpolation in a 256-entry θ row of slTables (θ clamped to [0, π/2]).
vec4 slThetaRow(int row, float theta) {
  float x = clamp(theta, 0.0, 0.5 * kSlPi) / (0.5 * kSlPi) * float(kSlThetaEntries - 1);
  int i0 = min(int(x), kSlThetaEntries - 2);
  float w = x - float(i0);
  return (1.0 - w) * texelFetch(slTables, ivec2(i0, row), 0) + w * texelFetch(slTables, ivec2(i0 + 1, row), 0);
}

// f_lm = √(4π/(2l+1)) z_l Y_lm(d) (sh_rotate.hpp rotateZonal), y = Y(d) (shEval16): a receiver
// evaluates Y once per direction and reuses it (the log and the cap of one SL share theirs).
void slRotateZonalY(vec4 z, in float y[16], out float f[16]) {
  const float s[4] = float[4](3.54490770181103205, 2.04665341589297697, 1.58533091904240551, 1.33984917138736218);
  for (uint i = 0u; i < 16u; ++i) {
    uint l = i < 1u ? 0u : (i < 4u ? 1u : (i < 9u ? 2u : 3u));
    f[i] = i < kSlCoeffs ? s[l] * z[l] * y[i] : 0.0;
  }
}

void slRotateZonal(vec4 z, vec3 d, out float f[16]) {
  float y[16];
  shEval16(d, y);
  slRotateZonalY(z, y, f);
}

// E = Σ Â_l v_lm Y_lm(n) for a scalar SH vector (sh_convolve.hpp evalIrradiance, Â_3 = 0), with
// y = Y(n): evaluated once per receiver.
float slIrradianceY(in float v[16], in float y[16]) {
  float e = SH_A0 * v[0] * y[0];
  for (uint i = 1u; i < 4u; ++i) e += SH_A1 * v[i] * y[i];
  for (uint i = 4u; i < 9u; ++i) e += SH_A2 * v[i] * y[i];
  return e;
}

// The optimal-linear (a, b) at ‖f̂‖ = m (sh_exp.hpp ExpTables::olCoefficients; m clamped to [0, 4]).
vec2 slOl(float m) {
  float x = clamp(m, 0.0, kSlMaxMagnitude) / kSlMaxMagnitude * float(kSlMagEntries - 1);
  int i0 = min(int(x), kSlMagEntries - 2);
  float w = x - float(i0);
  return (1.0 - w) * texelFetch(slTables, ivec2(i0, 2), 0).xy + w * texelFetch(slTables, ivec2(i0 + 1, 2), 0).xy;
}

// The hybrid exp (sh_exp.hpp expHybrid): DC isolation, optimal-linear on f̂ halved k times until
// ‖f̂‖ ≤ 4, blended over ‖f̂‖/2^k in [3, 4] towards one more halving (continuity, sh_exp.hpp), then k
// squarings (slSquare: the Gaunt tensor, unrolled).
void slExp(in float f[16], out float g[16]) {
  float m2 = 0.0;
  for (uint i = 1u; i < kSlCoeffs; ++i) m2 += f[i] * f[i];
  float m = sqrt(m2);
  int k = 0;
  while (m > kSlMaxMagnitude && k < 30) {
    m *= 0.5;
    ++k;
  }
  vec2 ab = slOl(m);
  float scale = exp2(-float(k));
  g[0] = ab.x * kSlSqrt4Pi;
  for (uint i = 1u; i < 16u; ++i) g[i] = i < kSlCoeffs ? ab.y * (f[i] * scale) : 0.0;
  float x = clamp((m - kSlBlendStart) / (kSlMaxMagnitude - kSlBlendStart), 0.0, 1.0);
  float blend = x * x * (3.0 - 2.0 * x);
  if (blend > 0.0) {
    vec2 abHalf = slOl(0.5 * m);
    float q[16], q2[16];
    q[0] = abHalf.x * kSlSqrt4Pi;
    for (uint i = 1u; i < 16u; ++i) q[i] = i < kSlCoeffs ? abHalf.y * (f[i] * (0.5 * scale)) : 0.0;
    slSquare(q, q2);
    for (uint i = 0u; i < 16u; ++i) g[i] = (1.0 - blend) * g[i] + blend * q2[i];
  }
  // k squarings, do…while: a `for` runs its body once more, masked (README "Loop bodies III").
  int s = 0;
  do {
    if (s < k) {
      float h[16];
      slSquare(g, h);
      g = h;
    }
    ++s;
  } while (s < k);
  float dc = exp(min(f[0] / kSlSqrt4Pi, kSlMaxExponent));
  for (uint i = 0u; i < 16u; ++i) g[i] *= dc;
}

// The unoccluded cap of an SL of angular size sn = sin θ = r/d, as a ZH over s² = sin²θ: the cap's
// closed-form ZH (the complement of sh_exp.hpp capVisibilityZonal: z_l = √(4π/(2l+1)) ∫_cap Y_l0).
// Every z_l has the factor 1 − P_l's neighbour, ∝ sin²θ: written with s² factored out
// (1 − cos θ = s²/(1 + cos θ)) so small caps keep float precision. Rotated to the SL's direction
// (slRotateZonalY) it is per-object's K/s², the cap's projected indicator.
vec4 slOpenCapZonal(float sn) {
  float t = sqrt(max(0.0, 1.0 - sn * sn));
  return vec4(sqrt(kSlPi) / (1.0 + t), 0.5 * sqrt(3.0 * kSlPi), 0.5 * sqrt(5.0 * kSlPi) * t,
              0.125 * sqrt(7.0 * kSlPi) * (5.0 * t * t - 1.0));
}

// The unoccluded cap's exact Ṽ: s² times the irradiance (sh_convolve.hpp evalIrradiance, Â_3 = 0) of
// its ZH rotated to the unit direction dir, at normal n, cos γ = dir · n. By the addition theorem
// (Σ_m Y_lm(dir) Y_lm(n) = (2l+1)/(4π) P_l(cos γ)) that irradiance is Σ_l Â_l z_l √((2l+1)/(4π)) P_l(cos γ),
// P_0 = 1, P_1 = x, P_2 = (3x² − 1)/2: no Y(dir), Y(n) or rotation — a receiver that needs the cap for
// nothing else (per-object blocking's nearest object, the hierarchy's parent) skips them.
float slOpenCapExact(float sn, float cosg) {
  vec4 zs = slOpenCapZonal(sn);
  float x = clamp(cosg, -1.0, 1.0);
  return sn * sn * (SH_A0 * 0.282094791773878143 * zs.x + SH_A1 * 0.488602511902919921 * zs.y * x +
                    SH_A2 * 0.630783130505040012 * zs.z * (1.5 * x * x - 0.5));
}

// Eq. 16–18: L̃ of SL i (angular radius θ, unit direction dir from the receiver to its centre), the
// weight ZH rotated to the SL-local direction from its centre to p (§7.1), dotted with L^c over the
// fp16 pairs (at order 3 the last pair's second coefficient is 0).
vec3 slAverageRadiance(uint i, float theta, vec3 dir) {
  float wz[16];
  slRotateZonal(slThetaRow(1, theta), transpose(slRotation(i)) * (-dir), wz);
  vec3 avg = vec3(0.0);
  for (uint m = 0u; m < (kSlCoeffs + 1u) / 2u; ++m) {
    vec2 r = slIntensityPair(i, 0u, m), g = slIntensityPair(i, 1u, m), b = slIntensityPair(i, 2u, m);
    avg += wz[2u * m] * vec3(r.x, g.x, b.x) + wz[2u * m + 1u] * vec3(r.y, g.y, b.y);
  }
  return avg;
}

#ifdef SL_OBJECT_TERMS
// The hierarchy's tile pass (sl/hierarchy.glsl): Σ L̃ Ṽ of each object's SLs in slIrradianceAt's last
// call (objects ≥ SL_OBJECT_TERMS add to the last entry).
vec3 slObjectTerms[SL_OBJECT_TERMS];
#endif

// Per-light state at this receiver, by slot s of the live list (evaluate.cpp's Prepared): only the
// SLs that reach p after the receiver rules take a slot, so every later loop runs over them alone.
// slWalk fills slLive, slDist and slAdjusted; slIrradianceLive and probe_shadow.glsl's
// slProbeShadowLive read them (sl_shadow.frag: one walk for both terms).
uint slLive[kSpheres];         // the SL's index
float slDist[kSpheres];
vec4 slAdjusted[kSpheres];     // its centre and radius after the receiver rules (slSeenFrom)
float slLogs[kSpheres * 16u];
float slRatio[kSpheres];       // exact Ṽ / Eq. 23 Ṽ of the unoccluded cap, when formed
float slExactOpen[kSpheres];   // the exact Ṽ, used alone when the ratio is not formed
bool slRatioFormed[kSpheres];
vec3 slAverage[kSpheres];
uint slOrder[kSpheres];        // slots, closest first
uint slSlotOf[kSpheres];       // the slot of SL i, for the live ones
uint slObjOf[kSpheres];        // per-object: the slot's object
float slCaps[kPerObject ? kSpheres * 16u : 1u];  // per-object: the cap's projected indicator K over s², by slot

// Eq. 23–24: Ṽ_i = ρ_n · [exp(B) − exp(B + G_i)] from the blockers' summed log B and i's own G_i,
// with the Ratio form; adds L̃ Ṽ to e. `s`: i's slot.
// Eq. 23 needs exp(B) and exp(B + G_i). When `haveExpB`, expB already holds exp(B) (the previous
// SL's exp(B + G), see slIrradianceAt) and that exp is skipped; expWith returns exp(B + G_i).
void slFinish(uint s, in float blockers[16], bool haveExpB, inout float expB[16], out float expWith[16],
              in float yn[16], inout vec3 e) {
  float with[16];
  for (uint k = 0u; k < 16u; ++k) with[k] = blockers[k] + slLogs[s * 16u + k];
  // A loop of 0 or 1 turns, not an if. On llvmpipe it saves nothing: a loop's first body always
  // runs, masked when no lane needs it (README "Loop bodies III"), so every slot pays two slExps
  // there; a GPU that skips an empty loop pays one where the exp is reused.
  for (uint t = haveExpB ? 1u : 0u; t < 1u; ++t) slExp(blockers, expB);
  slExp(with, expWith);
  float v[16];
  for (uint k = 0u; k < 16u; ++k) v[k] = expB[k] - expWith[k];
  float vis = slIrradianceY(v, yn);  // Eq. 24
  vis = slRatioFormed[s] ? vis * slRatio[s] : slExactOpen[s];
  e += slAverage[s] * vis;
#ifdef SL_OBJECT_TERMS
  slObjectTerms[min(slObject(slLive[s]), uint(SL_OBJECT_TERMS) - 1u)] += slAverage[s] * vis;
#endif
}

// The walk (the first loop): the candidates below `limit` that reach p after the receiver rules,
// in candidate order, into slLive / slDist / slAdjusted; returns their count. Every loop over
// candidates or live slots here and below is `do … while` with its body guarded: a `for` runs one
// more body with every lane masked (README "Loop bodies III"); this one walks the four words as one
// set (mask.glsl: max(n, 1) bodies, not n + 4).
uint slWalk(vec3 p, vec3 n, uvec4 candidates, uint limit) {
  uint count = 0u;
  uvec4 rest = candidates;
  do {
    uint i = maskPop(rest);
    if (i < limit) {
      vec4 cr;
      float d;
      if (slSeenFrom(i, p, n, cr, d)) {
        slLive[count] = i;
        slDist[count] = d;
        slAdjusted[count] = cr;
        ++count;
      }
    }
  } while (rest != uvec4(0u));
  return count;
}

// E(p) from the `count` live SLs slWalk left (the second loop on).
vec3 slIrradianceLive(vec3 p, vec3 n, uint count) {
  float zero[16];
  for (uint k = 0u; k < 16u; ++k) zero[k] = 0.0;
  float yn[16];
  shEval16(n, yn);
#ifdef SL_OBJECT_TERMS
  for (uint o = 0u; o < uint(SL_OBJECT_TERMS); ++o) slObjectTerms[o] = vec3(0.0);
#endif
  // Per-object blocking where every live SL is one object's (the kSingleObject tiles): no object is
  // closer, so E_o = exp(0) = 1 and Ṽ_i = X_i (the general path's first turn, fraction 1): an SL
  // needs its exact open cap and L̃ only — not its log, its rotated cap, Y(dir), Y(n) or the ranks
  // (Eq. 21's blocking is formed per object, and this object blocks nobody here).
  const bool kOpenOnly = kPerObject && kSlSingleObject;
  vec3 e = vec3(0.0);
  uint s = 0u;
  do {
    if (s < count) {
      vec3 c = slAdjusted[s].xyz;
      float r = slAdjusted[s].w;
      slOrder[s] = s;
      slSlotOf[min(slLive[s], kSpheres - 1u)] = s;
      float d = slDist[s];
      vec3 dir = (c - p) / d;
      float sn = min(1.0, r / d);
      float theta = asin(sn);
      // The unoccluded cap's Ṽ: exact (slOpenCapExact) and, per-sphere, as Eq. 23 sees it (exp(0) − exp(G_i)).
      float exactOpen = slOpenCapExact(sn, dot(dir, n));
      slExactOpen[s] = exactOpen;
      float lg[16];
      float ydir[16];
      if (!kOpenOnly) {
        shEval16(dir, ydir);
        slRotateZonalY(slThetaRow(0, theta), ydir, lg);
        for (uint k = 0u; k < 16u; ++k) slLogs[s * 16u + k] = lg[k];
      }
      // Eq. 18: the weight rotated to the SL-local direction from its centre to p (§7.1). Here, for
      // the live SLs only, and not in the walk (slWalk): there every candidate pays it (the
      // branch is not skipped), and the reads at the tile's index are no cheaper — measured by the
      // process's CPU time per frame (README "SL per-object blocking and sl.shadow cost"), per-object
      // 0.774 s here against 1.185 s there.
      uint i = slLive[s];
      if (kPerObject) slObjOf[s] = slObject(i);
      slAverage[s] = slAverageRadiance(i, theta, dir);
      if (kOpenOnly) {
        e += slAverage[s] * exactOpen;  // fraction 1, as the general path's first turn
#ifdef SL_OBJECT_TERMS
        slObjectTerms[min(slObjOf[s], uint(SL_OBJECT_TERMS) - 1u)] += slAverage[s] * exactOpen;  // fraction 1, as the general path's first turn
#endif
      } else if (kPerObject) {
        // ⟨f⟩ over the cap = (f · K)/(√(4π) K_00) (evaluate.cpp capAverage), with K/s² kept.
        float cap[16];
        slRotateZonalY(slOpenCapZonal(sn), ydir, cap);
        for (uint k = 0u; k < 16u; ++k) slCaps[s * 16u + k] = cap[k];
      } else {
        // ρ_n · (exp(0) − exp(G_i)) with both exps in closed form: exp(0) is the OL table's first
        // entry; one cap's log never reaches the hybrid's blend (‖f̂‖ ≤ 1.9 < 3,
        // SlProbeShadow.OneCapsLogIsBelowTheHybridsBlend), so slExp would be its OL step alone:
        // e^{G_0 Y_00} (a √(4π) δ_0 + b Ĝ) with ‖Ĝ‖ = ‖(z_1, z_2, z_3)‖ (a rotated ZH keeps each
        // band's norm). Written out rather than through slExp, whose blend square and masked squaring
        // llvmpipe runs even when they are not taken.
        vec4 zl = slThetaRow(0, theta);
        vec2 ab = slOl(sqrt(zl.y * zl.y + zl.z * zl.z + (kOrder > 3u ? zl.w * zl.w : 0.0)));
        float dcLog = exp(min(lg[0] / kSlSqrt4Pi, kSlMaxExponent));
        float eq23Open = SH_A0 * slOl(0.0).x -
                         dcLog * (SH_A0 * ab.x + ab.y * (slIrradianceY(lg, yn) - SH_A0 * lg[0] * yn[0]));
        slRatioFormed[s] = eq23Open > kSlMinOpen;
        slRatio[s] = slRatioFormed[s] ? exactOpen / eq23Open : 0.0;
      }
    }
    ++s;
  } while (s < count);
  if (kOpenOnly) return e;
  // Per-object blocking (§7.2) visits objects nearest first, by the distance from p to the mean of
  // their (unadjusted) sphere centres, ties by id (evaluate.cpp sorts (dist, id)): each object's rank.
  uint rank[kSpheres];
  uint t = 0u;
  do {
    if (t < count) rank[t] = 0u;
    ++t;
  } while (t < count);
  if (kPerObject) {
    // Each object's rank once per pixel, then looked up per live SL: the object loops' index is a
    // loop counter (one read for the 8 lanes), where ranking per live SL read its object's centre
    // per lane and ran the object loop once per live SL. Objects ≤ SLs ≤ kSpheres (every object
    // has ≥ 8 spheres), so objects² bodies per pixel (4 for two characters).
    uint objRank[kSpheres];
    uint objects = min(slObjectCount(), kSpheres);
    uint id = 0u;
    do {
      if (id < objects) {
        float d = length(slObjectCentre(id).xyz - p);
        uint r = 0u;
        uint o = 0u;
        do {
          if (o < objects) {
            vec4 oc = slObjectCentre(o);
            float od = length(oc.xyz - p);
            if (oc.w >= 0.5 && (od < d || (od == d && o < id))) ++r;
          }
          ++o;
        } while (o < objects);
        objRank[id] = r;
      }
      ++id;
    } while (id < objects);
    t = 0u;
    do {
      if (t < count) rank[t] = objRank[min(slObjOf[t], kSpheres - 1u)];
      ++t;
    } while (t < count);
  }
  if (kPerObject) {
    // Per-object blocking, one exp per object (evaluate.hpp "Per-object blocking", which derives
    // it): Ṽ_i = X_i · clamp(⟨exp(C_o)⟩_i, 0, 1), C_o the closer objects' summed logs. No sort: an
    // object's SLs need only the closer objects' sum, so each turn visits the live slots in slot
    // order (the index is the loop counter, the same in all lanes: no per-lane gathers) and takes
    // those of the turn's object; the next turn is the nearest object not yet visited. do…while,
    // since llvmpipe runs a `for` body once more masked (README "What costs what on lavapipe");
    // a pixel with no live SL runs one masked turn of each loop, its sums guarded.
    float closer[16] = zero;
    uint object = 0u, done = 0u;
    bool firstTurn = true;
    t = 0u;
    do {
      if (t < count) object = t == 0u ? rank[t] : min(object, rank[t]);
      ++t;
    } while (t < count);
    do {
      float expCloser[16];
      slExp(closer, expCloser);  // Eq. 21's exp of the closer objects, once for all of o's SLs
      uint next = 0xffffffffu;
      uint s = 0u;
      do {
        uint sc = min(s, kSpheres - 1u);
        bool mine = s < count && rank[sc] == object;
        if (s < count && rank[sc] > object) next = min(next, rank[sc]);
        float capE = 0.0;
        for (uint k = 0u; k < kSlCoeffs; ++k) capE += expCloser[k] * slCaps[sc * 16u + k];
        float area = max(kSlSqrt4Pi * slCaps[sc * 16u], 1e-30);
        // The first turn's object has no closer one: E_o = exp(0) = 1 exactly, as kOpenOnly takes it.
        float fraction = firstTurn ? 1.0 : clamp(capE / area, 0.0, 1.0);
        if (mine) {
          e += slAverage[sc] * (slExactOpen[sc] * fraction);
#ifdef SL_OBJECT_TERMS
          slObjectTerms[min(slObjOf[sc], uint(SL_OBJECT_TERMS) - 1u)] += slAverage[sc] * (slExactOpen[sc] * fraction);
#endif
          for (uint k = 0u; k < kSlCoeffs; ++k) closer[k] += slLogs[sc * 16u + k];
          ++done;
        }
        ++s;
      } while (s < count);
      object = next;
      firstTurn = false;
    } while (done < count);
    return e;
  }
  // Per-sphere: closest first; insertion sort is stable, as evaluate.cpp's stable_sort.
  for (uint a = 1u; a < count; ++a) {
    uint v = slOrder[a];
    uint b = a;
    while (b > 0u && (rank[slOrder[b - 1u]] > rank[v] ||
                      (rank[slOrder[b - 1u]] == rank[v] && slDist[slOrder[b - 1u]] > slDist[v]))) {
      slOrder[b] = slOrder[b - 1u];
      --b;
    }
    slOrder[b] = v;
  }
  // Per-sphere: one pass in that order. An SL's blockers are the SLs before it except those of its
  // own object that intersect it (§6.2). So they are the running sum of the logs visited so far minus the few
  // visited SLs that intersect it (slIntersecting: a mask built once per frame on the CPU): n + n·m
  // vector additions for m intersections per SL, not n(n+1)/2 with a pair test each — §8.3's
  // "O(mn) if results were re-used". (Floats: the sum is formed in another order than
  // evaluate.cpp's, a change at rounding level.)
  // Exp reuse: when neither this SL nor its predecessor skips an intersecting SL, this SL's blockers
  // are the predecessor's plus its log — the predecessor's exp(B + G), the same floats summed the
  // same way — so Eq. 23 costs one exp, not two.
  float run[16] = zero;      // Σ logs of the SLs visited so far
  float expPrev[16] = zero;  // the predecessor's exp(B + G)
  bool prevFull = false;
  uvec4 visited = uvec4(0u);  // SL i at bit i % 32 of word i / 32
  uint a = 0u;
  do {
    if (a < count) {
      uint s = slOrder[a];
      uint i = slLive[s];
      uvec4 skip = slIntersecting(i) & visited;
      float blockers[16] = run;
      uvec4 left = skip;
      do {
        uint j = maskPop(left);
        if (j < kMaskEmpty) {
          uint t = slSlotOf[j];
          for (uint k = 0u; k < kSlCoeffs; ++k) blockers[k] -= slLogs[t * 16u + k];
        }
      } while (left != uvec4(0u));
      bool full = skip == uvec4(0u);
      float expWith[16];
      slFinish(s, blockers, full && prevFull, expPrev, expWith, yn, e);
      expPrev = expWith;
      prevFull = full;
      for (uint k = 0u; k < 16u; ++k) run[k] += slLogs[s * 16u + k];
      visited[i >> 5u] |= 1u << (i & 31u);
    }
    ++a;
  } while (a < count);
  return e;
}

// E(p) (Eq. 14), W/m² per channel for L^c in W/(m²·sr), from the SLs whose bit is set in `candidates`
// (bit i % 32 of word i / 32; the tiled pass gives its tile's list, engine/gi/sl/tiles.hpp). SLs left
// out must be ones the receiver rules cull at p (beyond the influence bound): a culled SL neither
// lights nor blocks, so the sum is the same as over all SLs, term for term and in the same order.
//
// Two loops, because llvmpipe runs both sides of a branch but leaves a loop once none of its 8
// lanes is still in it (README "What costs what on lavapipe"): the walk (slWalk) applies the cheap
// receiver rules to every candidate and keeps the ones that reach p; the second (slIrradianceLive),
// with the rotations and exps, runs as often as the 8 pixels' longest live list, not once per candidate.
vec3 slIrradianceAt(vec3 p, vec3 n, uvec4 candidates) {
  return slIrradianceLive(p, n, slWalk(p, n, candidates, min(slCount(), kSpheres)));
}

// Over every SL (the self-test's receivers, which no tile list culls).
vec3 slIrradianceAt(vec3 p, vec3 n) {
  uvec4 all = uvec4(0u);
  uint count = min(slCount(), kSpheres);
  for (uint w = 0u; w < 4u; ++w) {
    uint bits = uint(clamp(int(count) - int(32u * w), 0, 32));
    all[w] = bits == 32u ? 0xffffffffu : (1u << bits) - 1u;
  }
  return slIrradianceAt(p, n, all);
}

#endif  // BOUNCE_SL_GLSL
