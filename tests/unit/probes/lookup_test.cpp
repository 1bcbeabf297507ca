// CPU lookups on hand-made volumes: exact interpolation cases and the binary format.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.hpp"
#include "engine/gi/probes/probe_volume.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"

using namespace bounce;
using namespace bounce::gi::probes;

namespace {

// Interpolation is a weighted sum of 8 floats with weights that sum to 1: a few float ulps.
constexpr float kInterpTol = 1e-5f;
// Chebyshev weight of a probe deep behind an occluder: σ²/(σ² + 0.3²) = 1e-4/0.0901, cubed
// ≈ 1.4e-9; a bound 7× above it still fails a test that forgot the visibility term (weight ~1/2).
constexpr float kOccludedWeightMax = 1e-8f;
// The remaining probe renormalised to weight 1: a division of a float by itself plus a sum with
// a 1e-9 term, within one ulp of 1 (1.2e-7); 1e-6 allows ~8 ulps.
constexpr float kRenormalisedTol = 1e-6f;

// 2×2×2 probes 1 m apart, every probe open (mean hit distance 10 m, so Chebyshev is 1) and a
// distinct radiance SH per probe; no bias, so the lookup point is the receiver itself.
ProbeVolume cube() {
  ProbeVolume v;
  v.grid.count = {2, 2, 2};
  v.grid.spacing = 1.0f;
  v.order = 3;
  v.bias = {0.0f, 0.0f};
  for (int p = 0; p < 8; ++p)
    for (int i = 0; i < 9; ++i) v.sh.push_back(glm::vec3(1.0f + p, 0.5f * p - 0.1f * i, 0.2f * i) * (i == 0 ? 2.0f : 0.1f));
  v.moments.assign(8 * kVisBins, glm::vec2(10.0f, 100.0f));
  v.valid.assign(8, 1u);
  return v;
}

std::vector<glm::vec3> average(const ProbeVolume& v, std::initializer_list<int> probes) {
  std::vector<glm::vec3> out(9, glm::vec3(0.0f));
  for (int p : probes)
    for (int i = 0; i < 9; ++i) out[i] += v.sh[p * 9 + i] / float(probes.size());
  return out;
}

}  // namespace

TEST(ProbeLookup, ReceiverExactlyBetweenTwoProbesIsTheirAverage) {
  const ProbeVolume v = cube();
  // Midpoint of the edge from probe 0 (0,0,0) to probe 1 (1,0,0); normal ⟂ the edge, so both
  // backface terms are equal and the weights are ½, ½.
  const glm::vec3 x(0.5f, 0.0f, 0.0f), n(0.0f, 1.0f, 0.0f);
  const auto got = v.radianceSH(x, n);
  const auto want = average(v, {0, 1});
  for (int i = 0; i < 9; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[i][c], want[i][c], kInterpTol);
  const glm::vec3 e = v.irradiance(x, n), we = sh::evalIrradiance<glm::vec3, float>(want, n);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], we[c], kInterpTol * 10.0f);
}

TEST(ProbeLookup, ReceiverAtAFaceCentreIsTheAverageOfFour) {
  const ProbeVolume v = cube();
  const auto got = v.radianceSH({0.5f, 0.5f, 0.0f}, {0.0f, 0.0f, 1.0f});  // face z = 0: probes 0..3
  const auto want = average(v, {0, 1, 2, 3});
  for (int i = 0; i < 9; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[i][c], want[i][c], kInterpTol);
}

TEST(ProbeLookup, AtAProbeItsOwnValueAndOutsideTheGridClamped) {
  const ProbeVolume v = cube();
  const auto at = v.radianceSH({1.0f, 1.0f, 1.0f});
  EXPECT_EQ(at[0], v.sh[7 * 9]);
  const auto beyond = v.radianceSH({5.0f, 5.0f, 5.0f});
  EXPECT_EQ(beyond[0], v.sh[7 * 9]);
}

TEST(ProbeLookup, InvalidProbesGetNoWeightAndAllInvalidGivesZero) {
  ProbeVolume v = cube();
  v.valid[1] = 0u;
  const auto got = v.radianceSH({0.5f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
  EXPECT_EQ(got[0], v.sh[0]);  // probe 1 dropped, probe 0 renormalised to weight 1
  v.valid.assign(8, 0u);
  EXPECT_EQ(v.irradiance({0.5f, 0.5f, 0.5f}, {0, 1, 0}), glm::vec3(0.0f));
}

TEST(ProbeLookup, ChebyshevCutsAProbeBehindAnOccluder) {
  ProbeVolume v = cube();
  // Probe 1 sees a wall 0.2 m away towards −x, σ = 1 cm: the receiver at 0.5 m is far behind it.
  const int bin = visBin(glm::vec3(-1.0f, 0.0f, 0.0f));
  v.moments[1 * kVisBins + bin] = glm::vec2(0.2f, 0.2f * 0.2f + 1e-4f);
  int probe[8];
  float weight[8];
  v.weights({0.5f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, glm::vec3(0.0f), probe, weight);
  // Chebyshev: σ²/(σ² + 0.3²) = 1e-4/0.0901, cubed ≈ 1.4e-9 → probe 1's share is below 1e-8.
  EXPECT_EQ(probe[1], 1);
  EXPECT_LT(weight[1], kOccludedWeightMax);
  EXPECT_NEAR(weight[0], 1.0f, kRenormalisedTol);
}

TEST(ProbeFormat, RoundTripsAndRejectsEveryCorruption) {
  ProbeVolume v = cube();
  EXPECT_FALSE(deserialize(serialize(v), "p.bin").hasDirMap());  // a volume without direction maps stays without
  for (std::size_t i = 0; i < 8 * std::size_t(math::kOctMapTexels) * 3; ++i)
    v.dirMap.push_back(glm::packHalf1x16(0.01f * float(i % 997)));
  ASSERT_TRUE(v.hasDirMap());
  const auto bytes = serialize(v);
  const ProbeVolume back = deserialize(bytes, "p.bin");
  EXPECT_EQ(back.dirMap, v.dirMap);
  EXPECT_EQ(back.sh, v.sh);
  EXPECT_EQ(back.moments, v.moments);
  EXPECT_EQ(back.valid, v.valid);
  EXPECT_EQ(back.grid.count, v.grid.count);
  EXPECT_EQ(back.order, v.order);
  // Every single flipped byte and every truncation is caught (magic, header checks or checksum).
  for (std::size_t i = 0; i < bytes.size(); i += 7) {
    auto bad = bytes;
    bad[i] ^= 0x5a;
    EXPECT_THROW(deserialize(bad, "p.bin"), InputError) << "byte " << i;
  }
  for (std::size_t n : {std::size_t(0), std::size_t(10), bytes.size() - 1})
    EXPECT_THROW(deserialize(std::span(bytes).first(n), "p.bin"), InputError);
}

// probeVisBin finds the φ column from the octant (signs, |x| vs |y|) instead of atan2: the bins
// must be the equal-area map's ⌊8·φ/2π⌋ (what the bake's stratified rays were binned by before),
// checked against atan2 in double on 200 000 random directions (a direction within 1e-6 rad of an
// octant edge may fall on either side; none is expected at this count, and the test counts them
// rather than skipping), plus the axes and the diagonals exactly.
TEST(ProbeLookup, VisBinColumnIsTheAtanOctant) {
  auto atanBin = [](const glm::dvec3& d) {
    const double u = std::clamp((1.0 - d.z) * 0.5, 0.0, 1.0);
    double phi = std::atan2(d.y, d.x);
    if (phi < 0.0) phi += 2.0 * math::kPi;
    const int i = std::min(int(u * 8.0), 7), j = std::min(int(phi / (2.0 * math::kPi) * 8.0), 7);
    return i * 8 + j;
  };
  std::uint64_t state = 0x853c49e6748fea9bull;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * 0x1.0p-53;
  };
  int edge = 0;
  for (int k = 0; k < 200000; ++k) {
    const double z = 2.0 * next() - 1.0, phi = 2.0 * math::kPi * next(), r = std::sqrt(1.0 - z * z);
    const glm::vec3 d(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
    const glm::dvec3 dd(d);
    const double phiF = std::fmod(std::atan2(dd.y, dd.x) + 2.0 * math::kPi, 2.0 * math::kPi);
    const double toEdge = std::abs(phiF / (math::kPi / 4.0) - std::round(phiF / (math::kPi / 4.0))) * (math::kPi / 4.0);
    if (toEdge < 1e-6) {
      ++edge;
      continue;
    }
    ASSERT_EQ(visBin(d), atanBin(dd)) << d.x << " " << d.y << " " << d.z;
  }
  EXPECT_LE(edge, 2);
  // Axes and diagonals: the column whose edge φ they start (φ = 0, π/4, …, 7π/4 → 0 … 7).
  const float h = std::sqrt(0.5f);
  const glm::vec3 edges[8] = {{1, 0, 0}, {h, h, 0}, {0, 1, 0}, {-h, h, 0}, {-1, 0, 0}, {-h, -h, 0}, {0, -1, 0}, {h, -h, 0}};
  for (int j = 0; j < 8; ++j) EXPECT_EQ(visBin(edges[j]), 4 * 8 + j) << j;
  EXPECT_EQ(visBin(glm::vec3(0, 0, 1)), 0);       // x = y = 0: column 0 (atan2(0, 0) = 0)
  EXPECT_EQ(visBin(glm::vec3(0, 0, -1)), 7 * 8);  // u = 1 clamps to row 7
}
