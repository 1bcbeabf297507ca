// FlatScene → glTF 2.0 binary through tinygltf's writer. The layout is described in export.hpp;
// this file only builds the tinygltf::Model (one buffer: vertex data, indices and PNG images).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stb_image_write.h>
#include <tiny_gltf.h>

#include "engine/asset/gltf_buffer.hpp"

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/log.hpp"
#include "engine/scene_export/export.hpp"

namespace bounce::scene_export {
namespace {

constexpr int kArrayBuffer = 34962;         // glTF bufferView.target for vertex attributes
constexpr int kElementArrayBuffer = 34963;  // and for indices
constexpr int kFilterLinear = 9729;
constexpr int kFilterLinearMipmapLinear = 9987;

// Columns of a world matrix count as orthogonal (the matrix decomposes into T·R·S) when the cosine
// of the angle between any two is below this. Products of float rotations and scales leave
// ~1e-7; any shear worth the name is far larger.
constexpr float kOrthogonalCos = 1e-5f;

bool decomposable(const glm::mat4& m) {
  if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      const glm::vec3 a(m[i]), b(m[j]);
      if (std::abs(glm::dot(a, b)) > kOrthogonalCos * glm::length(a) * glm::length(b)) return false;
    }
  return true;
}

bool isIdentity(const glm::mat4& m) { return m == glm::mat4(1.0f); }

// Floats as their shortest decimal form (asset::shortestDecimal).
double shortest(float f) { return asset::shortestDecimal(f); }

std::vector<double> shortest(std::initializer_list<float> values) {
  std::vector<double> out;
  for (float v : values) out.push_back(shortest(v));
  return out;
}

std::vector<double> matrixOf(const glm::mat4& m) {
  const float* p = glm::value_ptr(m);  // column-major, as glTF
  std::vector<double> out(16);
  std::transform(p, p + 16, out.begin(), [](float v) { return shortest(v); });
  return out;
}

// Material override as a map key: (has albedo, rgb, has emissive, rgb).
using OverrideKey = std::tuple<bool, float, float, float, bool, float, float, float>;
OverrideKey overrideKey(const std::optional<scene::MaterialOverride>& o) {
  const glm::vec3 a = o && o->albedo ? *o->albedo : glm::vec3(0.0f);
  const glm::vec3 e = o && o->emissive ? *o->emissive : glm::vec3(0.0f);
  return {o && o->albedo, a.x, a.y, a.z, o && o->emissive, e.x, e.y, e.z};
}

struct PrimGeometry {
  int position = -1, normal = -1, uv = -1, indices = -1;
};

class GlbBuilder {
 public:
  explicit GlbBuilder(const FlatScene& s) : s_(s) {
    model_.asset.version = "2.0";
    model_.asset.generator = "Bounce (bounce export)";
    model_.buffers.emplace_back();
  }

  tinygltf::Model build(ExportStats& stats) {
    tinygltf::Scene scene;
    scene.name = s_.name;
    // One root per entity, in level order; children are appended below.
    for (const auto& e : s_.entities) {
      tinygltf::Node n;
      n.name = e.id;
      if (e.dynamic) {
        tinygltf::Value::Object extras;
        extras["dynamic"] = tinygltf::Value(true);
        n.extras = tinygltf::Value(std::move(extras));
      }
      scene.nodes.push_back(int(model_.nodes.size()));
      model_.nodes.push_back(std::move(n));
    }
    for (const auto& c : s_.cameras) addCamera(c);
    for (const auto& inst : s_.meshes) addInstance(inst, stats);
    for (const auto& l : s_.lights) addLight(l);
    model_.scenes.push_back(std::move(scene));
    model_.defaultScene = 0;
    if (model_.buffers[0].data.empty()) model_.buffers.clear();  // an empty buffer is invalid glTF
    if (emissiveStrengthUsed_) model_.extensionsUsed.push_back("KHR_materials_emissive_strength");

    stats.nodes = model_.nodes.size();
    stats.meshes = model_.meshes.size();
    stats.materials = model_.materials.size();
    stats.textures = model_.textures.size();
    stats.cameras = s_.cameras.size();
    stats.lights = s_.lights.size();
    return std::move(model_);
  }

 private:
  void addChild(std::size_t entity, tinygltf::Node n) {
    model_.nodes[entity].children.push_back(int(model_.nodes.size()));
    model_.nodes.push_back(std::move(n));
  }

  template <class T>
  int addAccessor(const std::vector<T>& values, int componentType, int type, int target) {
    return asset::appendAccessor(model_, values.data(), values.size(), sizeof(T), componentType, type, target);
  }

  PrimGeometry writeGeometry(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                             const std::vector<glm::vec2>& uv, const std::vector<std::uint32_t>& indices) {
    PrimGeometry g;
    g.position = addAccessor(positions, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, kArrayBuffer);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    model_.accessors[std::size_t(g.position)].minValues = shortest({lo.x, lo.y, lo.z});  // required for POSITION
    model_.accessors[std::size_t(g.position)].maxValues = shortest({hi.x, hi.y, hi.z});
    g.normal = addAccessor(normals, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, kArrayBuffer);
    if (!uv.empty()) g.uv = addAccessor(uv, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, kArrayBuffer);
    g.indices = addAccessor(indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, kElementArrayBuffer);
    return g;
  }

  static bool drawable(const asset::Primitive& p) { return !p.indices.empty() && !p.positions.empty(); }

  const PrimGeometry& sharedGeometry(std::size_t asset, int mesh, std::size_t prim) {
    const auto key = std::tuple(asset, mesh, prim);
    if (auto it = geometry_.find(key); it != geometry_.end()) return it->second;
    const auto& p = s_.assets[asset].cooked.meshes[std::size_t(mesh)].primitives[prim];
    return geometry_[key] = writeGeometry(p.positions, p.normals, p.uv0, p.indices);
  }

  // World-space copy of a primitive, for an instance whose matrix is not TRS-decomposable.
  // `srcP`/`srcN`: the primitive's posed vertices (a deformed instance) instead of its cooked ones.
  PrimGeometry bakedGeometry(const asset::Primitive& p, const glm::mat4& m, const std::vector<glm::vec3>* srcP = nullptr,
                             const std::vector<glm::vec3>* srcN = nullptr) {
    const std::vector<glm::vec3>& inP = srcP ? *srcP : p.positions;
    const std::vector<glm::vec3>& inN = srcN ? *srcN : p.normals;
    const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(m));
    std::vector<glm::vec3> positions(inP.size()), normals(inN.size());
    for (std::size_t i = 0; i < positions.size(); ++i) positions[i] = glm::vec3(m * glm::vec4(inP[i], 1.0f));
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const glm::vec3 n = normalMatrix * inN[i];
      normals[i] = glm::dot(n, n) > 0.0f ? glm::normalize(n) : inN[i];
    }
    std::vector<std::uint32_t> indices = p.indices;
    // A mirroring matrix reverses winding; glTF would flip the front face for a node with a
    // negative determinant, so flip the triangles to keep the same front faces.
    if (glm::determinant(glm::mat3(m)) < 0.0f)
      for (std::size_t t = 0; t + 2 < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);
    return writeGeometry(positions, normals, p.uv0, indices);
  }

  // The glTF texture of an asset texture, or -1 when it has no pixels (the renderer then samples
  // white, which is what "no texture" means in glTF too).
  int texture(std::size_t asset, int index) {
    if (index < 0) return -1;
    const auto key = std::pair(asset, index);
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    const asset::Texture& t = s_.assets[asset].cooked.textures[std::size_t(index)];
    int result = -1;
    if (t.width > 0 && t.height > 0 && t.pixels.size() == std::size_t(t.width) * t.height * 4) {
      std::vector<unsigned char> png;
      auto append = [](void* ctx, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(ctx);
        out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
      };
      if (!stbi_write_png_to_func(append, &png, int(t.width), int(t.height), 4, t.pixels.data(), int(t.width) * 4))
        throw InternalError(s_.assets[asset].source.string() + ": texture " + std::to_string(index) +
                            ": PNG encoding failed");
      tinygltf::Image image;
      image.name = t.name.empty() ? s_.assets[asset].source.stem().string() + "/texture" + std::to_string(index) : t.name;
      image.mimeType = "image/png";
      image.bufferView = asset::appendBufferView(model_, png.data(), png.size(), 0);  // images: no target
      model_.images.push_back(std::move(image));
      if (model_.samplers.empty()) {  // the renderer's sampler: linear, mipmapped, repeat
        tinygltf::Sampler s;
        s.magFilter = kFilterLinear;
        s.minFilter = kFilterLinearMipmapLinear;
        model_.samplers.push_back(s);
      }
      tinygltf::Texture tex;
      tex.source = int(model_.images.size() - 1);
      tex.sampler = 0;
      model_.textures.push_back(tex);
      result = int(model_.textures.size() - 1);
    } else {
      log::warn(s_.assets[asset].source.string() + ": texture " + std::to_string(index) +
                " has no decoded pixels; exported without it");
    }
    return textures_[key] = result;
  }

  // The glTF material for asset material `index` (-1: the default material) under an entity's
  // override — the same colours GpuScene::extract gives the instance.
  int material(std::size_t asset, int index, const FlatEntity& entity) {
    const auto key = std::tuple(asset, index, overrideKey(entity.material));
    if (auto it = materials_.find(key); it != materials_.end()) return it->second;
    asset::Material src;  // defaults: white, no emission, no textures
    if (index >= 0) src = s_.assets[asset].cooked.materials[std::size_t(index)];
    glm::vec4 base = src.baseColorFactor;
    glm::vec3 emissive = src.emissiveFactor;
    const auto& o = entity.material;
    if (o && o->albedo) base = glm::vec4(*o->albedo, base.a);
    if (o && o->emissive) emissive = *o->emissive;

    tinygltf::Material m;
    m.name = index >= 0 && !src.name.empty() ? src.name : "material" + std::to_string(index);
    if (o && (o->albedo || o->emissive)) m.name += "@" + entity.id;
    m.pbrMetallicRoughness.baseColorFactor = shortest({base.r, base.g, base.b, base.a});
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = 1.0;
    m.pbrMetallicRoughness.baseColorTexture.index = texture(asset, src.baseColorTexture.texture);
    m.emissiveTexture.index = texture(asset, src.emissiveTexture.texture);
    const float peak = std::max({emissive.r, emissive.g, emissive.b});
    if (peak > 1.0f) {  // emissiveFactor is limited to [0, 1]; the strength carries the rest
      emissive /= peak;
      tinygltf::Value::Object strength;
      strength["emissiveStrength"] = tinygltf::Value(shortest(peak));
      m.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(std::move(strength));
      emissiveStrengthUsed_ = true;
    }
    m.emissiveFactor = shortest({emissive.r, emissive.g, emissive.b});
    m.doubleSided = src.doubleSided;
    model_.materials.push_back(std::move(m));
    return materials_[key] = int(model_.materials.size() - 1);
  }

  // A glTF mesh for an asset mesh under an entity's materials; `baked` gives world-space vertices.
  int mesh(const MeshInstance& inst, const glm::mat4* baked, ExportStats& stats) {
    const FlatEntity& entity = s_.entities[inst.entity];
    const auto key = std::tuple(inst.asset, inst.mesh, overrideKey(entity.material));
    const asset::Mesh& src = s_.assets[inst.asset].cooked.meshes[std::size_t(inst.mesh)];
    std::size_t triangles = 0;
    for (const auto& p : src.primitives) triangles += drawable(p) ? p.indices.size() / 3 : 0;
    stats.triangles += triangles;
    const bool posed = !inst.posedPositions.empty();  // a deformed instance: its own geometry, never shared
    const glm::mat4 identity(1.0f);
    if (posed && !baked) baked = &identity;
    if (!baked)
      if (auto it = meshes_.find(key); it != meshes_.end()) return it->second;

    tinygltf::Mesh m;
    m.name = src.name.empty() ? s_.assets[inst.asset].source.stem().string() + "/mesh" + std::to_string(inst.mesh)
                              : src.name;
    for (std::size_t pi = 0; pi < src.primitives.size(); ++pi) {
      const asset::Primitive& p = src.primitives[pi];
      if (!drawable(p)) continue;
      const bool own = posed && !inst.posedPositions[pi].empty();
      const PrimGeometry g = baked ? bakedGeometry(p, *baked, own ? &inst.posedPositions[pi] : nullptr,
                                                   own ? &inst.posedNormals[pi] : nullptr)
                                   : sharedGeometry(inst.asset, inst.mesh, pi);
      tinygltf::Primitive gp;
      gp.attributes["POSITION"] = g.position;
      gp.attributes["NORMAL"] = g.normal;
      if (g.uv >= 0) gp.attributes["TEXCOORD_0"] = g.uv;
      gp.indices = g.indices;
      gp.material = material(inst.asset, p.material, entity);
      gp.mode = TINYGLTF_MODE_TRIANGLES;
      m.primitives.push_back(std::move(gp));
    }
    int index = -1;
    if (!m.primitives.empty()) {
      model_.meshes.push_back(std::move(m));
      index = int(model_.meshes.size() - 1);
    }
    if (!baked) meshes_[key] = index;
    return index;
  }

  void addInstance(const MeshInstance& inst, ExportStats& stats) {
    const bool trs = decomposable(inst.world);
    const int m = mesh(inst, trs ? nullptr : &inst.world, stats);
    if (m < 0) return;
    const asset::Node& src = s_.assets[inst.asset].cooked.nodes[std::size_t(inst.node)];
    tinygltf::Node n;
    n.name = s_.entities[inst.entity].id + "/" + (src.name.empty() ? "node" + std::to_string(inst.node) : src.name);
    n.mesh = m;
    if (trs && !isIdentity(inst.world)) n.matrix = matrixOf(inst.world);
    addChild(inst.entity, std::move(n));
    ++stats.instances;
  }

  void addCamera(const CameraInstance& c) {
    tinygltf::Camera cam;
    cam.type = "perspective";
    cam.name = s_.entities[c.entity].id;
    cam.perspective.yfov = shortest(c.camera.yfovRad);
    cam.perspective.znear = shortest(c.camera.near);
    cam.perspective.zfar = shortest(c.camera.far);
    cam.perspective.aspectRatio = 0.0;  // omitted: the viewer's aspect, as the renderer's extent
    model_.cameras.push_back(std::move(cam));
    tinygltf::Node n;
    n.name = s_.entities[c.entity].id + "/camera";
    n.camera = int(model_.cameras.size() - 1);
    if (!isIdentity(c.world)) n.matrix = matrixOf(c.world);
    if (c.active) {
      tinygltf::Value::Object extras;
      extras["active"] = tinygltf::Value(true);
      n.extras = tinygltf::Value(std::move(extras));
    }
    addChild(c.entity, std::move(n));
  }

  void addLight(const LightInstance& l) {
    tinygltf::Light light;
    light.name = l.name;
    light.type = l.light.type == asset::LightType::Point ? "point" : l.light.type == asset::LightType::Spot ? "spot"
                                                                                                           : "directional";
    // Identity conversion (export.hpp): only a colour above 1 is rescaled into the intensity.
    glm::vec3 color = l.light.color;
    float intensity = l.light.intensity;
    if (const float peak = std::max({color.r, color.g, color.b}); peak > 1.0f) {
      color /= peak;
      intensity *= peak;
    }
    light.color = shortest({color.r, color.g, color.b});
    light.intensity = shortest(intensity);
    light.range = l.light.range > 0.0f ? shortest(l.light.range) : 0.0;
    if (l.light.type == asset::LightType::Spot) {
      light.spot.innerConeAngle = shortest(l.light.innerConeAngle);
      light.spot.outerConeAngle = shortest(l.light.outerConeAngle);
    }
    tinygltf::Value::Object extras;
    extras["shadows"] = tinygltf::Value(l.shadows);
    light.extras = tinygltf::Value(std::move(extras));
    model_.lights.push_back(std::move(light));

    tinygltf::Node n;
    n.name = l.name;
    if (!isIdentity(l.world)) n.matrix = matrixOf(l.world);
    tinygltf::Value::Object ref;
    ref["light"] = tinygltf::Value(int(model_.lights.size() - 1));
    n.extensions["KHR_lights_punctual"] = tinygltf::Value(std::move(ref));
    addChild(l.entity, std::move(n));
  }

  const FlatScene& s_;
  tinygltf::Model model_;
  std::map<std::tuple<std::size_t, int, std::size_t>, PrimGeometry> geometry_;
  std::map<std::pair<std::size_t, int>, int> textures_;
  std::map<std::tuple<std::size_t, int, OverrideKey>, int> materials_;
  std::map<std::tuple<std::size_t, int, OverrideKey>, int> meshes_;
  bool emissiveStrengthUsed_ = false;
};

}  // namespace

std::vector<std::uint8_t> writeGlb(const FlatScene& scene, ExportStats* stats) {
  ExportStats local;
  tinygltf::Model model = GlbBuilder(scene).build(local);
  // The stream writer, not WriteGltfSceneToFile: tinygltf 2.7's file writer reports success even
  // when the file cannot be opened; writing the bytes ourselves (atomically) reports it.
  std::ostringstream out(std::ios::binary);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/false, /*writeBinary=*/true) || !out)
    throw InternalError("tinygltf could not serialise the exported scene '" + scene.name + "'");
  const std::string bytes = out.str();
  local.bytes = bytes.size();
  if (stats) *stats = local;
  return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
}

ExportStats exportLevel(const scene::Level& level, const std::filesystem::path& out, const ExportOptions& options) {
  const FlatScene flat = flattenLevel(level, options.timeSeconds, options.cookCache);
  ExportStats stats;
  const std::vector<std::uint8_t> glb = writeGlb(flat, &stats);
  writeFileAtomic(out, glb);  // InternalError "<out>: cannot write: …" when it cannot
  return stats;
}

}  // namespace bounce::scene_export
