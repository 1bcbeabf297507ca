#include "engine/gi/rtf/occluders.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce::gi::rtf {

PosedOccluders::PosedOccluders(std::vector<ref::SceneDesc> objects) {
  for (ref::SceneDesc& s : objects) {
    s.textures.clear();
    for (ref::RefMaterial& m : s.materials) m.albedoTexture = m.emissiveTexture = -1;
    // Bounding sphere: the box's centre and the farthest vertex from it.
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    std::size_t triangles = 0;
    for (const ref::RefMesh& m : s.meshes) {
      triangles += m.indices.size() / 3;
      for (const glm::vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const glm::vec3 c = triangles > 0 ? 0.5f * (lo + hi) : glm::vec3(0.0f);
    float r = 0.0f;
    for (const ref::RefMesh& m : s.meshes)
      for (const glm::vec3& p : m.positions) r = std::max(r, glm::length(p - c));
    centre_.push_back(c);
    radius_.push_back(r);
    bvh_.push_back(triangles > 0 && r > 0.0f ? std::make_unique<ref::SceneBvh>(std::move(s)) : nullptr);
  }
}

PosedOccluders::~PosedOccluders() = default;

std::optional<PosedOccluders::Pose> PosedOccluders::pose(std::size_t index, const glm::mat4& world) const {
  if (index >= bvh_.size() || !bvh_[index]) return std::nullopt;
  const std::optional<gi::Placement> p = gi::tryPlace(centre_[index], radius_[index], world);
  if (!p) return std::nullopt;
  const glm::dmat3 m(world), g = glm::transpose(m) * m;
  double rowSum = 0.0;
  for (int i = 0; i < 3; ++i) rowSum = std::max(rowSum, std::abs(g[0][i]) + std::abs(g[1][i]) + std::abs(g[2][i]));
  return Pose{index, *p, float(double(radius_[index]) * std::sqrt(rowSum))};
}

bool PosedOccluders::occluded(std::span<const Pose> poses, std::size_t skip, glm::vec3 o, glm::vec3 d, float tMax) const {
  for (const Pose& p : poses) {
    if (p.index == skip) continue;
    // The segment's closest approach to the bounding sphere's centre (d is a unit vector).
    const glm::vec3 c = p.placement.centreWorld - o;
    const float t = std::clamp(glm::dot(c, d), 0.0f, tMax);
    const float r = p.cullRadius;
    if (glm::dot(c - t * d, c - t * d) > r * r) continue;
    const glm::vec3 oLocal(p.placement.worldToLocal * glm::vec4(o, 1.0f));
    const glm::vec3 dLocal(p.placement.worldToLocal * glm::vec4(d, 0.0f));  // not unit: t stays the world's
    if (bvh_[p.index]->occluded(oLocal, dLocal, 0.0f, tMax)) return true;
  }
  return false;
}

float PosedVisibility::visible(const render::LightGpu& light, glm::vec3 p, float radius) const {
  return incident::traceVisibility(light, p, radius, [this](glm::vec3 o, glm::vec3 d, float tMax) {
    return (level_ && level_->occluded(o, d, 0.0f, tMax)) || occluders_.occluded(poses_, skip_, o, d, tMax);
  });
}

}  // namespace bounce::gi::rtf
