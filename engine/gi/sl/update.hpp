#pragma once
// SL per frame (paper §7.1, "soft deformations"): where each SL of one entity is. Every SL moves
// with the average rotation and translation of the vertices it covers (SlSphere::vertices); a rigid
// object's vertices all move by the entity's transform, so its SLs move exactly with it.
//
// The bake frame is the entity's local frame as dnrt::objectScene lays it out (the instanced nodes
// at their file transforms, identity entity transform, rest pose). Vertex v of primitive P moves
// from there to the world by
//   T_v = F · S_v · N_P⁻¹   (P skinned and the entity posed: F = anim::skinFrame, S_v = the blended
//                            skin matrix anim::skinMatrix — the renderer's own CPU evaluation)
//   T_P = W_P · N_P⁻¹       (otherwise: W_P the node's world matrix with the pose's local matrices)
// with N_P the node's world matrix in the bake frame. Per SL, with V its covered vertices:
//   A = (1/|V|) Σ_v T_v,   centre' = A · centre,   rotation = polar(A₃ₓ₃) (closest rotation),
//   radius' = radius · (1/|V|) Σ_v |det (T_v)₃ₓ₃|^(1/3)   (each vertex's uniform scale, averaged)
// so translation + rotation are the covered vertices' averages, uniform scale follows the entity.
// An SL that covers no vertex (possible with the Lloyd fit) uses every vertex of the object.
// Morph targets do not move SLs (the paper's class: deformations small relative to each SL).
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/anim/pose.hpp"
#include "engine/asset/cooked_asset.hpp"
#include "engine/gi/sl/bake.hpp"
#include "engine/scene/components.hpp"

namespace bounce::gi::sl {

// One primitive of a MeshRef's instanced subtree, in the order ref::extractScene (and so
// dnrt::objectScene and the bake's vertex indices) visits them.
struct InstancedPrimitive {
  int node = -1;
  std::size_t primitive = 0;
  glm::mat4 bakeFrame{1.0f};      // N_P: the node's world matrix in the bake frame
  std::uint32_t firstVertex = 0;  // index of its vertex 0 in the bake's numbering
  std::uint32_t vertexCount = 0;
};
std::vector<InstancedPrimitive> instancedPrimitives(const asset::CookedAsset& asset, const scene::MeshRef& ref);

// The bake's Skin for these primitives (per primitive its JOINTS_0/WEIGHTS_0, empty when unskinned).
Skin skinOf(const asset::CookedAsset& asset, const std::vector<InstancedPrimitive>& primitives);

// One SL as pass 2 reads it (world space).
struct PosedSphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  glm::mat3 rotation{1.0f};  // SL local → world: rotates the intensity SH (weights, not samples)
};

// §7.3 (hierarchy.hpp, two levels): this frame's parent SL of every object, in object order —
// hierarchy.hpp parentSphere of the object's posed SLs (objects[i]: SL i's object; ids 0 … max), world
// frame (identity rotation); an id without SLs gets radius 0. CPU work, since the poses are on the
// CPU; the parents' intensity needs pass 1's and is a reduction on the device (IntensityPass).
std::vector<PosedSphere> parentSpheres(std::span<const PosedSphere> posed, std::span<const std::uint32_t> objects);

// Closest rotation to m (polar decomposition, Higham's Newton iteration); identity when m is
// singular. An improper m (mirroring transform) gives the closest orthogonal matrix, det −1.
glm::dmat3 closestRotation(const glm::dmat3& m);

class SpherePoser {
 public:
  // `asset` must outlive the poser (the session's cooked copy).
  SpherePoser(const asset::CookedAsset& asset, const scene::MeshRef& ref, const SphereSet& set);
  // entityWorld: the entity's WorldTransform; pose: its anim::Pose, or null (file transforms).
  void pose(const glm::mat4& entityWorld, const anim::Pose* pose, std::vector<PosedSphere>& out) const;
  // T_v for every vertex of the bake frame (the header's formula), for tests: T_v · p_v is the
  // vertex where the renderer draws it.
  std::vector<glm::dmat4> vertexTransforms(const glm::mat4& entityWorld, const anim::Pose* pose) const;

 private:
  // What T_v needs for one frame: T_P per primitive, the skin frame F.
  struct FrameState {
    std::vector<glm::dmat4> rigid;
    std::vector<double> rigidScale;
    glm::dmat4 skinFrame{1.0};
    const anim::Pose* pose = nullptr;
  };
  FrameState frameState(const glm::mat4& entityWorld, const anim::Pose* pose) const;
  glm::dmat4 skinnedTransform(const FrameState& f, std::uint32_t prim, std::uint32_t v) const;

  struct Covered {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> rigid;    // (primitive, vertices covered)
    std::vector<std::pair<std::uint32_t, std::uint32_t>> skinned;  // (primitive, vertex within it)
  };
  const asset::CookedAsset& asset_;
  scene::MeshRef ref_;
  std::vector<InstancedPrimitive> primitives_;
  std::vector<glm::dmat4> bakeFrameInverse_;  // N_P⁻¹
  std::vector<bool> skinned_;                 // per primitive: moved by its skin when posed
  std::vector<Covered> covered_;              // per SL
  Covered all_;                               // every vertex: SLs without vertices
  std::vector<glm::vec3> centres_;
  std::vector<float> radii_;
};

}  // namespace bounce::gi::sl
