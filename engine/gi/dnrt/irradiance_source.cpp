#include "engine/gi/dnrt/irradiance_source.hpp"

#include <span>

#include "engine/math/sh.hpp"

namespace bounce::gi::dnrt {

std::array<glm::vec3, 9> ConstantEnvironment::radianceSH(glm::vec3) const {
  std::array<glm::vec3, 9> c{};
  // A constant function L has the single coefficient ∫ L Y_00 dω = 4π L Y_00 = 2√π L.
  c[0] = radiance_ * static_cast<float>(4.0 * math::kPi * sh::constants::kY00);
  return c;
}

std::array<glm::vec3, 9> irradianceSH(const std::array<glm::vec3, 9>& radiance) {
  const auto e = sh::convolveCosine<glm::vec3>(std::span<const glm::vec3>(radiance));
  std::array<glm::vec3, 9> out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = e[i];
  return out;
}

}  // namespace bounce::gi::dnrt
