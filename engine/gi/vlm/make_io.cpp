// Subtractive VLM creation, the files: real geometry in (a level or one glTF asset), an editable
// glTF and a level snippet out (make.hpp).
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "engine/asset/gltf_buffer.hpp"

#include <limits>
#include <sstream>

#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/gi/vlm/make.hpp"
#include "engine/scene/asset_instances.hpp"
#include "engine/scene/components.hpp"

namespace bounce::gi::vlm {
namespace {

constexpr int kArrayBuffer = 34962;         // glTF bufferView.target for vertex attributes
constexpr int kElementArrayBuffer = 34963;  // and for indices

// Appends the real mesh nodes of `ref`'s subtree (placed by `world`) to `s`: positions, indices,
// and the area-weighted albedo sums (rgb·area, area). Mirroring matrices flip the winding back.
void appendReal(const asset::CookedAsset& a, const scene::MeshRef& ref, const glm::mat4& world,
                const scene::MaterialOverride* over, MakeSource& s, glm::dvec4& albedo, int onlyNode = -2) {
  scene::forEachInstancedNode(a, ref, world, [&](int n, const glm::mat4& m) {
    const asset::Node& node = a.nodes[std::size_t(n)];
    if (node.mesh < 0 || node.vlm.present || (onlyNode != -2 && n != onlyNode)) return;
    const bool mirror = glm::determinant(glm::mat3(m)) < 0.0f;
    for (const asset::Primitive& p : a.meshes[std::size_t(node.mesh)].primitives) {
      glm::vec3 base(1.0f);
      if (p.material >= 0) base = glm::vec3(a.materials[std::size_t(p.material)].baseColorFactor);
      if (over && over->albedo) base = *over->albedo;
      const auto first = std::uint32_t(s.positions.size());
      for (const glm::vec3& v : p.positions) s.positions.push_back(glm::vec3(m * glm::vec4(v, 1.0f)));
      for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const std::uint32_t i0 = first + p.indices[t], i1 = first + p.indices[t + 1], i2 = first + p.indices[t + 2];
        s.indices.insert(s.indices.end(), {i0, mirror ? i2 : i1, mirror ? i1 : i2});
        const double area = 0.5 * glm::length(glm::cross(s.positions[i1] - s.positions[i0], s.positions[i2] - s.positions[i0]));
        albedo += glm::dvec4(glm::dvec3(base) * area, area);
      }
    }
  });
}

void finish(MakeSource& s, const glm::dvec4& albedo, std::vector<MakeSource>& out) {
  if (s.indices.empty()) return;  // no triangles: nothing to stand for
  if (albedo.w > 0.0) s.albedo = glm::vec3(glm::dvec3(albedo) / albedo.w);
  out.push_back(std::move(s));
}

bool dynamicOrUnder(ecs::Registry& r, ecs::Entity e) {
  for (int guard = 0; !e.isNull() && guard < (1 << 20); ++guard) {
    if (r.has<scene::Dynamic>(e)) return true;
    const auto* p = r.tryGet<scene::Parent>(e);
    e = p ? p->entity : ecs::Entity::null();
  }
  return false;
}

}  // namespace

std::vector<MakeSource> sourcesFromLevel(const scene::Level& level, const std::filesystem::path& cookCache,
                                         std::size_t* skippedDynamic) {
  ecs::Registry r;
  const std::vector<ecs::Entity> es = scene::instantiate(level, r);
  std::vector<MakeSource> out;
  std::size_t skipped = 0;
  for (std::size_t i = 0; i < es.size(); ++i) {
    const scene::EntityDesc& d = level.entities[i];
    if (!d.mesh || d.vlm) continue;
    if (dynamicOrUnder(r, es[i])) {
      ++skipped;
      continue;
    }
    MakeSource s;
    s.name = d.id;
    s.tag = d.vlmTag ? std::uint32_t(d.vlmTag->tag) : 0;
    glm::dvec4 albedo(0.0);
    const scene::MeshRef& ref = r.get<scene::MeshRef>(es[i]);
    appendReal(scene::cookForRef(ref, cookCache), ref, r.get<scene::WorldTransform>(es[i]).matrix,
               r.tryGet<scene::MaterialOverride>(es[i]), s, albedo);
    finish(s, albedo, out);
  }
  if (skippedDynamic) *skippedDynamic = skipped;
  return out;
}

std::vector<MakeSource> sourcesFromAsset(const std::filesystem::path& asset, const std::optional<std::string>& node,
                                         const std::filesystem::path& cookCache) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(asset, ec))
    throwInputError(asset.string(), "file", "not found", "an existing .gltf or .glb file");
  scene::MeshRef ref;
  ref.asset = std::filesystem::absolute(asset).lexically_normal();
  if (node) ref.node = *node;
  const asset::CookedAsset a = asset::loadOrCook(ref.asset, cookCache);
  // One source per mesh node of the subtree (each its own tag), in the asset's frame.
  std::vector<int> meshNodes;
  scene::forEachInstancedNode(a, ref, glm::mat4(1.0f), [&](int n, const glm::mat4&) {
    if (a.nodes[std::size_t(n)].mesh >= 0 && !a.nodes[std::size_t(n)].vlm.present) meshNodes.push_back(n);
  });
  std::vector<MakeSource> out;
  for (int n : meshNodes) {
    MakeSource s;
    s.name = a.nodes[std::size_t(n)].name.empty() ? "node" + std::to_string(n) : a.nodes[std::size_t(n)].name;
    glm::dvec4 albedo(0.0);
    appendReal(a, ref, glm::mat4(1.0f), nullptr, s, albedo, n);
    finish(s, albedo, out);
  }
  if (out.empty())
    throwInputError(asset.string(), node ? "/nodes/" + *node : "/scene", "no triangles to start from", "a node with a mesh");
  return out;
}

void writeVlmGltf(const MakeResult& result, const std::filesystem::path& out) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "bounce vlm-make";
  model.buffers.resize(1);
  auto accessor = [&](const void* bytes, std::size_t count, std::size_t elementSize, int component, int type, int target) {
    return asset::appendAccessor(model, bytes, count, elementSize, component, type, target);
  };
  tinygltf::Scene scene;
  scene.name = "vlm";
  for (const MadeMesh& m : result.meshes) {
    if (m.indices.empty()) continue;
    tinygltf::Material mat;
    mat.name = m.source;
    mat.pbrMetallicRoughness.baseColorFactor = {asset::shortestDecimal(m.albedo.r), asset::shortestDecimal(m.albedo.g),
                                                 asset::shortestDecimal(m.albedo.b), 1.0};
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = 1.0;
    model.materials.push_back(mat);

    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = int(model.materials.size() - 1);
    const int pos = accessor(m.positions.data(), m.positions.size(), sizeof(glm::vec3), TINYGLTF_COMPONENT_TYPE_FLOAT,
                             TINYGLTF_TYPE_VEC3, kArrayBuffer);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    model.accessors[std::size_t(pos)].minValues = {lo.x, lo.y, lo.z};  // required on POSITION
    model.accessors[std::size_t(pos)].maxValues = {hi.x, hi.y, hi.z};
    prim.attributes["POSITION"] = pos;
    prim.attributes["NORMAL"] = accessor(m.normals.data(), m.normals.size(), sizeof(glm::vec3),
                                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, kArrayBuffer);
    prim.indices = accessor(m.indices.data(), m.indices.size(), 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                            TINYGLTF_TYPE_SCALAR, kElementArrayBuffer);
    tinygltf::Mesh mesh;
    mesh.name = "vlm-" + m.source;
    mesh.primitives.push_back(std::move(prim));
    model.meshes.push_back(std::move(mesh));

    tinygltf::Node node;
    node.name = "vlm-" + m.source;
    node.mesh = int(model.meshes.size() - 1);
    tinygltf::Value::Object vlm;
    vlm["tag"] = tinygltf::Value(int(m.tag));
    tinygltf::Value::Object extras;
    extras["bounce_vlm"] = tinygltf::Value(std::move(vlm));
    node.extras = tinygltf::Value(std::move(extras));
    scene.nodes.push_back(int(model.nodes.size()));
    model.nodes.push_back(std::move(node));
  }
  if (model.nodes.empty()) throw InternalError("vlm-make: no triangles left to write to " + out.string());
  model.scenes.push_back(std::move(scene));
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, out.string(), true, true, true, false))
    throw InternalError("vlm-make: could not write " + out.string());
}

std::string levelSnippet(const MakeResult& result, const std::string& assetFromLevel) {
  std::ostringstream s;
  s << "add to the level's \"entities\" (its glTF nodes carry extras.bounce_vlm, so a plain mesh entity is a VLM),\n"
    << "and \"vlm\" to its \"effects\":\n"
    << "  {\"id\": \"vlm-made\", \"mesh\": {\"asset\": " << nlohmann::json(assetFromLevel).dump() << "}}\n";
  bool header = false;
  for (const MadeMesh& m : result.meshes) {
    if (!m.tagAssigned) continue;
    if (!header)
      s << "give the real geometry these tags (it then skips its own virtual lights, thesis §3.4): add the\n"
        << "\"vlm_tag\" key to the entity with that id:\n";
    header = true;
    s << "  {\"id\": " << nlohmann::json(m.source).dump() << ", ..., \"vlm_tag\": " << m.tag << "}\n";
  }
  return s.str();
}

}  // namespace bounce::gi::vlm
