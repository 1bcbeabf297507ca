#pragma once
// One object's baked frame placed in the world: what DNRT (§5.2.1 of its paper) and RTF (Pan et al.
// 2007 §5: M, OOF and proxies in the object's local frame) both need to carry a field's positions,
// directions and SH between the object's local frame and the world. One copy for both: RTF had its
// own until session 12, which turned a mirrored object's reflection into an unrelated rotation.
//
// `world` is local → world: rotation, uniform scale, translation, and possibly a reflection
// (det < 0). Its normalised columns M map local directions to world directions. M is a rotation R
// (det +1) or a mirror M = −R (det −1, R = −M a rotation): sh::Rotation takes rotations only, so a
// mirror keeps R and the flag, and the SH maps below add the inversion's parity (−1)^l on band l
// (Y_lm(−ω) = (−1)^l Y_lm(ω)).
#include <optional>
#include <span>

#include <glm/glm.hpp>

#include "engine/core/error.hpp"
#include "engine/math/sh_rotate.hpp"

namespace bounce::gi {

struct Placement {
  glm::mat4 worldToLocal{1.0f};
  glm::mat3 localToWorldRotation{1.0f};  // R: orthonormal, det +1
  // det(world) < 0: local → world directions are n ↦ −R·n (a reflection).
  bool mirrored = false;
  glm::vec3 centreWorld{0.0f};
  float radiusWorld = 1.0f;  // radiusLocal × the largest axis scale (a non-uniform scale: an approximation)
  float radiusLocal = 1.0f;
  glm::vec3 centreLocal{0.0f};
  // M: local → world directions (normals, rays), ±R; orthonormal, det ±1. Its transpose is world → local.
  glm::mat3 localToWorldDirections() const { return mirrored ? -localToWorldRotation : localToWorldRotation; }
};

// The placement of a field with bounding centre `centreLocal` and radius `radiusLocal` (local units).
// Any finite `world` with non-zero axis scales places down to tiny objects: a uniform scale s has
// det s³ (1e-30 at s = 1e-10), so the determinant and the inverse are taken in double. Throws
// InternalError "<who>: singular object transform" when an axis scale is 0, `world` or radiusLocal
// is not finite (or radiusLocal ≤ 0), or an entry of worldToLocal / radiusLocal exceeds kMaxToUnit
// (a world radius s·R_local under ~1e-30: the float maps of its users would overflow, see place()).
inline constexpr double kMaxToUnit = 1e30;
Placement place(glm::vec3 centreLocal, float radiusLocal, const glm::mat4& world, const char* who);
// place() without the throw: nullopt where place() refuses. Per frame, a technique skips such an
// object's GI (a motion whose scale passes through 0 mid-run: the object adds and takes away nothing
// that frame, as it has no size); at the session's start the level's transform is checked instead
// (participants.hpp checkPlaceable: the level's bad input).
std::optional<Placement> tryPlace(glm::vec3 centreLocal, float radiusLocal, const glm::mat4& world);

// An orthogonal M (det ±1: a placement's normalised columns, SL's closest-rotation pose) as M = R or
// M = −R with R a rotation (sh::Rotation takes rotations only); `mirrored` when det M < 0.
struct SignedRotation {
  glm::mat3 rotation{1.0f};
  bool mirrored = false;
};
inline SignedRotation splitMirror(const glm::mat3& m) {
  const bool mirrored = glm::determinant(m) < 0.0f;
  return {mirrored ? -m : m, mirrored};
}

// The inversion's factor on SH band l for a mirrored frame, (−1)^l (Y_lm(−ω) = (−1)^l Y_lm(ω)); 1 otherwise.
inline float bandSign(bool mirrored, int l) { return mirrored && l % 2 == 1 ? -1.0f : 1.0f; }

// Band l of c times (−1)^l in place: the SH of f(−ω) (an inversion). 1, 4, 9 or 16 coefficients.
template <typename V>
void invert(std::span<V> c) {
  for (std::size_t l = 1; l * l < c.size(); ++l)
    if (bandSign(true, int(l)) < 0.0f)
      for (std::size_t i = l * l; i < (l + 1) * (l + 1) && i < c.size(); ++i) c[i] = -c[i];
}

// SH of a local-frame function f (1, 4, 9 or 16 coefficients; V float or RGB) in the world:
// g(M n) = f(n). A rotation by R (g'(ω) = f(Rᵀω), sh_rotate.hpp), then for a mirror the inversion
// (g(ω) = g'(−ω) = f(−Rᵀω) = f(M⁻¹ω)).
template <typename V>
void shToWorld(const Placement& p, std::span<const V> local, std::span<V> world) {
  sh::Rotationf::fromMatrix(p.localToWorldRotation).apply<V>(local, world);
  if (p.mirrored) invert<V>(world.first(local.size()));
}
// SH of a world function g in the local frame: f(n) = g(M n), the inverse of shToWorld.
template <typename V>
void shToLocal(const Placement& p, std::span<const V> world, std::span<V> local) {
  sh::Rotationf::fromMatrix(glm::transpose(p.localToWorldRotation)).apply<V>(world, local);
  if (p.mirrored) invert<V>(local.first(world.size()));
}

}  // namespace bounce::gi
