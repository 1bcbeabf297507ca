// Cook-time subdivision: limit positions and normals from Far (PrimvarRefiner::Limit) checked
// against an independent evaluation of the same limit surface with Bfr::Surface, plus the
// refined meshes' exact face counts.
#include "engine/asset/mesh_repair.hpp"
#include "engine/asset/subdivision.hpp"
#include "tests/unit/asset/test_util.hpp"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <memory>

namespace bounce::asset::test {
namespace {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;

// Far and Bfr evaluate the same bicubic/box-spline patches in float by different routes
// (stencils after refinement vs. patch points); they agree to float rounding of coordinates of
// size ~1. Relative to the mesh size.
constexpr float kLimitTolerance = 1e-5f;
// Normals: same surfaces, derivatives differ by rounding; 1 - cos(angle) below this.
constexpr float kNormalTolerance = 1e-4f;

std::unique_ptr<osd::Far::TopologyRefiner> baseRefiner(const detail::WeldedMesh& w, osd::Sdc::SchemeType scheme) {
  using Descriptor = osd::Far::TopologyDescriptor;
  static thread_local std::vector<int> counts, verts;
  counts.assign(w.triangles.size() / 3, 3);
  verts.assign(w.triangles.begin(), w.triangles.end());
  Descriptor d;
  d.numVertices = int(w.positions.size());
  d.numFaces = int(counts.size());
  d.numVertsPerFace = counts.data();
  d.vertIndicesPerFace = verts.data();
  osd::Sdc::Options o;
  o.SetVtxBoundaryInterpolation(osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  return std::unique_ptr<osd::Far::TopologyRefiner>(osd::Far::TopologyRefinerFactory<Descriptor>::Create(
      d, osd::Far::TopologyRefinerFactory<Descriptor>::Options(scheme, o)));
}

void compareWithBfr(const Primitive& prim, SubdivisionScheme scheme, osd::Sdc::SchemeType type) {
  const bool smooth = scheme != SubdivisionScheme::Bilinear;
  const detail::WeldedMesh w = detail::weld(prim.positions, prim.indices);
  const detail::LimitMesh lm = detail::refineToLimit(w, {}, {scheme, 2}, "test", "mesh");
  ASSERT_GE(lm.positions.size(), w.positions.size());
  const auto refiner = baseRefiner(w, type);
  ASSERT_TRUE(refiner);
  osd::Bfr::RefinerSurfaceFactory<> factory(*refiner);
  osd::Bfr::Surface<float> surface;
  const Bounds b = detail::meshBounds({prim});
  const float size = glm::length(b.max - b.min);
  std::vector<float> patch;
  std::size_t checkedNormals = 0;
  float worst = 0.0f;
  for (std::size_t f = 0; f < w.triangles.size() / 3; ++f) {
    ASSERT_TRUE(factory.InitVertexSurface(int(f), &surface)) << "face " << f;
    patch.resize(std::size_t(surface.GetNumPatchPoints()) * 3);
    surface.PreparePatchPoints(&w.positions[0].x, 3, patch.data(), 3);
    for (int k = 0; k < 3; ++k) {
      float uv[2], P[3], du[3], dv[3];
      surface.GetParameterization().GetVertexCoord(k, uv);
      surface.Evaluate(uv, patch.data(), 3, P, du, dv);
      const std::uint32_t v = w.triangles[3 * f + std::size_t(k)];
      const float err = glm::distance(glm::vec3(P[0], P[1], P[2]), lm.positions[v]);
      worst = std::max(worst, err);
      const glm::vec3 n = glm::cross(glm::vec3(du[0], du[1], du[2]), glm::vec3(dv[0], dv[1], dv[2]));
      // Bilinear limit surfaces have creases at every control vertex (one normal per incident
      // face), so only the smooth schemes have one normal to compare.
      if (smooth && glm::length(n) > 1e-6f * size * size && lm.normals[v] != glm::vec3(0.0f)) {
        EXPECT_GT(glm::dot(glm::normalize(n), lm.normals[v]), 1.0f - kNormalTolerance) << "face " << f << " corner " << k;
        ++checkedNormals;
      }
    }
  }
  EXPECT_LE(worst, kLimitTolerance * size);
  if (smooth) EXPECT_GT(checkedNormals, w.triangles.size() / 2);
}

struct Case {
  SubdivisionScheme scheme;
  osd::Sdc::SchemeType type;
  const char* name;
};
const Case kCases[] = {{SubdivisionScheme::CatmullClark, osd::Sdc::SCHEME_CATMARK, "catmull-clark"},
                       {SubdivisionScheme::Loop, osd::Sdc::SCHEME_LOOP, "loop"},
                       {SubdivisionScheme::Bilinear, osd::Sdc::SCHEME_BILINEAR, "bilinear"}};

TEST(Subdivision, LimitPositionsAndNormalsMatchBfrOnBox) {
  const CookedAsset box = cook(assets() / "Box/glTF/Box.gltf", geometryOnly());
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    compareWithBfr(box.meshes[0].primitives[0], c.scheme, c.type);
  }
}

TEST(Subdivision, LimitPositionsAndNormalsMatchBfrOnSuzanne) {
  const CookedAsset suzanne = cook(assets() / "Suzanne/glTF/Suzanne.gltf", geometryOnly());
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    compareWithBfr(suzanne.meshes[0].primitives[0], c.scheme, c.type);
  }
}

TEST(Subdivision, NodeExtrasAndOptionsRefineTheBox) {
  const fs::path dir = scratch();
  copyFolder(assets() / "Box/glTF", dir);
  auto doc = readJson(dir / "Box.gltf");
  doc["nodes"][1]["extras"]["subdivision"] = {{"scheme", "catmull-clark"}, {"levels", 2}};
  writeJson(dir / "Sub.gltf", doc);
  const CookedAsset a = cook(dir / "Sub.gltf", geometryOnly());
  // 12 triangles → 36 quads at level 1 → 144 quads at level 2 → 288 triangles.
  ASSERT_EQ(a.meshes.size(), 2u);  // the original stays for other users of mesh 0
  EXPECT_EQ(a.nodes[1].mesh, 1);
  EXPECT_EQ(a.nodes[1].subdivision, (Subdivision{SubdivisionScheme::CatmullClark, 2}));
  EXPECT_EQ(a.meshes[1].primitives[0].indices.size() / 3, 288u);
  // The limit surface of a cube lies strictly inside it, and its normals point outwards.
  EXPECT_LT(a.meshes[1].bounds.max.x, 0.5f);
  EXPECT_GT(a.meshes[1].bounds.min.x, -0.5f);
  const Primitive& p = a.meshes[1].primitives[0];
  for (std::size_t i = 0; i < p.positions.size(); ++i) EXPECT_GT(glm::dot(p.normals[i], p.positions[i]), 0.0f) << i;

  CookOptions o = geometryOnly();
  o.subdivision["1"] = {SubdivisionScheme::Loop, 1};  // by index, overriding the extras
  const CookedAsset loop = cook(dir / "Sub.gltf", o);
  EXPECT_EQ(loop.meshes[1].primitives[0].indices.size() / 3, 48u);  // 12 × 4
  o.subdivision.clear();
  o.subdivision["no such node"] = {SubdivisionScheme::Loop, 1};
  expectInputError([&] { (void)cook(dir / "Sub.gltf", o); }, {"Sub.gltf: options/subdivision/no such node: no node"});
  doc["nodes"][1]["extras"]["subdivision"] = {{"scheme", "sqrt3"}, {"levels", 1}};
  writeJson(dir / "Sub.gltf", doc);
  expectInputError([&] { (void)cook(dir / "Sub.gltf", geometryOnly()); },
                   {"Sub.gltf: /nodes/1/extras/subdivision/scheme: unknown scheme \"sqrt3\""});
}

TEST(Subdivision, UvSeamsSurviveAsFaceVaryingData) {
  // BoxTextured has UV seams on cube edges: after refinement every UV stays inside the range of
  // the original UVs (face-varying limits are convex combinations) and the vertex count exceeds
  // the welded count (seams kept split).
  CookOptions o = geometryOnly();
  o.subdivision["1"] = {SubdivisionScheme::CatmullClark, 1};
  const CookedAsset a = cook(assets() / "BoxTextured/glTF/BoxTextured.gltf", o);
  const Primitive& src = a.meshes[0].primitives[0];
  glm::vec2 lo(INFINITY), hi(-INFINITY);
  for (const auto& uv : src.uv0) lo = glm::min(lo, uv), hi = glm::max(hi, uv);
  const Primitive& p = a.meshes.back().primitives[0];
  ASSERT_EQ(p.uv0.size(), p.positions.size());
  EXPECT_EQ(p.indices.size() / 3, 72u);
  for (const auto& uv : p.uv0) {
    EXPECT_GE(uv.x, lo.x);
    EXPECT_LE(uv.x, hi.x);
    EXPECT_GE(uv.y, lo.y);
    EXPECT_LE(uv.y, hi.y);
  }
  EXPECT_GT(p.positions.size(), 26u);  // 8 + 12 + 6 vertices on the welded level-1 cube
}

}  // namespace
}  // namespace bounce::asset::test
