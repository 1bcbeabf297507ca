#include "engine/math/sampling.hpp"

#include <algorithm>
#include <cmath>

#include "engine/math/geometry.hpp"

namespace bounce::math {

Pcg32::Pcg32(std::uint64_t seed, std::uint64_t stream) {
  // pcg32_srandom_r: the increment must be odd; two steps mix the seed into the state.
  inc_ = (stream << 1u) | 1u;
  nextU32();
  state_ += seed;
  nextU32();
}

Pcg32 Pcg32::fromIndex(std::uint64_t index) {
  // splitmix64 (Steele, Lea, Flood 2014) finaliser: a bijection that scatters nearby indices.
  std::uint64_t z = index + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return Pcg32(z, index);
}

std::uint32_t Pcg32::nextU32() {
  const std::uint64_t old = state_;
  state_ = old * 6364136223846793005ull + inc_;
  const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
  const auto rot = static_cast<std::uint32_t>(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

float Pcg32::nextFloat() {
  // Top 24 bits: exactly representable, so the result is < 1 (a 32-bit value times 2^-32 can
  // round to 1.0f).
  return static_cast<float>(nextU32() >> 8) * 0x1p-24f;
}

glm::vec3 Pcg32::nextFloat3() {
  const float z = nextFloat(), y = nextFloat(), x = nextFloat();  // sequenced: see the header
  return {x, y, z};
}

double Pcg32::nextDouble() {
  const std::uint64_t hi = nextU32() >> 5;  // 27 bits
  const std::uint64_t lo = nextU32() >> 6;  // 26 bits
  return static_cast<double>((hi << 26) | lo) * 0x1p-53;
}

glm::dvec3 uniformSphere(const glm::dvec2& u) {
  const double z = 1.0 - 2.0 * u.x;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::dvec3 uniformHemisphere(const glm::dvec2& u, const glm::dvec3& n) {
  const double z = u.x;  // cosθ uniform in [0,1) gives uniform solid angle
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * u.y;
  return orthonormalBasis(n).toWorld({r * std::cos(phi), r * std::sin(phi), z});
}

namespace {
glm::dvec2 concentricDisk(const glm::dvec2& u) {
  const double a = 2.0 * u.x - 1.0, b = 2.0 * u.y - 1.0;
  if (a == 0.0 && b == 0.0) return {0.0, 0.0};
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = (kPi / 4.0) * (b / a);
  } else {
    r = b;
    phi = kPi / 2.0 - (kPi / 4.0) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}
}  // namespace

glm::dvec3 cosineHemisphere(const glm::dvec2& u, const glm::dvec3& n) {
  const glm::dvec2 d = concentricDisk(u);
  const double z = std::sqrt(std::max(0.0, 1.0 - d.x * d.x - d.y * d.y));
  return orthonormalBasis(n).toWorld({d.x, d.y, z});
}

std::vector<glm::dvec2> stratified2D(int n, Pcg32& rng) {
  std::vector<glm::dvec2> points;
  if (n <= 0) return points;
  points.reserve(static_cast<std::size_t>(n) * n);
  const double inv = 1.0 / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double jx = rng.nextDouble(), jy = rng.nextDouble();
      points.push_back({(i + jx) * inv, (j + jy) * inv});
    }
  return points;
}

glm::dvec3 fibonacciSphere(int i, int n) {
  const double goldenRatio = (1.0 + std::sqrt(5.0)) / 2.0;
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * (i / goldenRatio - std::floor(i / goldenRatio));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

std::vector<glm::dvec3> fibonacciSphere(int n) {
  std::vector<glm::dvec3> points;
  for (int i = 0; i < n; ++i) points.push_back(fibonacciSphere(i, n));
  return points;
}

}  // namespace bounce::math
