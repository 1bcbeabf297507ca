#pragma once
// The CPU face of vertex posing (the GPU face is shaders/skinning/skinning.comp; tests hold them
// equal): morph targets, then linear blend skinning with up to 8 influences.
//
//   MorphJob     p = p₀ + Σ_t w_t·Δp_t,  n = n₀ + Σ_t w_t·Δn_t (glTF 2.0 §3.7.2.2)
//   SkinningJob  S = Σ_i w_i·J_i over JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1,
//                p' = S·p,  n' = normalize(inverse(transpose(S₃ₓ₃))·n)   (normals by the inverse
//                transpose: exact for the non-uniform scale a joint may carry)
//
// posePrimitive() runs both for one primitive of one mesh node with a pose: the single
// evaluation the renderer, the reference tracer and the exporter share.
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/anim/pose.hpp"
#include "engine/asset/cooked_asset.hpp"

namespace bounce::anim {

struct MorphJob {
  const asset::Primitive* primitive = nullptr;
  std::span<const float> weights;  // one per target (missing trailing weights count as 0)
  std::span<glm::vec3> positions;  // out, one per vertex
  std::span<glm::vec3> normals;    // out, one per vertex (not normalised: skinning or the shader does)
  bool validate() const;
  bool run() const;
};

struct SkinningJob {
  const asset::Primitive* primitive = nullptr;  // joints/weights (and joints1/weights1)
  std::span<const glm::mat4> jointMatrices;     // the skin's, Pose::joints[skin]
  std::span<const glm::vec3> positions;         // in (bind pose, after morphing)
  std::span<const glm::vec3> normals;           // in
  std::span<glm::vec3> outPositions;            // asset space
  std::span<glm::vec3> outNormals;              // unit length
  // Spans of the primitive's vertex count, weights present, every influencing joint index below
  // the joint matrix count.
  bool validate() const;
  bool run() const;
};

// The blended skin matrix of vertex v (the sum SkinningJob applies): exposed for the tests.
glm::mat4 skinMatrix(const asset::Primitive& p, std::span<const glm::mat4> joints, std::size_t v);

// Whether a mesh node is drawn skinned: it has a skin and its primitives (or its cage's, for a
// subdivided mesh: asset::Mesh::cage) carry weights.
bool isSkinned(const asset::CookedAsset& asset, int node);
// Whether a node's geometry changes with a pose: skinned, or a mesh with morph targets.
bool isDeformed(const asset::CookedAsset& asset, int node);
// Whether any node of the asset is (a baked technique on it is baked in the bind pose and says so).
bool anyDeformed(const asset::CookedAsset& asset);

// Morph targets, then skinning (when isSkinned()), of primitive `p` of node `node`'s mesh or of its
// cage: what posePrimitive() does before any refinement. Returns true when skinned.
bool poseVertices(const asset::CookedAsset& asset, int node, const asset::Primitive& p, const Pose* pose,
                  std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);

// Primitive `prim` of mesh node `node` as posed: morphed with the pose's (or the mesh's default)
// weights, then skinned with the pose's joint matrices when isSkinned(). A primitive of a
// subdivided deformed mesh: its cage primitive posed so, then refined (LimitStencilJob). Returns true when skinned
// (positions in asset space: place them with skinFrame, never with the node's matrix), false when
// the result is in the node's own frame. pose may be null: the rest pose, morph defaults applied.
bool posePrimitive(const asset::CookedAsset& asset, int node, std::size_t prim, const Pose* pose,
                   std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);

}  // namespace bounce::anim
