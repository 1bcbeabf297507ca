#pragma once
// Where DNRT's c_j come from: the irradiance SH at an object's centre (paper §5.2.1, "sampling and
// interpolating the coefficients of the light probes closest to O"). The probe volume implements
// this interface; ConstantEnvironment (uniform radiance everywhere) is what tests use and what a
// level without probes falls back to.
#include <array>

#include <glm/glm.hpp>

namespace bounce::gi::dnrt {

// Order-3 (9 coefficient) RGB SH of incident RADIANCE at world point p, in world axes, in the
// convention of engine/math/sh_eval.hpp: L(ω) = Σ L_i Y_i(ω), ω pointing towards the source.
// DNRT's c_j are the cosine-convolved coefficients (irradianceSH below), as Eq. 4 requires.
struct IrradianceSource {
  virtual ~IrradianceSource() = default;
  virtual std::array<glm::vec3, 9> radianceSH(glm::vec3 p) const = 0;
};

// Uniform radiance L (W/(m²·sr) per channel) from every direction at every point: L_00 = 2√π L.
class ConstantEnvironment final : public IrradianceSource {
 public:
  explicit ConstantEnvironment(glm::vec3 radiance) : radiance_(radiance) {}
  std::array<glm::vec3, 9> radianceSH(glm::vec3 p) const override;

 private:
  glm::vec3 radiance_;
};

// c_j = Â_l L_lm (sh_convolve.hpp): the irradiance SH E(n) = Σ c_j Y_j(n) of radiance SH L.
std::array<glm::vec3, 9> irradianceSH(const std::array<glm::vec3, 9>& radiance);

}  // namespace bounce::gi::dnrt
