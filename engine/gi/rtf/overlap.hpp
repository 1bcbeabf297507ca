#pragma once
// The objects' shared occlusion in the GPU's blocked light (issue 14, README RTF "Seventh pass").
//
// The GPU pass adds each object's blocked term on its own (additive blending); Algorithm 1 (§5)
// multiplies the objects' visibilities, and for two objects
//   1 − V_A V_B = (1 − V_A) + (1 − V_B) − (1 − V_A)(1 − V_B),
// so the sum counts the directions both objects hide twice. The shading record's light is the
// indirect light at o (its shape and level, update.hpp packObject); this per-sample factor takes
// half the shared part off each object's term (the other half off the other object's), with the
// light across the hidden directions taken as uniform:
//   s_A(p) = max(0, 1 − ½ Σ_{B≠A} ∫(1 − V_A)(1 − V_B) dω / ∫(1 − V_A) dω),
// V_A the OOF of A's field sample p, V_B B's OOF looked up at p (Eq. 10's weights, the field's end
// included). Both integrals are exact for the order-4 SH: ∫fg dω = Σ_j f_j g_j, ∫f dω = √(4π)·f_0.
// Where no other object's field reaches p, s = 1: the light at o, unscaled. The ξ pass multiplies the
// sample's blocked light by it (shaders/rtf/xi.comp, buffer BlockedScale), the same slot the former
// per-sample light level used (blockedScale in update.hpp, kept for rtf_parts).
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/rtf/evaluate.hpp"

namespace bounce::gi::rtf {

// One vec4 (s, s, s, 1) per sample of objects[a]'s field, in field.hpp's sample order.
std::vector<glm::vec4> sharedOcclusionScale(std::span<const Object> objects, std::size_t a);

}  // namespace bounce::gi::rtf
