#pragma once
// DNRT at run time on the CPU: exactly what shaders/dnrt/dnrt.frag computes, so tests can check
// the bake and the runtime math together (and the shader against this).
//
//   L_DNRT(r) = ρ_r (n_o·n_r)₊ · s(r) · Σ_j c_j M_j(r)   per RGB channel        (Eq. 16, Listing 2)
//
// with the Eq. 16 typesetting slip read as a product (as Eq. 9 and Listing 2 have it), n_o =
// normalize(o − r) in world space, c_j the irradiance SH at o rotated into the object's frame
// (§5.2.1), M_j the trilinearly filtered field at r's position in units of R, clamped to the inner
// cube (Listing 2's texture clamping), and s(r) the §5.2.2 fall-off over the outer shell:
//   u = max(|q_x|, |q_y|, |q_z|) (q = local offset from o in units of R; u measures the nested cubes),
//   s = 1 for u <= inner,  s = ((inner/u)² − (inner/outer)²) / (1 − (inner/outer)²) for inner < u < outer,
//   s = 0 beyond outer.
// s is the inverse-square law shifted to reach 0 at the outer boundary: continuous (1 at the inner
// boundary, 0 at the outer one) and decreasing in between.
#include <array>
#include <optional>
#include <span>

#include <glm/glm.hpp>

#include "engine/gi/dnrt/field.hpp"
#include "engine/gi/placement.hpp"

namespace bounce::gi::dnrt {

// One object's field placed in the world (engine/gi/placement.hpp, shared with RTF): local → world
// is `world` (rotation, uniform scale, translation, a reflection allowed; a non-uniform scale uses
// its largest axis for R, an approximation).
using gi::Placement;
// Throws InternalError when `world` is singular or not finite.
inline Placement place(const Field& field, const glm::mat4& world) {
  return gi::place(field.centre, field.radius, world, "dnrt::place");
}
// nullopt where place() throws (gi::tryPlace): a frame skips such an object's GI.
inline std::optional<Placement> tryPlace(const Field& field, const glm::mat4& world) {
  return gi::tryPlace(field.centre, field.radius, world);
}

// c_j in the object's frame: the world irradiance SH (9 coefficients) rotated by the inverse of
// the object's rotation, so Σ c_local_j Y_j(n_local) = Σ c_world_j Y_j(R n_local) (§5.2.1).
std::array<glm::vec3, 9> toLocal(const std::array<glm::vec3, 9>& worldIrradiance, const glm::mat3& localToWorldRotation);
// The same for a placement, mirrored ones included: Σ c_local_j Y_j(n) = Σ c_world_j Y_j(M n) with
// M = world's normalised columns (gi::shToLocal: for a mirror M = −R, band l times (−1)^l).
std::array<glm::vec3, 9> toLocal(const std::array<glm::vec3, 9>& worldIrradiance, const Placement& placement);

// Trilinear sample of the decoded field at q (local offset from o in units of R), clamped to the
// inner cube. out.size() >= shCount.
void sampleField(const Field& field, glm::vec3 q, std::span<glm::vec3> out);

// The §5.2.2 fall-off factor s for a local offset q in units of R.
float falloff(const FieldSettings& s, glm::vec3 q);

// L_DNRT at world point r with unit normal nr and albedo rho (Eq. 16 without L_init).
glm::vec3 evaluate(const Field& field, const Placement& placement, const std::array<glm::vec3, 9>& localIrradiance,
                   glm::vec3 r, glm::vec3 nr, glm::vec3 rho);

}  // namespace bounce::gi::dnrt
