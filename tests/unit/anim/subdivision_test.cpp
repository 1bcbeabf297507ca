// Per-frame subdivision of a skinned cage: the limit stencils built at cook time, evaluated on the
// posed cage (LimitStencilJob, the CPU face), equal OpenSubdiv's own refinement of the same posed
// cage (Far::PrimvarRefiner level by level, then Limit: engine/asset refineToLimit) on every
// refined vertex of CesiumMan and Fox at several clip times; on the bind cage they equal the
// cooked rest surface; the cooked format keeps them; a corrupt table is refused.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/anim/pose.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/anim/subdivision.hpp"
#include "engine/asset/cook.hpp"
#include "engine/asset/cooked_format.hpp"
#include "engine/asset/subdivision.hpp"
#include "engine/core/error.hpp"

namespace bounce::anim {
namespace {

// Stencils sum ~20–60 weighted cage points at once; OpenSubdiv's refinement sums 4–10 per level,
// then the limit mask: the same real numbers in float by different routes, so they agree to a few
// dozen ulps of the coordinates. Relative to the cage's bounding-box diagonal.
constexpr float kPositionRelTol = 1e-5f;
// Normals: limit tangents by the two routes differ by rounding; 1 − cos(angle) below this where
// the tangent plane is well defined (|du × dv| ≥ kWellDefined·|du|·|dv| in the reference).
constexpr float kNormalTol = 1e-4f;

std::filesystem::path assets() {
  const char* env = std::getenv("BOUNCE_SHARED_DIR");
  return std::filesystem::path(env && *env ? env : BOUNCE_SHARED_DIR) / "assets";
}

asset::CookedAsset cookSubdivided(const std::string& file, asset::Subdivision s) {
  const auto path = assets() / file;
  const auto cache = std::filesystem::path(BOUNCE_TEST_OUT) / "anim-subdiv-cook";
  const auto plain = asset::loadOrCook(path, cache, {false, {}});
  asset::CookOptions options{false, {}};
  for (std::size_t i = 0; i < plain.nodes.size(); ++i)
    if (plain.nodes[i].mesh >= 0) options.subdivision[std::to_string(i)] = s;
  return asset::loadOrCook(path, cache, options);
}

// The skinned mesh nodes whose mesh follows a cage.
std::vector<int> cagedNodes(const asset::CookedAsset& a) {
  std::vector<int> out;
  for (std::size_t n = 0; n < a.nodes.size(); ++n)
    if (a.nodes[n].mesh >= 0 && a.meshes[std::size_t(a.nodes[n].mesh)].cage >= 0 && isSkinned(a, int(n)))
      out.push_back(int(n));
  return out;
}

float diagonal(const asset::Bounds& b) { return glm::length(b.max - b.min); }

struct Worst {
  float position = 0.0f, normal = 0.0f;
  std::size_t vertices = 0, normals = 0;
};

// Every refined vertex of every caged node of `a`, posed with clip 0 at time t.
Worst compareWithOpenSubdiv(const asset::CookedAsset& a, asset::Subdivision s, float t) {
  Worst worst;
  Pose pose;
  evaluatePose(a, a.animations.empty() ? -1 : 0, t, pose);
  for (int n : cagedNodes(a)) {
    const asset::Mesh& mesh = a.meshes[std::size_t(a.nodes[std::size_t(n)].mesh)];
    // The same node drawing its cage: posePrimitive there is the posed cage (morph + skinning).
    asset::CookedAsset caged = a;
    caged.nodes[std::size_t(n)].mesh = mesh.cage;
    for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const asset::Primitive& refined = mesh.primitives[pi];
      const std::size_t cp = std::size_t(refined.stencils.cagePrimitive);
      const asset::Primitive& cage = a.meshes[std::size_t(mesh.cage)].primitives[cp];
      std::vector<glm::vec3> P, N, cageP, cageN;
      EXPECT_TRUE(posePrimitive(a, n, pi, &pose, P, N));
      EXPECT_TRUE(posePrimitive(caged, n, cp, &pose, cageP, cageN));
      // OpenSubdiv's own refinement of the posed cage: the bind cage's welded topology (as the
      // cook welds it), each welded vertex at its representative's posed position.
      asset::detail::WeldedMesh w = asset::detail::weld(cage.positions, cage.indices);
      for (std::size_t i = 0; i < w.positions.size(); ++i) w.positions[i] = cageP[w.representative[i]];
      const auto lm = asset::detail::refineToLimit(w, cage.uv0, s, "test", "posed cage");
      std::vector<std::uint32_t> limitVertex;
      const asset::Primitive again = asset::detail::subdividePrimitive(cage, s, "test", "cage", true, &limitVertex);
      EXPECT_EQ(again.positions, refined.positions);  // the cook is deterministic: same row order
      EXPECT_EQ(limitVertex.size(), P.size());
      if (limitVertex.size() != P.size()) continue;
      asset::Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
      for (const auto& p : cageP) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
      }
      const float size = diagonal(b);
      for (std::size_t o = 0; o < P.size(); ++o) {
        const std::uint32_t v = limitVertex[o];
        worst.position = std::max(worst.position, glm::distance(P[o], lm.positions[v]) / size);
        ++worst.vertices;
        if (lm.normals[v] != glm::vec3(0.0f)) {
          worst.normal = std::max(worst.normal, 1.0f - glm::dot(N[o], lm.normals[v]));
          ++worst.normals;
        }
      }
    }
  }
  return worst;
}

std::string sci(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3e", v);
  return b;
}

TEST(Subdivision, SkinnedCageRefinedPerFrameEqualsOpenSubdivOnThePosedCage) {
  struct Case {
    const char* label;
    const char* file;
    asset::Subdivision s;
    std::size_t minVertices;
  };
  const asset::Subdivision cc1{asset::SubdivisionScheme::CatmullClark, 1};
  const asset::Subdivision cc2{asset::SubdivisionScheme::CatmullClark, 2};
  const asset::Subdivision loop1{asset::SubdivisionScheme::Loop, 1};
  for (const Case& c : {Case{"CesiumMan-cc1", "CesiumMan/glTF-Binary/CesiumMan.glb", cc1, 10000},
                        Case{"CesiumMan-loop1", "CesiumMan/glTF-Binary/CesiumMan.glb", loop1, 10000},
                        Case{"Fox-cc2", "Fox/glTF-Binary/Fox.glb", cc2, 10000}}) {
    SCOPED_TRACE(c.label);
    const auto a = cookSubdivided(c.file, c.s);
    ASSERT_FALSE(cagedNodes(a).empty()) << "the skinned mesh kept its cage";
    for (float t : {0.0f, 0.37f, 1.1f}) {
      SCOPED_TRACE(t);
      const Worst w = compareWithOpenSubdiv(a, c.s, t);
      EXPECT_GE(w.vertices, c.minVertices);
      EXPECT_GE(w.normals, w.vertices * 9 / 10);
      EXPECT_LE(w.position, kPositionRelTol);
      EXPECT_LE(w.normal, kNormalTol);
      RecordProperty(std::string(c.label) + "-worst-rel-position-t" + std::to_string(int(t * 100)), sci(w.position));
      RecordProperty(std::string(c.label) + "-worst-normal-t" + std::to_string(int(t * 100)), sci(w.normal));
    }
  }
}

TEST(Subdivision, StencilsOnTheBindCageGiveTheCookedRestSurface) {
  const auto a = cookSubdivided("CesiumMan/glTF-Binary/CesiumMan.glb", {asset::SubdivisionScheme::CatmullClark, 2});
  std::size_t checked = 0;
  for (const auto& mesh : a.meshes) {
    if (mesh.cage < 0) continue;
    const float size = diagonal(a.meshes[std::size_t(mesh.cage)].bounds);
    for (const auto& p : mesh.primitives) {
      const auto& cage = a.meshes[std::size_t(mesh.cage)].primitives[std::size_t(p.stencils.cagePrimitive)];
      std::vector<glm::vec3> P(p.positions.size()), N(p.positions.size());
      ASSERT_TRUE((LimitStencilJob{&p.stencils, cage.positions, cage.normals, P, N}.run()));
      for (std::size_t v = 0; v < P.size(); ++v) {
        EXPECT_LE(glm::distance(P[v], p.positions[v]), kPositionRelTol * size) << v;
        ++checked;
      }
      // Position weights are an affine combination (they sum to 1): translating the cage
      // translates the surface. And each tangent's weights sum to 0.
      for (std::size_t v = 0; v + 1 < p.stencils.offsets.size(); ++v) {
        double w = 0, wu = 0, wv = 0;
        for (std::uint32_t k = p.stencils.offsets[v]; k < p.stencils.offsets[v + 1]; ++k) {
          w += p.stencils.weights[k];
          wu += p.stencils.duWeights[k];
          wv += p.stencils.dvWeights[k];
        }
        ASSERT_NEAR(w, 1.0, 1e-5) << v;
        ASSERT_NEAR(wu, 0.0, 1e-4) << v;
        ASSERT_NEAR(wv, 0.0, 1e-4) << v;
      }
    }
  }
  EXPECT_GT(checked, 40000u);  // CesiumMan's 3273 cage vertices, level 2
  // Serial and parallel evaluation are the same arithmetic per row: bit-identical.
  for (const auto& mesh : a.meshes) {
    if (mesh.cage < 0) continue;
    const auto& p = mesh.primitives[0];
    const auto& cage = a.meshes[std::size_t(mesh.cage)].primitives[std::size_t(p.stencils.cagePrimitive)];
    std::vector<glm::vec3> P1(p.positions.size()), N1(P1.size()), P2(P1.size()), N2(P1.size());
    ASSERT_TRUE((LimitStencilJob{&p.stencils, cage.positions, cage.normals, P1, N1, true}.run()));
    ASSERT_TRUE((LimitStencilJob{&p.stencils, cage.positions, cage.normals, P2, N2, false}.run()));
    EXPECT_EQ(P1, P2);
    EXPECT_EQ(N1, N2);
  }
}

TEST(Subdivision, JobRejectsMismatchedSpans) {
  const auto a = cookSubdivided("Fox/glTF-Binary/Fox.glb", {asset::SubdivisionScheme::CatmullClark, 1});
  const int n = cagedNodes(a).at(0);
  const auto& mesh = a.meshes[std::size_t(a.nodes[std::size_t(n)].mesh)];
  const auto& p = mesh.primitives[0];
  const auto& cage = a.meshes[std::size_t(mesh.cage)].primitives[0];
  std::vector<glm::vec3> P(p.positions.size()), N(P.size());
  const std::vector<glm::vec3> shortCage(cage.positions.begin(), cage.positions.begin() + std::ptrdiff_t(cage.positions.size() / 2));
  EXPECT_FALSE((LimitStencilJob{&p.stencils, shortCage, shortCage, P, N}.validate()));
  std::vector<glm::vec3> fewer(P.size() - 1);
  EXPECT_FALSE((LimitStencilJob{&p.stencils, cage.positions, cage.normals, fewer, N}.validate()));
  EXPECT_TRUE((LimitStencilJob{&p.stencils, cage.positions, cage.normals, P, N}.validate()));
}

TEST(Subdivision, CookedFormatKeepsTheStencilsAndRefusesACorruptTable) {
  const auto a = cookSubdivided("Fox/glTF-Binary/Fox.glb", {asset::SubdivisionScheme::CatmullClark, 1});
  const auto bytes = asset::serializeCooked(a);
  EXPECT_EQ(asset::parseCooked(bytes, "fox.bcook"), a);
  std::size_t refined = 0;
  for (std::size_t m = 0; m < a.meshes.size(); ++m) {
    if (a.meshes[m].cage < 0) continue;
    ++refined;
    auto bad = a;
    bad.meshes[m].primitives[0].stencils.indices[3] = 1u << 30;
    try {
      asset::validate(bad, "fox.bcook");
      ADD_FAILURE() << "a stencil index past the cage was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("fox.bcook: meshes/" + std::to_string(m) + "/primitives/0/stencils/indices/3: index 1073741824"),
                std::string::npos)
          << e.what();
    }
    auto selfCage = a;
    selfCage.meshes[m].cage = std::int32_t(m);
    EXPECT_THROW(asset::validate(selfCage, "fox.bcook"), InputError);
  }
  EXPECT_EQ(refined, 1u);
}

}  // namespace
}  // namespace bounce::anim
