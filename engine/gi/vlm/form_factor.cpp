#include "engine/gi/vlm/form_factor.hpp"

namespace bounce::gi::vlm {

double formFactor(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& v0, const glm::dvec3& v1,
                  const glm::dvec3& v2) {
  return formFactor<double>(x, n, v0, v1, v2);
}

}  // namespace bounce::gi::vlm
