// probes/probe_tiles.glsl's C++ face (the same source, compiled against glm as node.cpp does): the
// octahedral map, the tile's border rule and tap placement, and the tiles' interpolation error on a
// closed-form SH. The GPU test (gpu_match_test.cpp ProbeGpu.Tiles…) bounds the pass by
// tileIrradianceError, which uses these same functions, so it cannot catch a wrong rule here.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "engine/gi/probes/node.hpp"
#include "engine/math/sh.hpp"

using namespace bounce;

namespace glsl {
using namespace glm;
#include "shaders/probes/probe_tiles.glsl"
}  // namespace glsl

namespace {

constexpr int kN = glsl::PROBE_TILE_N, kTile = glsl::PROBE_TILE;

// Unit directions spread over the sphere (Fibonacci lattice) plus the axes and the octahedron's
// edges, where the map folds.
std::vector<glm::vec3> directions() {
  std::vector<glm::vec3> d;
  constexpr int kCount = 4096;
  for (int i = 0; i < kCount; ++i) {
    const float z = 1.0f - (2.0f * float(i) + 1.0f) / kCount, r = std::sqrt(1.0f - z * z);
    const float phi = 2.39996323f * float(i);
    d.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  for (const glm::vec3 a : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) d.push_back(a), d.push_back(-a);
  for (float s : {-1.0f, 1.0f})
    for (float t : {-1.0f, 1.0f}) {
      d.push_back(glm::normalize(glm::vec3(s, t, 0.0f)));
      d.push_back(glm::normalize(glm::vec3(s, 0.0f, t)));
      d.push_back(glm::normalize(glm::vec3(0.0f, s, t)));
    }
  return d;
}

// The angle between unit vectors from their chord (acos of a dot near 1 loses half the digits).
float angle(glm::vec3 a, glm::vec3 b) { return 2.0f * std::asin(std::min(glm::length(a - b) * 0.5f, 1.0f)); }

// Interior texel i's centre on the octahedral square, per axis (probe_tiles.glsl probeTileDirection).
float centre(int i) { return (float(i) - 0.5f) / float(kN) * 2.0f - 1.0f; }

}  // namespace

// decode(encode(n)) = n to float rounding (a few ulps of the normalisation), inside the square.
TEST(ProbeTiles, OctahedralRoundTrip) {
  float worst = 0.0f;
  for (const glm::vec3 n : directions()) {
    const glm::vec2 o = glsl::probeOctEncode(n);
    EXPECT_LE(std::max(std::abs(o.x), std::abs(o.y)), 1.0f) << n.x << " " << n.y << " " << n.z;
    worst = std::max(worst, glm::length(glsl::probeOctDecode(o) - n));
  }
  EXPECT_LT(worst, 1e-6f);
}

// The square's edges are the map's seams: (1, v) and (1, −v) are one direction (likewise the other
// three edges), so the sphere continues past edge x = 1 at (2 − x, −y), past x = −1 at (−2 − x, −y),
// and the same with x and y swapped; past a corner both folds apply (the opposite corner). A border
// texel must hold the direction at its own extended centre folded that way — derived here from the
// geometry, not from probeTileSource — to within a texel's angle (it matches exactly when the rule
// is DDGI's; a clamp-to-edge copy is off by up to 90° along the edges).
TEST(ProbeTiles, BorderTexelsHoldTheirExtendedPositionsDirection) {
  for (int i = 0; i <= 64; ++i) {
    const float v = -1.0f + 2.0f * float(i) / 64.0f;
    EXPECT_LT(angle(glsl::probeOctDecode({1.0f, v}), glsl::probeOctDecode({1.0f, -v})), 1e-6f);
    EXPECT_LT(angle(glsl::probeOctDecode({-1.0f, v}), glsl::probeOctDecode({-1.0f, -v})), 1e-6f);
    EXPECT_LT(angle(glsl::probeOctDecode({v, 1.0f}), glsl::probeOctDecode({-v, 1.0f})), 1e-6f);
    EXPECT_LT(angle(glsl::probeOctDecode({v, -1.0f}), glsl::probeOctDecode({-v, -1.0f})), 1e-6f);
  }
  // A texel's angle: the largest between neighbouring interior texels' directions.
  float texel = 0.0f;
  for (int y = 1; y <= kN; ++y)
    for (int x = 1; x <= kN; ++x) {
      const glm::vec3 d = glsl::probeTileDirection({x, y});
      if (x < kN) texel = std::max(texel, angle(d, glsl::probeTileDirection({x + 1, y})));
      if (y < kN) texel = std::max(texel, angle(d, glsl::probeTileDirection({x, y + 1})));
    }
  const auto fold = [](glm::vec2 o) {
    if (o.x > 1.0f) o = {2.0f - o.x, -o.y};
    if (o.x < -1.0f) o = {-2.0f - o.x, -o.y};
    if (o.y > 1.0f) o = {-o.x, 2.0f - o.y};
    if (o.y < -1.0f) o = {-o.x, -2.0f - o.y};
    return o;
  };
  int border = 0;
  float worst = 0.0f;
  for (int y = 0; y < kTile; ++y)
    for (int x = 0; x < kTile; ++x) {
      if (x > 0 && x <= kN && y > 0 && y <= kN) {  // interior: its own centre
        EXPECT_LT(angle(glsl::probeTileDirection({x, y}), glsl::probeOctDecode({centre(x), centre(y)})), 1e-6f);
        continue;
      }
      ++border;
      const glm::vec3 want = glsl::probeOctDecode(fold({centre(x), centre(y)}));
      const float a = angle(glsl::probeTileDirection({x, y}), want);
      worst = std::max(worst, a);
      EXPECT_LE(a, texel) << "border texel " << x << "," << y;
    }
  EXPECT_EQ(border, 4 * (kN + 1));
  EXPECT_LT(worst, 1e-5f);  // DDGI's copy rule is exactly the fold
}

// Every tap lands between the border texels' centres (0.5 … N + 1.5 would be past them): the
// bilinear footprint never leaves the probe's square, so no neighbour probe's texel bleeds in.
TEST(ProbeTiles, TapCoordinatesStayInsideTheSquare) {
  for (const glm::vec3 n : directions()) {
    const glm::vec2 c = glsl::probeTileCoord(n);
    EXPECT_GE(std::min(c.x, c.y), 1.0f);
    EXPECT_LE(std::max(c.x, c.y), float(kN + 1));
  }
  // And the interior texel centres map to themselves.
  for (int y = 1; y <= kN; ++y)
    for (int x = 1; x <= kN; ++x) {
      const glm::vec2 c = glsl::probeTileCoord(glsl::probeTileDirection({x, y}));
      EXPECT_NEAR(c.x, float(x) + 0.5f, 1e-4f);
      EXPECT_NEAR(c.y, float(y) + 0.5f, 1e-4f);
    }
}

// A single-direction light: radiance SH L_lm = Y_lm(d) (the projection of δ(ω − d)), so
// E(n) = Σ_l Â_l (2l+1)/(4π) P_l(d·n) (Ramamoorthi & Hanrahan 2001, eq. 7 with the addition
// theorem), peak at n = d: π/(4π) + (2π/3)·3/(4π) + (π/4)·5/(4π) = 1.0625 at order 3 (0.75 at order 2).
// The tiles' bilinear interpolation error must stay under kTileErrorOfPeak of that peak for d
// anywhere: on an axis, across the octahedral seam (the lower hemisphere's fold) and in general
// position. With a wrong border rule a tap near an edge blends directions far apart on the sphere
// and the error rises to a large part of the peak (E changes by ~peak across 90°).
TEST(ProbeTiles, InterpolationErrorOfASingleDirectionLight) {
  constexpr double kPi = 3.14159265358979323846;
  // Measured largest ratio (printed below): 7.0 % at order 3 (d on the z axis, where E is sharpest
  // in the square), 5.6 % at order 2; a delta light is the sharpest E a probe can hold, so a baked
  // probe's is below this. 8 % bounds both; a misplaced tap or border is off by a large part of the
  // peak instead.
  constexpr double kTileErrorOfPeak = 0.08;
  for (int order : {2, 3}) {
    const double peak = 0.25 + 0.5 + (order == 3 ? 0.3125 : 0.0);
    double worstRatio = 0.0;
    for (const glm::vec3 d : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, 2, 3)),
                              glm::normalize(glm::vec3(1, 0.3f, -0.2f)), glm::normalize(glm::vec3(-0.5f, 0.5f, -1)),
                              glm::normalize(glm::vec3(1, 1, 0))}) {
      gi::probes::ProbeVolume v;
      v.order = order;
      v.grid.count = glm::ivec3(1);
      v.valid = {1u};
      v.moments.assign(std::size_t(gi::probes::kVisBins), glm::vec2(1.0f, 1.0f));
      const auto y = sh::evalBasis<float>(order, d);
      for (int i = 0; i < v.coeffs(); ++i) v.sh.push_back(glm::vec3(y[std::size_t(i)]));
      // The closed form's peak is what the library evaluates at n = d.
      const float atD = sh::evalIrradiance<glm::vec3, float>(std::span<const glm::vec3>(v.sh), d).x;
      EXPECT_NEAR(atD, peak, 1e-5);
      const double e = gi::probes::tileIrradianceError(v);
      worstRatio = std::max(worstRatio, e / peak);
      EXPECT_LT(e, kTileErrorOfPeak * peak) << "order " << order << " d " << d.x << " " << d.y << " " << d.z;
      EXPECT_GT(e, 0.0);  // the measure is live (E is not bilinear in the octahedral square)
    }
    std::printf("order %d: largest tile interpolation error %.4f of the peak E = %.4f (pi/4 E_00 %.4f)\n", order,
                worstRatio, peak, kPi / 4.0);
  }
}
