#pragma once
// Internal: primitive clean-up steps of the cook (see mesh_repair.cpp for the documented repairs).
#include "engine/asset/cooked_asset.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bounce::asset::detail {

// glTF primitive modes (glTF 2.0 §3.7.2.1).
enum : int { kModePoints = 0, kModeLines = 1, kModeLineLoop = 2, kModeLineStrip = 3, kModeTriangles = 4,
             kModeTriangleStrip = 5, kModeTriangleFan = 6 };

// Converts a strip or fan index list into a triangle list (glTF 2.0 §3.7.2.1 winding); a triangle
// list is returned as is.
std::vector<std::uint32_t> toTriangleList(int mode, std::vector<std::uint32_t> indices);

struct RepairCounts {
  std::size_t nonFinite = 0;   // triangles dropped for a NaN/Inf vertex position
  std::size_t degenerate = 0;  // triangles dropped for zero area
  std::size_t removedVertices = 0;
};

// Drops bad triangles and, when vertices with non-finite positions exist, the vertices no
// triangle uses. Works on every per-vertex array of `p`.
RepairCounts repairTriangles(Primitive& p);

// Area-weighted vertex normals: each triangle adds its unnormalised cross product (length = twice
// its area) to its three vertices, then each sum is normalised. Vertices with a zero sum get +Y.
std::vector<glm::vec3> areaWeightedNormals(const std::vector<glm::vec3>& positions,
                                          const std::vector<std::uint32_t>& indices);

// Bounds over the positions of every primitive of a mesh (zero box when it has none).
Bounds meshBounds(const std::vector<Primitive>& primitives);

}  // namespace bounce::asset::detail
