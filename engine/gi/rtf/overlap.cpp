#include "engine/gi/rtf/overlap.hpp"
// overlap.hpp: the objects' shared occlusion, per field sample.

#include <algorithm>

#include "engine/core/parallel.hpp"
#include "engine/math/sh_rotate.hpp"

namespace bounce::gi::rtf {

OtherField::OtherField(std::span<const Object> objects, std::size_t a, std::size_t b)
    : field_(objects[b].field), reach_(objects[b].reach) {
  const Placement pa = place(*objects[a].field, objects[a].world), pb = place(*field_, objects[b].world);
  const FieldSettings& sb = field_->settings;
  const float drb = (sb.outerRadius - sb.innerRadius) / float(sb.spheres - 1);
  reachWorld_ = pb.radiusWorld * std::max(sb.outerRadius + drb, reach_);
  centre_ = pb.centreWorld, centreA_ = pa.centreWorld;
  etaWorld_ = pb.radiusWorld;
  beforeOnTies_ = b < a;
  worldToLocal_ = pb.worldToLocal;
  toA_ = sh::Rotationf::fromMatrix(glm::transpose(pa.localToWorldRotation) * pb.localToWorldRotation);
  invert_ = pa.mirrored != pb.mirrored;
}

ShScalar OtherField::hiddenInA(glm::vec3 p) const {
  constexpr float u = kUnitVisibility;
  const Field& fb = *field_;
  const glm::vec3 qb = (glm::vec3(worldToLocal_ * glm::vec4(p, 1.0f)) - fb.centre) / fb.radius;
  ShScalar vb = occlusion(fb, qb, reach_);
  for (int j = 0; j < kShCount; ++j) vb[std::size_t(j)] = (j == 0 ? u : 0.0f) - vb[std::size_t(j)];
  if (vb == ShScalar{}) return vb;
  ShScalar vbA{};
  toA_.apply<float>(std::span<const float>(vb), std::span<float>(vbA));
  if (invert_) gi::invert<float>(std::span<float>(vbA));
  return vbA;
}

bool OtherField::nearerThanA(glm::vec3 p) const {
  const float distA = glm::length(p - centreA_), distB = glm::length(p - centre_);
  return distB < distA || (distB == distA && beforeOnTies_);
}

bool OtherField::reaches(float reachA) const { return glm::length(centreA_ - centre_) < reachA + reachWorld_; }

OcclusionShares sharedOcclusion(std::span<const Object> objects, std::size_t a) {
  constexpr float u = kUnitVisibility;  // ∫f dω = u·f_0 (evaluate.hpp)
  const Field& f = *objects[a].field;
  const FieldSettings& s = f.settings;
  OcclusionShares out{std::vector<glm::vec4>(sampleCount(s), glm::vec4(1.0f)), std::vector<float>(sampleCount(s), 1.0f)};
  const Placement pa = place(f, objects[a].world);
  const float dr = (s.outerRadius - s.innerRadius) / float(s.spheres - 1);
  const float reachA = pa.radiusWorld * (s.outerRadius + dr);
  std::vector<OtherField> others;
  for (std::size_t b = 0; b < objects.size(); ++b)
    if (b != a) {
      OtherField o(objects, a, b);
      if (o.reaches(reachA)) others.push_back(o);  // else no sample of A lies in B's field
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
      float shared = 0.0f, letThrough = 1.0f, letThroughOn = 1.0f;
      for (const OtherField& o : others) {
        const ShScalar vbA = o.hiddenInA(p);  // (1 − V_B) at p, A's frame
        if (vbA == ShScalar{}) continue;      // beyond B's field
        float dot = a0 * vbA[0];
        for (int j = 1; j < kShCount; ++j) dot -= oofA[j] * vbA[std::size_t(j)];  // (1 − V_A)_j = −oof_j for j > 0
        const float share = std::clamp(dot / (a0 * u), 0.0f, 1.0f);
        shared += share;
        // Several nearer objects multiply, as Algorithm 1's visibilities do. For receivers on an object's
        // surface, Algorithm 1 leaves the receiver's own entity out: inside B's bounding sphere they are
        // mostly B's own, so there B takes nothing off (overlap.hpp).
        if (o.nearerThanA(p)) {
          letThrough *= 1.0f - share;
          if (glm::length(p - o.centre()) >= o.etaWorld()) letThroughOn *= 1.0f - share;
        }
      }
      out.scale[smp] = glm::vec4(glm::vec3(std::max(0.0f, 1.0f - 0.5f * shared)), letThrough);
      out.onObjects[smp] = letThroughOn;
    }
  }, 64);
  return out;
}

}  // namespace bounce::gi::rtf
