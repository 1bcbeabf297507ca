#include "engine/gi/rtf/overlap.hpp"
// overlap.hpp: the objects' shared occlusion, per field sample.

#include <algorithm>
#include <cmath>

#include "engine/core/parallel.hpp"

namespace bounce::gi::rtf {

namespace {

constexpr float kPi = float(math::kPi);

// Two caps with α_a + α_b ≤ π (each one's complement holds the other's axis' antipode).
float capIntersectionNarrow(float ca, float cb, float cg) {
  const float a = std::acos(ca), b = std::acos(cb), g = std::acos(cg);
  if (g >= a + b) return 0.0f;                                        // disjoint
  if (g <= std::abs(a - b)) return 2.0f * kPi * (1.0f - std::max(ca, cb));  // the smaller inside the larger
  const float sa = std::sin(a), sb = std::sin(b), sg = std::sin(g);
  const auto ac = [](float x) { return std::acos(std::clamp(x, -1.0f, 1.0f)); };
  // Ω = 2[π − acos((cos γ − cos α_a cos α_b)/(sin α_a sin α_b)) − acos((cos α_b − cos γ cos α_a)/(sin γ sin α_a)) cos α_a
  //          − acos((cos α_a − cos γ cos α_b)/(sin γ sin α_b)) cos α_b]
  const float omega = 2.0f * (kPi - ac((cg - ca * cb) / (sa * sb)) - ac((cb - cg * ca) / (sg * sa)) * ca -
                              ac((ca - cg * cb) / (sg * sb)) * cb);
  return std::clamp(omega, 0.0f, 2.0f * kPi * (1.0f - std::max(ca, cb)));
}

}  // namespace

float capIntersection(float cosA, float cosB, float cosGamma) {
  const float ca = std::clamp(cosA, -1.0f, 1.0f), cb = std::clamp(cosB, -1.0f, 1.0f), cg = std::clamp(cosGamma, -1.0f, 1.0f);
  if (std::acos(ca) + std::acos(cb) <= kPi) return capIntersectionNarrow(ca, cb, cg);
  // Complements: half-angles π − α about the antipodes, the same γ; cos(π − α) = −cos α.
  const float both = 2.0f * kPi * (1.0f - ca) + 2.0f * kPi * (1.0f - cb) - 4.0f * kPi + capIntersectionNarrow(-ca, -cb, cg);
  return std::clamp(both, 0.0f, 2.0f * kPi * (1.0f - std::max(ca, cb)));
}

glm::vec4 hiddenCap(const float* notV) {
  const float omega = kUnitVisibility * notV[0];  // ∫(1 − V) dω, sr
  const glm::vec3 l1(notV[3], notV[1], notV[2]);  // x, y, z lobes ∝ ∫(1 − V) ω dω
  const float len = glm::length(l1);
  const glm::vec3 axis = len > 1e-12f ? l1 / len : glm::vec3(0.0f, 0.0f, 1.0f);
  return glm::vec4(axis, std::clamp(1.0f - omega / (2.0f * kPi), -1.0f, 1.0f));
}

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
    glm::mat4 worldToLocal;
    glm::mat3 toA;  // B's local frame → A's local frame (rotations; the caps' axes only)
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
    others.push_back({&fb, objects[b].reach, pb.worldToLocal, glm::transpose(pa.localToWorldRotation) * pb.localToWorldRotation});
  }
  if (others.empty()) return out;
  const int per = samplesPerSphere(s);
  parallelFor(0, std::size_t(per), [&](std::size_t ray) {
    const glm::vec3 dir = pa.localToWorldRotation * sampleDirection(s, ray);
    for (int sphere = 0; sphere < s.spheres; ++sphere) {
      const std::size_t smp = std::size_t(sphere) * std::size_t(per) + ray;
      float notA[kShCount];
      for (int j = 0; j < kShCount; ++j) notA[j] = (j == 0 ? u : 0.0f) - f.oof[smp * kShCount + std::size_t(j)];
      const float omegaA = u * notA[0];  // ∫(1 − V_A) dω, sr
      if (omegaA <= 1e-6f) continue;     // A hides nothing from this sample
      const glm::vec4 capA = hiddenCap(notA);
      const glm::vec3 p = pa.centreWorld + pa.radiusWorld * sphereRadius(s, sphere) * dir;
      float shared = 0.0f;
      for (const Other& o : others) {
        const Field& fb = *o.field;
        const glm::vec3 qb = (glm::vec3(o.worldToLocal * glm::vec4(p, 1.0f)) - fb.centre) / fb.radius;
        // (1 − V_B) at p: u·δ_0 − V_B, V_B Eq. 10's lookup faded to V = 1 at the field's end (occlusion()),
        // so all zero beyond B's field.
        ShScalar vb = occlusion(fb, qb, o.reach);
        for (int j = 0; j < kShCount; ++j) vb[std::size_t(j)] = (j == 0 ? u : 0.0f) - vb[std::size_t(j)];
        if (u * vb[0] <= 1e-6f) continue;  // B hides nothing from p
        const glm::vec4 capB = hiddenCap(vb.data());
        const float cosGamma = glm::dot(glm::vec3(capA), o.toA * glm::vec3(capB));
        shared += std::clamp(capIntersection(capA.w, capB.w, cosGamma) / omegaA, 0.0f, 1.0f);
      }
      out[smp] = glm::vec4(glm::vec3(std::max(0.0f, 1.0f - 0.5f * shared)), 1.0f);
    }
  }, 64);
  return out;
}

}  // namespace bounce::gi::rtf
