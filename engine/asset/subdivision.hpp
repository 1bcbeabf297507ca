#pragma once
// Internal (exposed for tests): cook-time subdivision with OpenSubdiv.
#include "engine/asset/cooked_asset.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace bounce::asset::detail {

// A primitive's triangles with vertices welded by exact position: glTF splits vertices at UV and
// normal seams, but the subdivision surface must see one connected control mesh.
struct WeldedMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> representative;  // per welded vertex: its first original vertex
  std::vector<std::uint32_t> triangles;  // 3 welded indices per triangle
  std::vector<std::uint32_t> corners;    // per triangle corner: the original vertex index
};
WeldedMesh weld(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices);

// Uniform refinement to `s.levels`, then every finest-level vertex projected to the limit surface
// (Far::PrimvarRefiner::Limit). With OpenSubdiv's default ordering (vertex children first) the
// first `mesh.positions.size()` limit vertices are the limit points of the control vertices.
struct LimitMesh {
  std::vector<glm::vec3> positions;  // per finest vertex, on the limit surface
  std::vector<glm::vec3> normals;    // normalize(cross(du, dv)) of the limit tangents
  std::vector<glm::vec2> uv;         // per finest face-varying value (empty when no uv given)
  std::vector<std::uint32_t> faceVertices;  // finest faces (quads, or triangles for loop), flattened
  std::vector<std::uint32_t> faceUvs;       // matching face-varying indices (when uv given)
  int verticesPerFace = 4;
};
// `uv` (may be empty) is indexed by mesh.corners (the original vertex of each corner).
// With `stencils`, also the same limit points and tangents as linear functions of the control
// vertices (one row per finest vertex, indices into mesh.positions; cagePrimitive left -1): the
// refinement stencils of Far::StencilTableFactory composed with the limit masks of
// Far::PrimvarRefiner::Limit, so evaluating them on mesh.positions gives what this function
// returns, up to float rounding.
LimitMesh refineToLimit(const WeldedMesh& mesh, const std::vector<glm::vec2>& uv, Subdivision s,
                        const std::string& file, const std::string& where, LimitStencils* stencils = nullptr);

// Subdivides one primitive into an indexed triangle list. Joints, weights and morph targets have
// no meaning on the refined surface and are dropped; with `deformable`, the result instead gets
// LimitStencils on p's vertices (indices: each welded vertex's representative, cagePrimitive
// still -1 for the caller to set), so it follows p's posed vertices every frame. `limitVertex`
// (optional, for tests): per output vertex, its vertex of refineToLimit(weld(p), …).
Primitive subdividePrimitive(const Primitive& p, Subdivision s, const std::string& file, const std::string& where,
                             bool deformable = false, std::vector<std::uint32_t>* limitVertex = nullptr);

}  // namespace bounce::asset::detail
