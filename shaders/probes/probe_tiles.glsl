// Per-probe irradiance tiles (DDGI's layout: Majercik et al. 2019, JCGT 8(2), §3.1 and Fig. 4):
// each probe's E(n) = Σ_lm Â_l L_lm Y_lm(n) (sh.glsl shIrradiance9) stored over an octahedral map
// of the sphere of normals (Cigolle et al. 2014, "A Survey of Efficient Representations for
// Independent Unit Vectors", JCGT 3(2), §3.4) in a PROBE_TILE_N² texel square with a one-texel
// border, RGBA16F, written each frame by probes/tiles.comp and read by probes.frag with ONE
// hardware-bilinear tap per probe instead of the probe's 8 packed SH words: on llvmpipe an
// indexed uniform word is a per-lane load, and the 8 a probe were ~0.3 of the lighting pass; an
// RGBA16F bilinear tap of this small, cache-resident image costs less (README "Probes cost,
// session 11"). E is linear in L, so Σ_k w_k E_k(n) is the E of Σ_k w_k L_k: the same sum the SH
// path forms, up to the tile's interpolation error (bounded there) and fp16.
// Shared by the GPU (tiles.comp, probes.frag) and the C++ tests (compiled against glm), so keep to
// the GLSL/C++ common subset (see common/sh.glsl).
#ifndef BOUNCE_PROBE_TILES_GLSL
#define BOUNCE_PROBE_TILES_GLSL

const int PROBE_TILE_N = 14;                 // interior texels per side
const int PROBE_TILE = PROBE_TILE_N + 2;     // with the border: a probe's square in the image

// Unit vector → the octahedral square [-1, 1]² (upper hemisphere inside |u| + |v| ≤ 1, the lower
// folded out over the diagonals).
vec2 probeOctEncode(vec3 n) {
  float s = abs(n.x) + abs(n.y) + abs(n.z);
  vec2 o = vec2(n.x / s, n.y / s);
  if (n.z < 0.0f) {
    float sx = o.x >= 0.0f ? 1.0f : -1.0f;
    float sy = o.y >= 0.0f ? 1.0f : -1.0f;
    o = vec2((1.0f - abs(o.y)) * sx, (1.0f - abs(o.x)) * sy);
  }
  return o;
}

vec3 probeOctDecode(vec2 o) {
  vec3 n = vec3(o.x, o.y, 1.0f - abs(o.x) - abs(o.y));
  if (n.z < 0.0f) {
    float sx = o.x >= 0.0f ? 1.0f : -1.0f;
    float sy = o.y >= 0.0f ? 1.0f : -1.0f;
    n = vec3((1.0f - abs(o.y)) * sx, (1.0f - abs(o.x)) * sy, n.z);
  }
  return normalize(n);
}

// The interior texel (1…N per axis) whose value tile texel t (0…N+1) holds: itself inside; on the
// border DDGI's copy rule, the texel across the octahedral fold (each edge of the square folds onto
// itself mirrored, each corner onto the opposite corner), so bilinear taps across the edge
// interpolate between directions that are neighbours on the sphere.
ivec2 probeTileSource(ivec2 t) {
  const int N = PROBE_TILE_N;
  bool bx = t.x == 0 || t.x == N + 1;
  bool by = t.y == 0 || t.y == N + 1;
  if (bx && by) return ivec2(t.x == 0 ? N : 1, t.y == 0 ? N : 1);
  if (by) return ivec2(N + 1 - t.x, t.y == 0 ? 1 : N);
  if (bx) return ivec2(t.x == 0 ? 1 : N, N + 1 - t.y);
  return t;
}

// The normal whose E tile texel t stores: its source texel's centre on the square.
vec3 probeTileDirection(ivec2 t) {
  ivec2 s = probeTileSource(t);
  vec2 o = vec2((float(s.x) - 0.5f) / float(PROBE_TILE_N) * 2.0f - 1.0f,
                (float(s.y) - 0.5f) / float(PROBE_TILE_N) * 2.0f - 1.0f);
  return probeOctDecode(o);
}

// Where a tap for normal n lands inside a probe's square, in texels from its corner (texel i's centre
// at i + 0.5): interior texel i (1…N) is centred on o = (i − 0.5)/N·2 − 1.
vec2 probeTileCoord(vec3 n) {
  vec2 o = probeOctEncode(n);
  return vec2(1.0f + (o.x * 0.5f + 0.5f) * float(PROBE_TILE_N), 1.0f + (o.y * 0.5f + 0.5f) * float(PROBE_TILE_N));
}

// The square of the probe at grid corner c: PROBE_TILE·(c.x, c.y + count.y·c.z) in an image of
// PROBE_TILE·count.x × PROBE_TILE·count.y·count.z texels (the probe images' row layout, probe_sh.glsl:
// probe p = x + count.x·row). From c, not p: a per-lane integer division is scalarised on llvmpipe.
ivec2 probeTileOrigin(ivec3 c, ivec3 count) {
  return ivec2(PROBE_TILE * c.x, PROBE_TILE * (c.y + count.y * c.z));
}

#endif  // BOUNCE_PROBE_TILES_GLSL
