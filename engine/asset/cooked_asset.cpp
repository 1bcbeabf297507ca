// CookedAsset invariants (see cooked_asset.hpp). validate() runs after every cook and every read,
// so downstream code may index without checks.
#include "engine/asset/cooked_asset.hpp"

#include "engine/core/error.hpp"

#include <cmath>

namespace bounce::asset {

std::size_t CookedAsset::triangleCount() const {
  std::size_t n = 0;
  for (const auto& m : meshes)
    for (const auto& p : m.primitives) n += p.indices.size() / 3;
  return n;
}

std::size_t CookedAsset::droppedTriangleCount() const {
  std::size_t n = 0;
  for (const auto& m : meshes)
    for (const auto& p : m.primitives) n += p.droppedTriangles;
  return n;
}

namespace {

std::string at(const std::string& base, std::size_t i) { return base + "/" + std::to_string(i); }

// Mesh::cage and Primitive::stencils: a cage without a cage of its own, every stencil row inside
// its index range and every index inside the cage primitive, finite weights.
void validateStencils(const CookedAsset& a, std::size_t m, std::size_t p, const std::string& file) {
  const Mesh& mesh = a.meshes[m];
  const Primitive& prim = mesh.primitives[p];
  const LimitStencils& st = prim.stencils;
  const std::string where = at(at("meshes", m) + "/primitives", p) + "/stencils";
  if (mesh.cage < 0) {
    if (st.present() || !st.offsets.empty() || !st.indices.empty())
      throwInputError(file, where, "stencils on a mesh without a cage", "none");
    return;
  }
  if (std::size_t(mesh.cage) >= a.meshes.size() || std::size_t(mesh.cage) == m || a.meshes[std::size_t(mesh.cage)].cage != -1)
    throwInputError(file, at("meshes", m) + "/cage", "cage " + std::to_string(mesh.cage),
                    "another mesh of the asset without a cage of its own");
  const Mesh& cage = a.meshes[std::size_t(mesh.cage)];
  if (st.cagePrimitive < 0 || std::size_t(st.cagePrimitive) >= cage.primitives.size())
    throwInputError(file, where + "/cagePrimitive", std::to_string(st.cagePrimitive),
                    "< " + std::to_string(cage.primitives.size()));
  const std::size_t n = prim.positions.size(), e = st.indices.size();
  const std::size_t cageVertices = cage.primitives[std::size_t(st.cagePrimitive)].positions.size();
  if (st.offsets.size() != n + 1 || st.offsets.front() != 0 || st.offsets.back() != e || st.weights.size() != e ||
      st.duWeights.size() != e || st.dvWeights.size() != e)
    throwInputError(file, where, "stencil table sizes do not match", std::to_string(n + 1) + " offsets from 0 to the weight count");
  for (std::size_t v = 0; v < n; ++v)
    if (st.offsets[v] > st.offsets[v + 1]) throwInputError(file, at(where + "/offsets", v + 1), "decreasing offset", "non-decreasing");
  for (std::size_t k = 0; k < e; ++k) {
    if (st.indices[k] >= cageVertices)
      throwInputError(file, at(where + "/indices", k), "index " + std::to_string(st.indices[k]), "< " + std::to_string(cageVertices));
    if (!std::isfinite(st.weights[k]) || !std::isfinite(st.duWeights[k]) || !std::isfinite(st.dvWeights[k]))
      throwInputError(file, at(where + "/weights", k), "non-finite weight", "finite numbers");
  }
}

}  // namespace

void validate(const CookedAsset& a, const std::string& file) {
  auto ref = [&](const std::string& where, std::int32_t i, std::size_t size) {
    if (i < -1 || (i >= 0 && std::size_t(i) >= size))
      throwInputError(file, where, "reference " + std::to_string(i) + " out of range", "-1 or < " + std::to_string(size));
  };
  auto need = [&](const std::string& where, std::int32_t i, std::size_t size) {
    if (i < 0 || std::size_t(i) >= size)
      throwInputError(file, where, "index " + std::to_string(i) + " out of range", "< " + std::to_string(size));
  };
  for (std::size_t m = 0; m < a.meshes.size(); ++m)
    for (std::size_t p = 0; p < a.meshes[m].primitives.size(); ++p) {
      const Primitive& prim = a.meshes[m].primitives[p];
      const std::string where = at(at("meshes", m) + "/primitives", p);
      const std::size_t n = prim.positions.size();
      auto sized = [&](const char* what, std::size_t size, bool optional) {
        if (size != n && !(optional && size == 0))
          throwInputError(file, where + "/" + what, std::to_string(size) + " values", std::to_string(n) + " (one per vertex)");
      };
      sized("normals", prim.normals.size(), false);
      sized("uv0", prim.uv0.size(), true);
      sized("joints", prim.joints.size(), true);
      sized("weights", prim.weights.size(), true);
      sized("joints1", prim.joints1.size(), true);
      sized("weights1", prim.weights1.size(), true);
      if (prim.joints.size() != prim.weights.size() || prim.joints1.size() != prim.weights1.size() ||
          (!prim.joints1.empty() && prim.joints.empty()))
        throwInputError(file, where + "/joints", "joint and weight sets do not pair up", "JOINTS_n with WEIGHTS_n, set 1 only with set 0");
      for (std::size_t t = 0; t < prim.targets.size(); ++t) {
        sized(("targets/" + std::to_string(t) + "/positions").c_str(), prim.targets[t].positions.size(), true);
        sized(("targets/" + std::to_string(t) + "/normals").c_str(), prim.targets[t].normals.size(), true);
      }
      if (prim.indices.size() % 3 != 0) throwInputError(file, where + "/indices", "not whole triangles", "a multiple of 3");
      for (std::size_t i = 0; i < prim.indices.size(); ++i)
        if (prim.indices[i] >= n)
          throwInputError(file, at(where + "/indices", i), "index " + std::to_string(prim.indices[i]), "< " + std::to_string(n));
      for (const auto& q : prim.positions)
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
          throwInputError(file, where + "/positions", "non-finite position", "finite numbers");
      ref(where + "/material", prim.material, a.materials.size());
      validateStencils(a, m, p, file);
    }
  for (std::size_t m = 0; m < a.materials.size(); ++m) {
    ref(at("materials", m) + "/baseColorTexture", a.materials[m].baseColorTexture.texture, a.textures.size());
    ref(at("materials", m) + "/emissiveTexture", a.materials[m].emissiveTexture.texture, a.textures.size());
  }
  for (std::size_t t = 0; t < a.textures.size(); ++t) {
    const Texture& tex = a.textures[t];
    if (!tex.pixels.empty() && tex.pixels.size() != std::size_t(tex.width) * tex.height * 4)
      throwInputError(file, at("textures", t), std::to_string(tex.pixels.size()) + " pixel bytes",
                      std::to_string(std::size_t(tex.width) * tex.height * 4) + " (RGBA8) or none");
  }
  std::vector<int> parents(a.nodes.size(), 0);
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const Node& n = a.nodes[i];
    const std::string where = at("nodes", i);
    ref(where + "/mesh", n.mesh, a.meshes.size());
    ref(where + "/camera", n.camera, a.cameras.size());
    ref(where + "/light", n.light, a.lights.size());
    ref(where + "/skin", n.skin, a.skins.size());
    if (n.vlm.present) {  // the same rules as the importer's extras.bounce_vlm check
      const NodeVlm& v = n.vlm;
      auto in = [](glm::vec3 c, float lo, float hi) {
        return std::isfinite(c.x + c.y + c.z) && glm::all(glm::greaterThanEqual(c, glm::vec3(lo))) &&
               glm::all(glm::lessThanEqual(c, glm::vec3(hi)));
      };
      if (n.mesh < 0 || v.tag < 1 || v.tag > (1u << 24) || !in(v.color, 0.0f, 3e38f) ||
          !(v.intensity >= 0.0f && v.intensity <= 1e6f) || !in(v.reflectance, 0.0f, 1.0f))
        throwInputError(file, where + "/vlm", "invalid bounce_vlm extras", "a mesh node, tag in [1, 2^24], colour >= 0, "
                                                                           "intensity in [0, 1e6], reflectance in [0, 1]");
    }
    for (std::size_t c = 0; c < n.children.size(); ++c) {
      need(at(where + "/children", c), n.children[c], a.nodes.size());
      if (++parents[std::size_t(n.children[c])] > 1 || std::size_t(n.children[c]) == i)
        throwInputError(file, at(where + "/children", c), "node with several parents", "a forest of nodes");
    }
  }
  // With at most one parent each, the graph is a forest iff walking up from every node ends.
  std::vector<int> parent(a.nodes.size(), -1);
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    for (std::int32_t c : a.nodes[i].children) parent[std::size_t(c)] = int(i);
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    std::size_t steps = 0;
    for (int p = parent[i]; p != -1; p = parent[std::size_t(p)])
      if (++steps > a.nodes.size()) throwInputError(file, at("nodes", i), "node is its own ancestor", "no cycles");
  }
  for (std::size_t r = 0; r < a.rootNodes.size(); ++r) need(at("rootNodes", r), a.rootNodes[r], a.nodes.size());
  for (std::size_t s = 0; s < a.skins.size(); ++s) {
    for (std::size_t j = 0; j < a.skins[s].joints.size(); ++j) need(at(at("skins", s) + "/joints", j), a.skins[s].joints[j], a.nodes.size());
    ref(at("skins", s) + "/skeleton", a.skins[s].skeleton, a.nodes.size());
    if (a.skins[s].inverseBindMatrices.size() != a.skins[s].joints.size())
      throwInputError(file, at("skins", s), "inverse bind matrix count differs from joint count", "one per joint");
  }
  for (std::size_t i = 0; i < a.animations.size(); ++i) {
    const Animation& an = a.animations[i];
    for (std::size_t s = 0; s < an.samplers.size(); ++s) {
      const auto& smp = an.samplers[s];
      const std::size_t keys = smp.input.size() * (smp.interpolation == Interpolation::CubicSpline ? 3 : 1);
      if (smp.components == 0 || smp.output.size() != keys * smp.components)
        throwInputError(file, at(at("animations", i) + "/samplers", s), "output size does not match keys × components",
                        std::to_string(keys) + " × " + std::to_string(smp.components));
    }
    for (std::size_t c = 0; c < an.channels.size(); ++c) {
      need(at(at("animations", i) + "/channels", c) + "/sampler", an.channels[c].sampler, an.samplers.size());
      need(at(at("animations", i) + "/channels", c) + "/node", an.channels[c].node, a.nodes.size());
    }
  }
  validateSkinsAndAnimations(a, file);
}

}  // namespace bounce::asset
