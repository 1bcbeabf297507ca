#pragma once
// Deterministic random numbers and sphere/hemisphere sampling. Every sampler maps a point u of
// the unit square [0,1)² to a direction; pdfs are per steradian. Bakes seed a generator from an
// index (texel, probe, sample batch) so results do not depend on thread scheduling.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::math {

// PCG32 (O'Neill 2014, "PCG: A family of simple fast space-efficient statistically good
// algorithms for random number generation", pcg32_random_r / pcg32_srandom_r): 64-bit LCG state,
// 32-bit output by xorshift-high + random rotation. `stream` selects one of 2^63 sequences.
class Pcg32 {
 public:
  Pcg32(std::uint64_t seed, std::uint64_t stream = 0);
  // A generator for work item `index` (splitmix64 of the index as seed, the index as stream), so
  // neighbouring indices get unrelated sequences.
  static Pcg32 fromIndex(std::uint64_t index);

  std::uint32_t nextU32();
  // Uniform in [0, 1): 32 random bits for float (largest value 1 - 2^-24), 53 for double.
  float nextFloat();
  double nextDouble();
  // Three floats as (x, y, z), drawn in the order z, y, x. Use this, never
  // glm::vec3(nextFloat(), nextFloat(), nextFloat()): function arguments are unsequenced, GCC drew
  // them right to left and clang left to right, so the two compilers used different samples (a test
  // passed under one and failed under the other). z first keeps every sample GCC builds drew before.
  glm::vec3 nextFloat3();
  glm::dvec2 next2D() { const double a = nextDouble(); return {a, nextDouble()}; }

 private:
  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 0;
};

inline constexpr double kPi = 3.14159265358979323846;

// Uniform on the sphere, pdf 1/(4π): z = 1 - 2u.x, φ = 2π u.y.
glm::dvec3 uniformSphere(const glm::dvec2& u);
inline constexpr double uniformSpherePdf() { return 1.0 / (4.0 * kPi); }

// Uniform on the hemisphere around unit normal n, pdf 1/(2π).
glm::dvec3 uniformHemisphere(const glm::dvec2& u, const glm::dvec3& n);
inline constexpr double uniformHemispherePdf() { return 1.0 / (2.0 * kPi); }

// Cosine-weighted around unit normal n (Malley's method: uniform disk lifted to the hemisphere,
// concentric map of Shirley & Chiu 1997 so strata stay compact), pdf cosθ/π.
glm::dvec3 cosineHemisphere(const glm::dvec2& u, const glm::dvec3& n);
inline double cosineHemispherePdf(double cosTheta) { return cosTheta > 0.0 ? cosTheta / kPi : 0.0; }

// n×n jittered strata of the unit square, row-major (n² points), each jittered by rng.
std::vector<glm::dvec2> stratified2D(int n, Pcg32& rng);

// Point i of n on the spherical Fibonacci lattice (González 2010, "Measurement of areas on a sphere
// using Fibonacci and latitude–longitude lattices"): z_i = 1 - (2i+1)/n, φ_i = 2π i/Φ. Nearly
// uniform, deterministic, any n; good for "check this along many directions".
glm::dvec3 fibonacciSphere(int i, int n);
std::vector<glm::dvec3> fibonacciSphere(int n);

}  // namespace bounce::math
