#pragma once
// Rotation of SH coefficient vectors, bands 0..3 (orders up to 4), exact.
//
// Meaning: for a rotation matrix R, apply(c) returns the coefficients of the ROTATED function
// g(ω) = f(Rᵀω), i.e. g(Rω) = f(ω): a light arriving from direction ω arrives from Rω afterwards.
// (To express a world-space SH in an object's local frame, pass the inverse/transpose.)
//
// Band 0 is invariant. Band 1, in this basis (Y_1,-1, Y_1,0, Y_1,1) ∝ (y, z, x), is R itself with
// rows and columns permuted to (y, z, x): M¹[m][n] = R[p(m)][p(n)], p(-1) = y, p(0) = z, p(1) = x.
// Bands l >= 2 follow from bands 1 and l-1 by the recurrence of Ivanic & Ruedenberg, "Rotation
// Matrices for Real Spherical Harmonics. Direct Determination by Recursion", J. Phys. Chem. 100
// (1996) 6342, Tables 1–2 and eq. 8.1, with the corrections of J. Phys. Chem. A 102 (1998) 9099
// (the m < 0 branch of V, see sh_rotate.cpp). Their real SH have no Condon–Shortley phase, the
// convention of sh_eval.hpp, so the recurrence is used as published with no sign changes.
// Tests check it against rotate-then-project and against the band-1 vector rotation.
#include <array>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.hpp"
#include "engine/math/sh_eval.hpp"

namespace bounce::sh {

template <typename T>
class Rotation {
 public:
  // r must be a proper rotation (orthonormal, det +1) to within 1e-3 (float) / 1e-6 (double)
  // per entry; otherwise throws InternalError (a scale or reflection would silently give a wrong
  // answer).
  static Rotation fromMatrix(const glm::mat<3, 3, T>& r);
  // q need not be unit length (normalised here); zero length throws InternalError.
  static Rotation fromQuaternion(const glm::qua<T>& q);

  // Band l's (2l+1)×(2l+1) matrix, row-major, entry (m+l, n+l): g_lm = Σ_n M[m][n] f_ln.
  std::span<const T> band(int l) const;

  // out[i] for every coefficient of in (1, 4, 9 or 16 of them); in and out must not overlap.
  // V is T (scalar) or glm::vec<3,T> (RGB).
  template <typename V>
  void apply(std::span<const V> in, std::span<V> out) const {
    const int order = orderFromCount(in.size());
    if (out.size() < in.size()) throw InternalError("sh::Rotation::apply: output too small");
    out[0] = in[0];
    for (int l = 1; l < order; ++l) {
      const int n2 = 2 * l + 1, base = l * l;
      const auto m = band(l);
      for (int r = 0; r < n2; ++r) {
        V sum(0);
        for (int c = 0; c < n2; ++c) sum += in[base + c] * m[r * n2 + c];
        out[base + r] = sum;
      }
    }
  }

  template <typename V>
  std::vector<V> apply(std::span<const V> in) const {
    std::vector<V> out(in.size());
    apply<V>(in, std::span<V>(out));
    return out;
  }
  template <typename V>
  std::vector<V> apply(const std::vector<V>& in) const {
    return apply<V>(std::span<const V>(in));
  }

 private:
  std::array<T, 9> band1_{};
  std::array<T, 25> band2_{};
  std::array<T, 49> band3_{};
};

using Rotationd = Rotation<double>;
using Rotationf = Rotation<float>;

// Zonal rotation shortcut: a function symmetric about axis d with zonal coefficients z_l
// (the m = 0 coefficients it would have with axis +Z) has f_lm = √(4π/(2l+1)) z_l Y_lm(d)
// (Sloan 2008, "Stupid Spherical Harmonics Tricks", §"Zonal harmonics"). zonal.size() = order;
// returns order² coefficients. d must be unit length.
template <typename T>
std::vector<T> rotateZonal(std::span<const T> zonal, const glm::vec<3, T>& d);

}  // namespace bounce::sh
