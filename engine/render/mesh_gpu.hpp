#pragma once
// A cooked mesh on the GPU: one interleaved vertex buffer (MeshVertex) and one uint32 index
// buffer holding every primitive, each primitive a range of indices.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gpu/buffer.hpp"

namespace bounce::render {

struct MeshGpu {
  struct Primitive {
    std::uint32_t firstIndex = 0;
    std::uint32_t indexCount = 0;
    std::int32_t vertexOffset = 0;
    std::uint32_t material = 0;  // index into the asset's materials
  };
  gpu::Buffer vertices;
  gpu::Buffer indices;
  std::vector<Primitive> primitives;
  // A mesh posed on the GPU (used by a deformed node: skinned, every primitive weighted, or with
  // morph targets): its bind-pose vertices with joints and weights (SkinVertex, the skinning
  // pass's input), in the same order as `vertices`. Empty otherwise (then posed on the CPU).
  gpu::Buffer skinVertices;
  std::uint32_t vertexCount = 0;
  // Its morph targets (the most any primitive has; a primitive with fewer, or a target without
  // normals, has zero displacements there): Δp, Δn as vec4 pairs, target-major (skinning.comp),
  // and each target's displacement box (morphMin/Max[t]) for the posed instance's bounds.
  gpu::Buffer morphDeltas;
  std::uint32_t morphTargets = 0;
  std::vector<glm::vec3> morphMin, morphMax;
  // A subdivided mesh of a deformed cage (asset::Mesh::cage): its limit stencils on the cage's
  // vertices (StencilRow per vertex of `vertices`, StencilWeight per weight), read by the
  // subdivision pass when the cage is skinned on the GPU. Empty otherwise.
  const MeshGpu* cage = nullptr;
  gpu::Buffer stencilRows, stencilWeights;
};

}  // namespace bounce::render
