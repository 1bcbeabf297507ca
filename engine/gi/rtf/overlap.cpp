#include "engine/gi/rtf/overlap.hpp"
// overlap.hpp: the objects' shared occlusion, per field sample.

#include <algorithm>

#include "engine/core/parallel.hpp"
#include "engine/math/sh_rotate.hpp"

namespace bounce::gi::rtf {

std::vector<glm::vec4> sharedOcclusionScale(std::span<const Object> objects, std::size_t a) {
  constexpr float u = kUnitVisibility;  // ∫f dω = u·f_0 (evaluate.hpp)
  const Field& f = *objects[a].field;
  const FieldSettings& s = f.settings;
  std::vector<glm::vec4> out(sampleCount(s), glm::vec4(1.0f));
  const Placement pa = place(f, objects[a].world);
  const float dr = (s.outerRadius - s.innerRadius) / float(s.spheres - 1);
  const float reachA = pa.radiusWorld * (s.outerRadius + dr);
  struct Other {
    const Field* field;
    float reach;
    glm::vec3 centre;   // o_B, world
    float etaWorld;     // η_B, world units (field->radius is the local one)
    bool nearerOnTies;  // Algorithm 1's stable order: at equal distances the lower index is nearer
    glm::mat4 worldToLocal;
    // B's local frame → A's local frame: directions M_A⁻¹ M_B = ±R_Aᵀ R_B (gi::Placement), the
    // rotation R_Aᵀ R_B then the inversion (−1)^l when exactly one of the two is mirrored.
    sh::Rotationf toA;
    bool invert;
  };
  std::vector<Other> others;
  for (std::size_t b = 0; b < objects.size(); ++b) {
    if (b == a) continue;
    const Field& fb = *objects[b].field;
    const Placement pb = place(fb, objects[b].world);
    const FieldSettings& sb = fb.settings;
    const float drb = (sb.outerRadius - sb.innerRadius) / float(sb.spheres - 1);
    const float reachB = pb.radiusWorld * std::max(sb.outerRadius + drb, objects[b].reach);
    if (glm::length(pa.centreWorld - pb.centreWorld) >= reachA + reachB) continue;  // no sample of A in B's field
    others.push_back({&fb, objects[b].reach, pb.centreWorld, pb.radiusWorld, b < a, pb.worldToLocal,
                      sh::Rotationf::fromMatrix(glm::transpose(pa.localToWorldRotation) * pb.localToWorldRotation),
                      pa.mirrored != pb.mirrored});
  }
  if (others.empty()) return out;
  const int per = samplesPerSphere(s);
  parallelFor(0, std::size_t(per), [&](std::size_t ray) {
    const glm::vec3 dir = pa.localToWorldDirections() * sampleDirection(s, ray);
    for (int sphere = 0; sphere < s.spheres; ++sphere) {
      const std::size_t smp = std::size_t(sphere) * std::size_t(per) + ray;
      const float* oofA = f.oof.data() + smp * kShCount;
      const float a0 = u - oofA[0];  // (1 − V_A)'s l = 0 coefficient
      if (a0 <= 1e-6f) continue;     // A hides nothing from this sample
      const glm::vec3 p = pa.centreWorld + pa.radiusWorld * sphereRadius(s, sphere) * dir;
      const float distA = glm::length(p - pa.centreWorld);
      float shared = 0.0f, letThrough = 1.0f;
      for (const Other& o : others) {
        const Field& fb = *o.field;
        const glm::vec3 qb = (glm::vec3(o.worldToLocal * glm::vec4(p, 1.0f)) - fb.centre) / fb.radius;
        // (1 − V_B) at p: u·δ_0 − V_B, V_B Eq. 10's lookup faded to V = 1 at the field's end (occlusion()),
        // so all zero beyond B's field.
        ShScalar vb = occlusion(fb, qb, o.reach);
        for (int j = 0; j < kShCount; ++j) vb[std::size_t(j)] = (j == 0 ? u : 0.0f) - vb[std::size_t(j)];
        if (vb == ShScalar{}) continue;
        ShScalar vbA{};
        o.toA.apply<float>(std::span<const float>(vb), std::span<float>(vbA));
        if (o.invert) gi::invert<float>(std::span<float>(vbA));
        float dot = a0 * vbA[0];
        for (int j = 1; j < kShCount; ++j) dot -= oofA[j] * vbA[std::size_t(j)];  // (1 − V_A)_j = −oof_j for j > 0
        const float share = std::clamp(dot / (a0 * u), 0.0f, 1.0f);
        shared += share;
        const float distB = glm::length(p - o.centre);
        // Algorithm 1 leaves the receiver's own entity out: inside B's bounding sphere the receivers
        // are mostly B's own surface, so there B takes nothing off A's light (overlap.hpp). Several
        // nearer objects multiply, as Algorithm 1's visibilities do.
        const bool nearer = distB < distA || (distB == distA && o.nearerOnTies);
        if (nearer && distB >= o.etaWorld) letThrough *= 1.0f - share;
      }
      out[smp] = glm::vec4(glm::vec3(std::max(0.0f, 1.0f - 0.5f * shared)), letThrough);
    }
  }, 64);
  return out;
}

}  // namespace bounce::gi::rtf
