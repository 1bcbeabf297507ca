#include "engine/anim/skinning.hpp"

#include <glm/gtc/matrix_inverse.hpp>

#include "engine/anim/subdivision.hpp"
#include "engine/core/error.hpp"

namespace bounce::anim {

bool MorphJob::validate() const {
  if (!primitive) return false;
  const std::size_t n = primitive->positions.size();
  return positions.size() == n && normals.size() == n;
}

bool MorphJob::run() const {
  if (!validate()) return false;
  const asset::Primitive& p = *primitive;
  std::copy(p.positions.begin(), p.positions.end(), positions.begin());
  std::copy(p.normals.begin(), p.normals.end(), normals.begin());
  for (std::size_t t = 0; t < p.targets.size() && t < weights.size(); ++t) {
    const float w = weights[t];
    if (w == 0.0f) continue;
    const asset::MorphTarget& target = p.targets[t];
    for (std::size_t v = 0; v < target.positions.size(); ++v) positions[v] += w * target.positions[v];
    for (std::size_t v = 0; v < target.normals.size(); ++v) normals[v] += w * target.normals[v];
  }
  return true;
}

glm::mat4 skinMatrix(const asset::Primitive& p, std::span<const glm::mat4> joints, std::size_t v) {
  glm::mat4 s(0.0f);
  for (int k = 0; k < 4; ++k) {
    if (p.weights[v][k] != 0.0f) s += p.weights[v][k] * joints[p.joints[v][k]];
    if (!p.weights1.empty() && p.weights1[v][k] != 0.0f) s += p.weights1[v][k] * joints[p.joints1[v][k]];
  }
  return s;
}

bool SkinningJob::validate() const {
  if (!primitive || primitive->weights.empty()) return false;
  const asset::Primitive& p = *primitive;
  const std::size_t n = p.positions.size();
  if (positions.size() != n || normals.size() != n || outPositions.size() != n || outNormals.size() != n) return false;
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 4; ++k) {
      if (p.weights[v][k] != 0.0f && p.joints[v][k] >= jointMatrices.size()) return false;
      if (!p.weights1.empty() && p.weights1[v][k] != 0.0f && p.joints1[v][k] >= jointMatrices.size()) return false;
    }
  return true;
}

bool SkinningJob::run() const {
  if (!validate()) return false;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const glm::mat4 s = skinMatrix(*primitive, jointMatrices, v);
    outPositions[v] = glm::vec3(s * glm::vec4(positions[v], 1.0f));
    const glm::vec3 n = glm::inverseTranspose(glm::mat3(s)) * normals[v];
    const float len = glm::length(n);
    outNormals[v] = len > 0.0f ? n / len : normals[v];
  }
  return true;
}

namespace {

// The mesh whose primitives a node's pose deforms: its cage when it has one (Mesh::cage).
const asset::Mesh& deformedMesh(const asset::CookedAsset& a, const asset::Mesh& m) {
  return m.cage >= 0 ? a.meshes[std::size_t(m.cage)] : m;
}

}  // namespace

bool poseVertices(const asset::CookedAsset& a, int node, const asset::Primitive& p, const Pose* pose,
                  std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  const asset::Node& n = a.nodes[std::size_t(node)];
  positions.resize(p.positions.size());
  normals.resize(p.positions.size());
  if (!MorphJob{&p, morphWeights(a, pose, node), positions, normals}.run())
    throw InternalError("anim: MorphJob failed on " + a.sourceName);
  const bool skinned = isSkinned(a, node) && !p.weights.empty();
  if (!skinned) return false;
  Pose rest;
  if (!pose) {
    evaluatePose(a, -1, 0.0f, rest);
    pose = &rest;
  }
  const std::vector<glm::vec3> morphedP = positions, morphedN = normals;
  if (!SkinningJob{&p, pose->joints[std::size_t(n.skin)], morphedP, morphedN, positions, normals}.run())
    throw InternalError("anim: SkinningJob failed on " + a.sourceName);
  return true;
}

bool isSkinned(const asset::CookedAsset& a, int node) {
  const asset::Node& n = a.nodes[std::size_t(node)];
  if (n.skin < 0 || n.mesh < 0) return false;
  for (const auto& p : deformedMesh(a, a.meshes[std::size_t(n.mesh)]).primitives)
    if (!p.weights.empty()) return true;
  return false;
}

bool isDeformed(const asset::CookedAsset& a, int node) {
  const asset::Node& n = a.nodes[std::size_t(node)];
  if (n.mesh < 0) return false;
  if (isSkinned(a, node)) return true;
  for (const auto& p : deformedMesh(a, a.meshes[std::size_t(n.mesh)]).primitives)
    if (!p.targets.empty()) return true;
  return false;
}

bool anyDeformed(const asset::CookedAsset& a) {
  for (std::size_t n = 0; n < a.nodes.size(); ++n)
    if (isDeformed(a, int(n))) return true;
  return false;
}

bool posePrimitive(const asset::CookedAsset& a, int node, std::size_t prim, const Pose* pose,
                   std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  const asset::Mesh& mesh = a.meshes[std::size_t(a.nodes[std::size_t(node)].mesh)];
  const asset::Primitive& p = mesh.primitives[prim];
  if (mesh.cage < 0) return poseVertices(a, node, p, pose, positions, normals);
  // A subdivided deformed mesh: pose its cage primitive, then evaluate the limit stencils on it.
  const asset::Primitive& cage = a.meshes[std::size_t(mesh.cage)].primitives[std::size_t(p.stencils.cagePrimitive)];
  std::vector<glm::vec3> cageP, cageN;
  const bool skinned = poseVertices(a, node, cage, pose, cageP, cageN);
  positions.resize(p.positions.size());
  normals.resize(p.positions.size());
  if (!LimitStencilJob{&p.stencils, cageP, cageN, positions, normals}.run())
    throw InternalError("anim: LimitStencilJob failed on " + a.sourceName);
  return skinned;
}

}  // namespace bounce::anim
