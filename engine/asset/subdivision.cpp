// Cook-time subdivision surfaces (OpenSubdiv 3.5, Far API).
//
// A node flagged with {scheme, levels} gets its mesh replaced by a refined copy: the control mesh
// (vertices welded by position) is refined uniformly `levels` times with Far::TopologyRefiner, the
// finest vertices are projected to the limit surface with Far::PrimvarRefiner::Limit, and their
// normals are the normalised cross product of the two limit tangents. UVs ride along as a
// face-varying channel (so UV seams stay seams), also evaluated at the limit. Boundaries use
// "edge and corner" interpolation, the usual choice for modelled meshes with open borders.
//
// A skinned or morphed mesh keeps its control mesh ("cage") and gets the same limit surface as
// stencils (CookedAsset LimitStencils): built once here, evaluated every frame on the posed cage
// by engine/anim (CPU) and shaders/subdivision/subdivision.comp (GPU), so the smooth surface
// bends with the skeleton.
#include "engine/asset/subdivision.hpp"

#include "engine/asset/gltf_import.hpp"
#include "engine/asset/mesh_repair.hpp"
#include "engine/core/error.hpp"
#include "engine/core/log.hpp"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>

namespace bounce::asset::detail {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;

namespace {

// Primvar types with the interface PrimvarRefiner expects (Clear, AddWithWeight).
template <int N>
struct Value {
  float v[N];
  void Clear(void* = nullptr) {
    for (float& x : v) x = 0.0f;
  }
  void AddWithWeight(const Value& src, float w) {
    for (int i = 0; i < N; ++i) v[i] += w * src.v[i];
  }
};
using V3 = Value<3>;
using V2 = Value<2>;

osd::Sdc::SchemeType schemeType(SubdivisionScheme s) {
  switch (s) {
    case SubdivisionScheme::Loop: return osd::Sdc::SCHEME_LOOP;
    case SubdivisionScheme::Bilinear: return osd::Sdc::SCHEME_BILINEAR;
    default: return osd::Sdc::SCHEME_CATMARK;
  }
}

// Limit masks over the finest level's vertices, as Far::PrimvarRefiner::Limit produces them: its
// source values are "vertex j" (Unit) and its outputs collect (j, weight) pairs (Mask).
struct Unit {
  int j;
};
struct Mask {
  std::vector<std::pair<int, float>> e;
  void Clear(void* = nullptr) { e.clear(); }
  void AddWithWeight(const Unit& src, float w) {
    if (w != 0.0f) e.emplace_back(src.j, w);
  }
};

// Limit stencils on the control vertices: limit mask (over finest vertices j) ∘ refinement
// stencil of j (over control vertices), summed in a dense scratch row, one row per finest vertex.
LimitStencils composeLimitStencils(const osd::Far::TopologyRefiner& refiner, const osd::Far::PrimvarRefiner& primvar) {
  // StencilTableFactoryReal<float>, not its StencilTableFactory wrapper: the wrapper static_casts the
  // StencilTableReal<float> it made to StencilTable, a derived type the object is not (UBSan's vptr check
  // reports it, issue 17). The base type has every accessor used here.
  using Factory = osd::Far::StencilTableFactoryReal<float>;
  Factory::Options options;
  options.generateIntermediateLevels = false;  // the finest level's vertices only, row j = finest vertex j
  options.generateControlVerts = false;
  options.generateOffsets = true;
  options.maxLevel = unsigned(refiner.GetMaxLevel());
  std::unique_ptr<const osd::Far::StencilTableReal<float>> refine(Factory::Create(refiner, options));
  const int finest = refiner.GetLevel(refiner.GetMaxLevel()).GetNumVertices();
  std::vector<Unit> units(static_cast<std::size_t>(finest));
  for (int j = 0; j < finest; ++j) units[std::size_t(j)] = Unit{j};
  std::vector<Mask> pos(units.size()), du(units.size()), dv(units.size());
  primvar.Limit(units, pos, du, dv);

  LimitStencils out;
  out.offsets.reserve(units.size() + 1);
  out.offsets.push_back(0);
  const std::size_t control = std::size_t(refiner.GetLevel(0).GetNumVertices());
  std::vector<glm::vec3> acc(control, glm::vec3(0.0f));  // (position, du, dv) weight of each control vertex
  std::vector<char> touched(control, 0);
  std::vector<std::uint32_t> row;
  const auto& sizes = refine->GetSizes();
  const auto& offsets = refine->GetOffsets();
  const auto& indices = refine->GetControlIndices();
  const auto& weights = refine->GetWeights();
  for (std::size_t v = 0; v < units.size(); ++v) {
    row.clear();
    auto add = [&](const Mask& m, int component) {
      for (const auto& [j, w] : m.e)
        for (int k = offsets[std::size_t(j)]; k < offsets[std::size_t(j)] + sizes[std::size_t(j)]; ++k) {
          const std::size_t i = std::size_t(indices[std::size_t(k)]);
          if (!touched[i]) {
            touched[i] = 1;
            row.push_back(std::uint32_t(i));
          }
          acc[i][component] += w * weights[std::size_t(k)];
        }
    };
    add(pos[v], 0);
    add(du[v], 1);
    add(dv[v], 2);
    std::sort(row.begin(), row.end());  // ascending cage vertices: reads in memory order
    for (std::uint32_t i : row) {
      out.indices.push_back(i);
      out.weights.push_back(acc[i].x);
      out.duWeights.push_back(acc[i].y);
      out.dvWeights.push_back(acc[i].z);
      acc[i] = glm::vec3(0.0f);
      touched[i] = 0;
    }
    out.offsets.push_back(std::uint32_t(out.indices.size()));
  }
  return out;
}

}  // namespace

WeldedMesh weld(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
  WeldedMesh w;
  std::map<std::array<float, 3>, std::uint32_t> index;
  std::vector<std::uint32_t> remap(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    auto [it, inserted] = index.emplace(std::array<float, 3>{positions[i].x, positions[i].y, positions[i].z},
                                        std::uint32_t(w.positions.size()));
    if (inserted) {
      w.positions.push_back(positions[i]);
      w.representative.push_back(std::uint32_t(i));
    }
    remap[i] = it->second;
  }
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t a = remap[indices[t]], b = remap[indices[t + 1]], c = remap[indices[t + 2]];
    if (a == b || b == c || a == c) continue;  // collapsed by welding: no face for OpenSubdiv
    w.triangles.insert(w.triangles.end(), {a, b, c});
    w.corners.insert(w.corners.end(), {indices[t], indices[t + 1], indices[t + 2]});
  }
  return w;
}

LimitMesh refineToLimit(const WeldedMesh& mesh, const std::vector<glm::vec2>& uv, Subdivision s, const std::string& file,
                        const std::string& where, LimitStencils* stencils) {
  using Descriptor = osd::Far::TopologyDescriptor;
  using Factory = osd::Far::TopologyRefinerFactory<Descriptor>;
  const int faces = int(mesh.triangles.size() / 3);
  if (faces == 0) throwInputError(file, where, "no triangles to subdivide", "a mesh with at least one triangle");
  std::vector<int> vertsPerFace(std::size_t(faces), 3);
  std::vector<int> faceVerts(mesh.triangles.begin(), mesh.triangles.end());
  std::vector<int> fvarIndices(mesh.corners.begin(), mesh.corners.end());
  Descriptor desc;
  desc.numVertices = int(mesh.positions.size());
  desc.numFaces = faces;
  desc.numVertsPerFace = vertsPerFace.data();
  desc.vertIndicesPerFace = faceVerts.data();
  Descriptor::FVarChannel channel;
  const bool hasUv = !uv.empty();
  if (hasUv) {
    channel.numValues = int(uv.size());
    channel.valueIndices = fvarIndices.data();
    desc.numFVarChannels = 1;
    desc.fvarChannels = &channel;
  }
  osd::Sdc::Options options;
  options.SetVtxBoundaryInterpolation(osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  options.SetFVarLinearInterpolation(osd::Sdc::Options::FVAR_LINEAR_CORNERS_ONLY);
  std::unique_ptr<osd::Far::TopologyRefiner> refiner(
      Factory::Create(desc, Factory::Options(schemeType(s.scheme), options)));
  if (!refiner) throwInputError(file, where, "OpenSubdiv rejected the mesh topology", "a valid polygon mesh");
  osd::Far::TopologyRefiner::UniformOptions uniform(int(s.levels));
  uniform.fullTopologyInLastLevel = true;  // Limit() needs the last level's full topology
  refiner->RefineUniform(uniform);

  // Interpolate level by level, then project the finest level to the limit.
  const osd::Far::PrimvarRefiner primvar(*refiner);
  std::vector<V3> verts(std::size_t(refiner->GetNumVerticesTotal()));
  std::vector<V2> fvar(hasUv ? std::size_t(refiner->GetNumFVarValuesTotal(0)) : 0);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) verts[i] = V3{{mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z}};
  for (std::size_t i = 0; i < uv.size(); ++i) fvar[i] = V2{{uv[i].x, uv[i].y}};
  V3* src = verts.data();
  V2* fsrc = fvar.data();
  for (int level = 1; level <= int(s.levels); ++level) {
    V3* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, src, dst);
    src = dst;
    if (hasUv) {
      V2* fdst = fsrc + refiner->GetLevel(level - 1).GetNumFVarValues(0);
      primvar.InterpolateFaceVarying(level, fsrc, fdst);
      fsrc = fdst;
    }
  }
  const osd::Far::TopologyLevel& finest = refiner->GetLevel(int(s.levels));
  const std::size_t n = std::size_t(finest.GetNumVertices());
  std::vector<V3> pos(n), du(n), dv(n);
  primvar.Limit(src, pos, du, dv);
  if (stencils) *stencils = composeLimitStencils(*refiner, primvar);

  LimitMesh out;
  out.verticesPerFace = s.scheme == SubdivisionScheme::Loop ? 3 : (s.levels == 0 ? 3 : 4);
  out.positions.resize(n);
  out.normals.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.positions[i] = glm::vec3(pos[i].v[0], pos[i].v[1], pos[i].v[2]);
    const glm::vec3 c = glm::cross(glm::vec3(du[i].v[0], du[i].v[1], du[i].v[2]), glm::vec3(dv[i].v[0], dv[i].v[1], dv[i].v[2]));
    const float len = glm::length(c);
    out.normals[i] = len > 0.0f && std::isfinite(len) ? c / len : glm::vec3(0.0f);  // zero: filled in by the caller
  }
  if (hasUv) {
    std::vector<V2> limitUv(std::size_t(finest.GetNumFVarValues(0)));
    primvar.LimitFaceVarying(fsrc, limitUv);
    for (const V2& u : limitUv) out.uv.emplace_back(u.v[0], u.v[1]);
  }
  for (int f = 0; f < finest.GetNumFaces(); ++f) {
    const auto fv = finest.GetFaceVertices(f);
    if (fv.size() != out.verticesPerFace)
      throwInputError(file, where, "refined face has " + std::to_string(fv.size()) + " corners", std::to_string(out.verticesPerFace));
    for (int k = 0; k < fv.size(); ++k) out.faceVertices.push_back(std::uint32_t(fv[k]));
    if (hasUv) {
      const auto fu = finest.GetFaceFVarValues(f, 0);
      for (int k = 0; k < fu.size(); ++k) out.faceUvs.push_back(std::uint32_t(fu[k]));
    }
  }
  return out;
}

Primitive subdividePrimitive(const Primitive& p, Subdivision s, const std::string& file, const std::string& where,
                             bool deformable, std::vector<std::uint32_t>* limitVertex) {
  const WeldedMesh w = weld(p.positions, p.indices);
  LimitStencils limit;
  const LimitMesh lm = refineToLimit(w, p.uv0, s, file, where, deformable ? &limit : nullptr);
  Primitive out;
  std::vector<std::uint32_t> limitOf;  // per output vertex, its limit vertex
  out.material = p.material;
  // One output vertex per distinct (limit vertex, uv value) pair.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> vertexOf;
  std::vector<std::uint32_t> corners;
  const bool hasUv = !lm.uv.empty();
  for (std::size_t c = 0; c < lm.faceVertices.size(); ++c) {
    const std::uint32_t v = lm.faceVertices[c], u = hasUv ? lm.faceUvs[c] : 0;
    auto [it, inserted] = vertexOf.emplace(std::make_pair(v, u), std::uint32_t(out.positions.size()));
    if (inserted) {
      limitOf.push_back(v);
      out.positions.push_back(lm.positions[v]);
      out.normals.push_back(lm.normals[v]);
      if (hasUv) out.uv0.push_back(lm.uv[u]);
    }
    corners.push_back(it->second);
  }
  const int n = lm.verticesPerFace;
  for (std::size_t f = 0; f + std::size_t(n) <= corners.size(); f += std::size_t(n)) {
    out.indices.insert(out.indices.end(), {corners[f], corners[f + 1], corners[f + 2]});
    if (n == 4) out.indices.insert(out.indices.end(), {corners[f], corners[f + 2], corners[f + 3]});
  }
  const RepairCounts r = repairTriangles(out);  // limit projection can collapse tiny faces at creases
  out.droppedTriangles = std::uint32_t(r.nonFinite + r.degenerate);
  if (r.removedVertices != 0) limitOf.clear();  // vertices renumbered (non-finite limit points): no row map
  if (limitVertex) *limitVertex = limitOf;
  if (deformable && !limitOf.empty()) {
    // One stencil row per output vertex (a UV seam repeats its limit vertex's row), indices on p's
    // own vertices through the weld's representatives.
    LimitStencils& st = out.stencils;
    st.offsets.push_back(0);
    for (std::uint32_t v : limitOf) {
      for (std::uint32_t k = limit.offsets[v]; k < limit.offsets[v + 1]; ++k) {
        st.indices.push_back(w.representative[limit.indices[k]]);
        st.weights.push_back(limit.weights[k]);
        st.duWeights.push_back(limit.duWeights[k]);
        st.dvWeights.push_back(limit.dvWeights[k]);
      }
      st.offsets.push_back(std::uint32_t(st.indices.size()));
    }
  } else if (deformable) {
    log::warn(file + ": " + where + ": subdivided surface has non-finite limit points; it stays in the rest pose");
  }
  // Degenerate tangents (e.g. at some boundary corners): use the area-weighted normal there.
  const auto fallback = areaWeightedNormals(out.positions, out.indices);
  for (std::size_t i = 0; i < out.normals.size(); ++i)
    if (out.normals[i] == glm::vec3(0.0f)) out.normals[i] = fallback[i];
  return out;
}

namespace {

// Resolves CookOptions::subdivision keys (node name, or index in decimal) to node indices.
std::map<std::size_t, Subdivision> requested(const ImportContext& ctx, const CookOptions& options, const CookedAsset& a) {
  std::map<std::size_t, Subdivision> out;
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    if (a.nodes[i].subdivision.levels > 0) out[i] = a.nodes[i].subdivision;
  for (const auto& [key, s] : options.subdivision) {
    bool found = false;
    for (std::size_t i = 0; i < a.nodes.size(); ++i)
      if (a.nodes[i].name == key || std::to_string(i) == key) {
        out[i] = s;
        found = true;
      }
    if (!found) ctx.fail("options/subdivision/" + key, "no node with this name or index", "a node of the asset");
    if (s.levels > 4) ctx.fail("options/subdivision/" + key, "levels " + std::to_string(s.levels), "0 to 4");
  }
  return out;
}

}  // namespace

void applySubdivision(const ImportContext& ctx, const CookOptions& options, CookedAsset& out) {
  std::map<std::tuple<std::int32_t, std::uint32_t, std::uint32_t>, std::int32_t> refinedMesh;
  for (const auto& [node, s] : requested(ctx, options, out)) {
    Node& n = out.nodes[node];
    n.subdivision = s;
    if (n.mesh < 0 || s.levels == 0) continue;
    const auto key = std::make_tuple(n.mesh, std::uint32_t(s.scheme), s.levels);
    if (auto it = refinedMesh.find(key); it != refinedMesh.end()) {
      n.mesh = it->second;
      continue;
    }
    const Mesh& src = out.meshes[std::size_t(n.mesh)];
    Mesh refined;
    refined.name = src.name + " (subdivided)";
    // A skinned or morphed mesh: keep it as the cage the refined surface follows every frame.
    bool deformable = false;
    for (const Primitive& prim : src.primitives) deformable = deformable || !prim.joints.empty() || !prim.targets.empty();
    for (std::size_t p = 0; p < src.primitives.size(); ++p) {
      const Primitive& prim = src.primitives[p];
      if (prim.indices.empty()) continue;
      Primitive r = subdividePrimitive(prim, s, ctx.file, ptr(ptr("/meshes", std::size_t(n.mesh)) + "/primitives", p),
                                       deformable);
      if (deformable) r.stencils.cagePrimitive = std::int32_t(p);
      refined.primitives.push_back(std::move(r));
    }
    if (deformable) {
      // A primitive without stencils (non-finite limit points, warned) cannot follow: then the
      // whole mesh stays static, as before cages existed.
      bool all = true;
      for (const Primitive& r : refined.primitives) all = all && !r.stencils.offsets.empty();
      for (Primitive& r : refined.primitives) {
        if (!all) r.stencils = LimitStencils{};
      }
      if (all) {
        refined.cage = n.mesh;
        refined.morphWeights = src.morphWeights;
      }
    }
    refined.bounds = meshBounds(refined.primitives);
    out.meshes.push_back(std::move(refined));
    n.mesh = std::int32_t(out.meshes.size() - 1);
    refinedMesh[key] = n.mesh;
  }
}

}  // namespace bounce::asset::detail
