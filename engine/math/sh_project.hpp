#pragma once
// Projection c_i = ∫_S² f(ω) Y_i(ω) dω of a function or a cube map onto SH of a given order.
//
// Three estimators, from cheapest-to-write to exact:
//  - projectMonteCarlo: stratified uniform sphere samples (n×n jittered strata, deterministic seed),
//    error ~1/N for smooth f in 2D (Owen 1997); for arbitrary callables (a bake's ray-cast radiance);
//  - projectQuadrature: exact for f a polynomial of degree <= `degree` (band-limited f, products);
//  - projectCubeMap: texel values times their exact solid angles.
// V is the value type: double (scalar) or glm::dvec3 (RGB).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/math/quadrature.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_eval.hpp"

namespace bounce::sh {

// f: glm::dvec3 (unit direction) -> V. Uses samplesPerAxis² samples, each of weight 4π/N.
template <typename F>
auto projectMonteCarlo(const F& f, int order, int samplesPerAxis, std::uint64_t seed) {
  using V = decltype(f(glm::dvec3(0.0)));
  checkOrder(order);
  math::Pcg32 rng(seed);
  const auto samples = math::stratified2D(samplesPerAxis, rng);
  std::vector<V> c(static_cast<std::size_t>(coeffCount(order)), V(0));
  if (samples.empty()) return c;
  std::array<double, kMaxCoeffs> y{};
  for (const auto& u : samples) {
    const glm::dvec3 d = math::uniformSphere(u);
    evalBasis<double>(order, d, y);
    const V value = f(d);
    for (std::size_t i = 0; i < c.size(); ++i) c[i] += value * y[i];
  }
  const double w = 4.0 * math::kPi / static_cast<double>(samples.size());
  for (auto& ci : c) ci *= w;
  return c;
}

// Exact (to rounding) when f is a polynomial of degree <= `degree` in the direction's components,
// e.g. a function band-limited to l <= degree; for other f, a high-order deterministic rule.
template <typename F>
auto projectQuadrature(const F& f, int order, int degree) {
  using V = decltype(f(glm::dvec3(0.0)));
  checkOrder(order);
  // The integrand f·Y_i has degree up to degree + order - 1.
  const auto nodes = math::sphereQuadrature(degree + order - 1);
  std::vector<V> c(static_cast<std::size_t>(coeffCount(order)), V(0));
  std::array<double, kMaxCoeffs> y{};
  for (const auto& node : nodes) {
    evalBasis<double>(order, node.dir, y);
    const V value = f(node.dir) * node.weight;
    for (std::size_t i = 0; i < c.size(); ++i) c[i] += value * y[i];
  }
  return c;
}

// Cube maps. Faces in Vulkan order +X, -X, +Y, -Y, +Z, -Z; texel (x, y) of a face, x to the right,
// y downwards, as the Vulkan spec's cube map face selection table (§16.5.4) lays out s and t.
inline constexpr int kCubeFaces = 6;

// Unit direction through the centre of texel (x, y) of `face` in a size×size face.
glm::dvec3 cubeTexelDirection(int face, int x, int y, int size);

// Exact solid angle (sr) of texel (x, y) of a size×size face: with A(u, v) = atan2(uv, √(u²+v²+1))
// the solid angle of the face rectangle [0,u]×[0,v] at unit distance, the texel [u0,u1]×[v0,v1]
// subtends A(u0,v0) - A(u0,v1) - A(u1,v0) + A(u1,v1). Same on every face; sums to 4π.
double cubeTexelSolidAngle(int x, int y, int size);

// texels: 6·size·size linear RGB values, face-major then row-major (face, y, x).
// Throws InternalError when the span does not hold 6·size² values or size < 1.
std::vector<glm::dvec3> projectCubeMap(std::span<const glm::vec3> texels, int size, int order);

}  // namespace bounce::sh
