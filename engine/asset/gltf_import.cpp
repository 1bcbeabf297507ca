// glTF 2.0 import: tinygltf parses, this file turns its model into CookedAsset meshes, materials
// and textures, checking every reference on the way (accessors.cpp checks the bytes).
#include "engine/asset/gltf_import.hpp"

#include "engine/asset/accessors.hpp"
#include "engine/asset/draco_decode.hpp"
#include "engine/asset/gltf_json.hpp"
#include "engine/asset/images.hpp"
#include "engine/asset/mesh_repair.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/log.hpp"

#include <cmath>
#include <numeric>

namespace bounce::asset::detail {

namespace {

// Image callback: keep the encoded bytes; decodeTextures() decodes them later so that decode
// errors become our InputErrors and geometry-only cooks can skip decoding.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->width = image->height = -1;  // marks "still encoded"
  return true;
}

// File access for tinygltf: only absolute paths, so that a file missing next to the glTF is never
// silently found in the current working directory (tinygltf also searches ".").
bool fileExists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::path(path).is_absolute() && std::filesystem::is_regular_file(path, ec);
}
std::string expandPath(const std::string& path, void*) { return path; }
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  try {
    *out = readFileBytes(path);
    return true;
  } catch (const std::exception& e) {
    if (err) *err = e.what();
    return false;
  }
}

const char* const kSupportedRequired[] = {"KHR_draco_mesh_compression", "KHR_lights_punctual", "KHR_mesh_quantization",
                                          "KHR_materials_emissive_strength", "KHR_texture_transform"};

}  // namespace

tinygltf::Model loadModel(std::span<const std::uint8_t> bytes, const std::string& file, const std::filesystem::path& baseDir) {
  const GltfContainer container = splitContainer(bytes, file);
  nlohmann::json doc = parseJson(container.json, file);
  precheckJson(doc, container, file, baseDir);

  // tinygltf insists that an index accessor has a bufferView, which a Draco primitive's does not
  // (its indices live in the Draco payload): hand tinygltf a copy without those references.
  std::vector<std::uint8_t> rewritten;
  if (dropDracoIndices(doc)) {
    rewritten = rebuildContainer(doc, container);
    bytes = rewritten;
  }
  const GltfContainer parsed = splitContainer(bytes, file);

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keepEncodedImage, nullptr);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &expandPath, &readWholeFile, nullptr, nullptr});
  tinygltf::Model model;
  std::string err, warn;
  std::string base = baseDir.empty() ? std::string() : std::filesystem::absolute(baseDir).string();
  bool ok = false;
  try {
    if (container.binary)
      ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base);
    else
      ok = loader.LoadASCIIFromString(&model, &err, &warn, parsed.json.data(), unsigned(parsed.json.size()), base);
  } catch (const std::exception& e) {
    throwInputError(file, "glTF", std::string("parse failed: ") + e.what(), "a valid glTF 2.0 file");
  }
  if (!ok) {
    const std::string first = err.substr(0, err.find('\n'));
    throwInputError(file, "glTF", "parse failed: " + first, "a valid glTF 2.0 file");
  }
  for (const auto& ext : model.extensionsRequired) {
    bool known = false;
    for (const char* s : kSupportedRequired) known = known || ext == s;
    if (!known) log::warn(file + ": /extensionsRequired: extension " + ext + " is not supported; ignoring it");
  }
  return model;
}

std::vector<Material> importMaterials(const ImportContext& ctx) {
  const auto& m = ctx.model;
  auto textureRef = [&](const std::string& where, int index, int texCoord) {
    TextureRef r;
    if (index < 0) return r;
    if (std::size_t(index) >= m.textures.size())
      ctx.fail(where + "/index", "texture index " + std::to_string(index) + " out of range",
               "< " + std::to_string(m.textures.size()));
    const int source = m.textures[std::size_t(index)].source;
    if (source >= 0 && std::size_t(source) >= m.images.size())
      ctx.fail(ptr("/textures", std::size_t(index)) + "/source", "image index " + std::to_string(source) + " out of range",
               "< " + std::to_string(m.images.size()));
    if (source < 0) log::warn(ctx.file + ": " + ptr("/textures", std::size_t(index)) + ": texture has no source image; ignored");
    if (texCoord < 0) ctx.fail(where + "/texCoord", "negative texCoord", "≥ 0");
    r.texture = source;
    r.uvSet = texCoord;
    return r;
  };
  std::vector<Material> out;
  for (std::size_t i = 0; i < m.materials.size(); ++i) {
    const tinygltf::Material& src = m.materials[i];
    const std::string where = ptr("/materials", i);
    Material mat;
    mat.name = src.name;
    const auto& pbr = src.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() != 4)
      ctx.fail(where + "/pbrMetallicRoughness/baseColorFactor", "has " + std::to_string(pbr.baseColorFactor.size()) + " values", "4");
    for (int k = 0; k < 4; ++k) mat.baseColorFactor[k] = float(pbr.baseColorFactor[std::size_t(k)]);
    mat.baseColorTexture = textureRef(where + "/pbrMetallicRoughness/baseColorTexture", pbr.baseColorTexture.index,
                                      pbr.baseColorTexture.texCoord);
    if (src.emissiveFactor.size() != 3)
      ctx.fail(where + "/emissiveFactor", "has " + std::to_string(src.emissiveFactor.size()) + " values", "3");
    for (int k = 0; k < 3; ++k) mat.emissiveFactor[k] = float(src.emissiveFactor[std::size_t(k)]);
    mat.emissiveTexture = textureRef(where + "/emissiveTexture", src.emissiveTexture.index, src.emissiveTexture.texCoord);
    mat.doubleSided = src.doubleSided;
    if (src.alphaMode == "OPAQUE" || src.alphaMode.empty()) mat.alphaMode = AlphaMode::Opaque;
    else if (src.alphaMode == "MASK") mat.alphaMode = AlphaMode::Mask;
    else if (src.alphaMode == "BLEND") mat.alphaMode = AlphaMode::Blend;
    else ctx.fail(where + "/alphaMode", "unknown alpha mode \"" + src.alphaMode + "\"", "OPAQUE, MASK or BLEND");
    mat.alphaCutoff = float(src.alphaCutoff);
    for (float f : {mat.baseColorFactor.x, mat.baseColorFactor.y, mat.baseColorFactor.z, mat.baseColorFactor.w,
                    mat.emissiveFactor.x, mat.emissiveFactor.y, mat.emissiveFactor.z, mat.alphaCutoff})
      if (!std::isfinite(f)) ctx.fail(where, "non-finite colour factor or cutoff", "finite numbers");
    out.push_back(mat);
  }
  return out;
}

std::vector<Texture> importTextures(const ImportContext& ctx, const std::vector<Material>& materials, bool decode) {
  std::vector<Texture> out;
  for (std::size_t i = 0; i < ctx.model.images.size(); ++i) {
    const tinygltf::Image& im = ctx.model.images[i];
    const std::string where = ptr("/images", i);
    if (im.image.empty() && !im.uri.empty())
      ctx.fail(where + "/uri", "texture file '" + im.uri + "' not found or empty", "a readable image file next to the glTF");
    Texture t = decodeImage(im.image, decode, ctx.file, where);
    t.name = im.name.empty() ? im.uri : im.name;
    out.push_back(std::move(t));
  }
  for (const Material& m : materials)
    for (int t : {m.baseColorTexture.texture, m.emissiveTexture.texture})
      if (t >= 0) out[std::size_t(t)].srgb = true;
  return out;
}

namespace {

struct Attributes {
  std::size_t vertexCount = 0;
  std::vector<float> position, normal, uv, weights, weights1;
  std::vector<std::uint32_t> joints, joints1, indices;
  bool indexed = false;
};

int attribute(const tinygltf::Primitive& p, const char* name) {
  auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -2 : it->second;
}

// Reads the attributes from accessors (the uncompressed path).
Attributes readAccessors(const ImportContext& ctx, const tinygltf::Primitive& p, const std::string& where) {
  Attributes a;
  const std::string at = where + "/attributes/";
  const int pos = attribute(p, "POSITION");
  if (pos == -2) ctx.fail(at + "POSITION", "primitive has no POSITION attribute", "a POSITION accessor");
  AccessorInfo info;
  a.position = readFloats(ctx, pos, at + "POSITION", {TINYGLTF_TYPE_VEC3}, &info);
  a.vertexCount = info.count;
  auto sameCount = [&](const char* name, const AccessorInfo& i) {
    if (i.count != a.vertexCount)
      ctx.fail(at + name, "has " + std::to_string(i.count) + " elements", std::to_string(a.vertexCount) + " like POSITION");
  };
  if (int n = attribute(p, "NORMAL"); n != -2) {
    a.normal = readFloats(ctx, n, at + "NORMAL", {TINYGLTF_TYPE_VEC3}, &info);
    sameCount("NORMAL", info);
  }
  if (int n = attribute(p, "TEXCOORD_0"); n != -2) {
    a.uv = readFloats(ctx, n, at + "TEXCOORD_0", {TINYGLTF_TYPE_VEC2}, &info);
    sameCount("TEXCOORD_0", info);
  }
  if (int n = attribute(p, "JOINTS_0"); n != -2) {
    a.joints = readUints(ctx, n, at + "JOINTS_0", {TINYGLTF_TYPE_VEC4}, &info);
    sameCount("JOINTS_0", info);
  }
  if (int n = attribute(p, "WEIGHTS_0"); n != -2) {
    a.weights = readFloats(ctx, n, at + "WEIGHTS_0", {TINYGLTF_TYPE_VEC4}, &info);
    sameCount("WEIGHTS_0", info);
  }
  if (int n = attribute(p, "JOINTS_1"); n != -2) {
    a.joints1 = readUints(ctx, n, at + "JOINTS_1", {TINYGLTF_TYPE_VEC4}, &info);
    sameCount("JOINTS_1", info);
  }
  if (int n = attribute(p, "WEIGHTS_1"); n != -2) {
    a.weights1 = readFloats(ctx, n, at + "WEIGHTS_1", {TINYGLTF_TYPE_VEC4}, &info);
    sameCount("WEIGHTS_1", info);
  }
  if (p.indices >= 0 || p.indices < -1) {
    a.indices = readUints(ctx, p.indices, where + "/indices", {TINYGLTF_TYPE_SCALAR});
    a.indexed = true;
  }
  return a;
}

Attributes readDraco(const ImportContext& ctx, const tinygltf::Value& ext, const std::string& where) {
  DracoMesh d = decodeDraco(ctx, ext, where);
  Attributes a;
  a.vertexCount = d.vertexCount;
  a.indices = std::move(d.indices);
  a.indexed = true;
  auto take = [&](const char* name) -> DracoAttribute* {
    auto it = d.attributes.find(name);
    return it == d.attributes.end() ? nullptr : &it->second;
  };
  if (auto* p = take("POSITION")) a.position = std::move(p->values);
  else ctx.fail(where + "/extensions/KHR_draco_mesh_compression/attributes", "no POSITION attribute", "POSITION");
  if (auto* p = take("NORMAL")) a.normal = std::move(p->values);
  if (auto* p = take("TEXCOORD_0")) a.uv = std::move(p->values);
  if (auto* p = take("JOINTS_0")) a.joints = std::move(p->uints);
  if (auto* p = take("WEIGHTS_0")) a.weights = std::move(p->values);
  if (auto* p = take("JOINTS_1")) a.joints1 = std::move(p->uints);
  if (auto* p = take("WEIGHTS_1")) a.weights1 = std::move(p->values);
  return a;
}

template <class V>
std::vector<V> pack(const std::vector<float>& f) {
  constexpr int n = V::length();
  std::vector<V> out(f.size() / n);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int k = 0; k < n; ++k) out[i][k] = f[i * n + std::size_t(k)];
  return out;
}

// Skin influences (glTF 2.0 §3.7.3.3): JOINTS_n and WEIGHTS_n come in pairs, set 1 only with set 0;
// weights are finite and non-negative, and not all zero on a vertex. A sum away from 1 is
// renormalised (the spec lets a loader do so) with one warning per primitive.
void checkSkinWeights(const ImportContext& ctx, const std::string& where, Primitive& p) {
  const std::string at = where + "/attributes/";
  if (p.joints.empty() != p.weights.empty())
    ctx.fail(at + (p.joints.empty() ? "WEIGHTS_0" : "JOINTS_0"), "JOINTS_0 and WEIGHTS_0 not given together", "both or neither");
  if (p.joints1.empty() != p.weights1.empty())
    ctx.fail(at + (p.joints1.empty() ? "WEIGHTS_1" : "JOINTS_1"), "JOINTS_1 and WEIGHTS_1 not given together", "both or neither");
  if (!p.joints1.empty() && p.joints.empty()) ctx.fail(at + "JOINTS_1", "set 1 without set 0", "JOINTS_0/WEIGHTS_0 as well");
  // The spec's tolerance on the sum is 2e-7 per weight times the weight count; looser here so that
  // 8-bit and 16-bit normalised weights (which cannot hit 1 exactly) pass without a warning.
  constexpr float kSumTolerance = 2e-3f;
  std::size_t renormalised = 0;
  for (std::size_t v = 0; v < p.weights.size(); ++v) {
    glm::vec4 w0 = p.weights[v], w1 = p.weights1.empty() ? glm::vec4(0.0f) : p.weights1[v];
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      for (float w : {w0[k], w1[k]}) {
        if (!std::isfinite(w)) ctx.fail(at + "WEIGHTS_0", "vertex " + std::to_string(v) + " has a NaN/Inf weight", "finite weights");
        if (w < 0.0f) ctx.fail(at + "WEIGHTS_0", "vertex " + std::to_string(v) + " has a negative weight " + std::to_string(w),
                               "weights >= 0");
        sum += w;
      }
    }
    if (!(sum > 0.0f)) ctx.fail(at + "WEIGHTS_0", "vertex " + std::to_string(v) + " has all weights zero", "weights summing to 1");
    if (std::fabs(sum - 1.0f) > kSumTolerance) ++renormalised;
    p.weights[v] = w0 / sum;
    if (!p.weights1.empty()) p.weights1[v] = w1 / sum;
  }
  if (renormalised)
    log::warn(ctx.file + ": " + where + ": renormalised the skin weights of " + std::to_string(renormalised) +
              " vertices (their sum was not 1)");
}

// Returns false when the primitive is skipped (points or lines).
bool importPrimitive(const ImportContext& ctx, const tinygltf::Primitive& src, const std::string& where, Primitive& out,
                     std::size_t& skipped) {
  if (src.mode < kModeTriangles) {
    if (src.mode < kModePoints) ctx.fail(where + "/mode", "unknown mode " + std::to_string(src.mode), "0 to 6");
    ++skipped;
    return false;
  }
  if (src.mode > kModeTriangleFan) ctx.fail(where + "/mode", "unknown mode " + std::to_string(src.mode), "0 to 6");
  if (src.material < -1 || src.material >= int(ctx.model.materials.size()))
    ctx.fail(where + "/material", "material index " + std::to_string(src.material) + " out of range",
             "< " + std::to_string(ctx.model.materials.size()));
  auto draco = src.extensions.find("KHR_draco_mesh_compression");
  Attributes a = draco != src.extensions.end() ? readDraco(ctx, draco->second, where) : readAccessors(ctx, src, where);

  if (a.indexed) {
    for (std::size_t i = 0; i < a.indices.size(); ++i)
      if (a.indices[i] >= a.vertexCount)
        ctx.fail(where + "/indices", "index " + std::to_string(i) + " is " + std::to_string(a.indices[i]),
                 "< vertex count " + std::to_string(a.vertexCount));
  } else {
    a.indices.resize(a.vertexCount);
    std::iota(a.indices.begin(), a.indices.end(), 0u);
  }
  if (src.mode == kModeTriangles && a.indices.size() % 3 != 0)
    ctx.fail(where + (a.indexed ? "/indices" : "/attributes/POSITION"),
             std::to_string(a.indices.size()) + " corners is not a whole number of triangles", "a multiple of 3");

  out.material = src.material;
  out.indices = toTriangleList(src.mode, std::move(a.indices));
  out.positions = pack<glm::vec3>(a.position);
  out.normals = pack<glm::vec3>(a.normal);
  out.uv0 = pack<glm::vec2>(a.uv);
  out.weights = pack<glm::vec4>(a.weights);
  out.weights1 = pack<glm::vec4>(a.weights1);
  auto joints = [&](const std::vector<std::uint32_t>& in, std::vector<glm::u16vec4>& dst, const char* name) {
    dst.resize(in.size() / 4);
    for (std::size_t i = 0; i < in.size(); ++i) {
      if (in[i] > 0xFFFF) ctx.fail(where + "/attributes/" + name, "joint index " + std::to_string(in[i]), "≤ 65535");
      dst[i / 4][int(i % 4)] = std::uint16_t(in[i]);
    }
  };
  joints(a.joints, out.joints, "JOINTS_0");
  joints(a.joints1, out.joints1, "JOINTS_1");
  checkSkinWeights(ctx, where, out);
  for (std::size_t t = 0; t < src.targets.size(); ++t) {
    MorphTarget mt;
    const std::string tw = ptr(where + "/targets", t);
    for (const auto& [name, index] : src.targets[t]) {
      if (name != "POSITION" && name != "NORMAL") continue;  // tangents are not kept
      AccessorInfo info;
      auto values = pack<glm::vec3>(readFloats(ctx, index, tw + "/" + name, {TINYGLTF_TYPE_VEC3}, &info));
      if (info.count != a.vertexCount)
        ctx.fail(tw + "/" + name, "has " + std::to_string(info.count) + " elements", std::to_string(a.vertexCount));
      (name == "POSITION" ? mt.positions : mt.normals) = std::move(values);
    }
    out.targets.push_back(std::move(mt));
  }

  const RepairCounts r = repairTriangles(out);
  out.droppedTriangles = std::uint32_t(r.nonFinite + r.degenerate);
  if (r.nonFinite)
    log::warn(ctx.file + ": " + where + ": dropped " + std::to_string(r.nonFinite) +
              " triangles with NaN/Inf vertex positions (and " + std::to_string(r.removedVertices) + " unused vertices)");
  if (r.degenerate)
    log::warn(ctx.file + ": " + where + ": dropped " + std::to_string(r.degenerate) + " zero-area triangles");
  const std::vector<glm::vec3> generated = areaWeightedNormals(out.positions, out.indices);
  if (out.normals.empty()) {
    out.normals = generated;
  } else {
    // Normalise given normals; a zero or non-finite one takes the generated value.
    for (std::size_t i = 0; i < out.normals.size(); ++i) {
      const float len = glm::length(out.normals[i]);
      out.normals[i] = std::isfinite(len) && len > 0.0f ? out.normals[i] / len : generated[i];
    }
  }
  return true;
}

}  // namespace

std::vector<Mesh> importMeshes(const ImportContext& ctx) {
  std::vector<Mesh> out;
  std::size_t skipped = 0;
  for (std::size_t m = 0; m < ctx.model.meshes.size(); ++m) {
    const tinygltf::Mesh& src = ctx.model.meshes[m];
    Mesh mesh;
    mesh.name = src.name;
    for (double w : src.weights) mesh.morphWeights.push_back(float(w));
    for (std::size_t p = 0; p < src.primitives.size(); ++p) {
      Primitive prim;
      if (importPrimitive(ctx, src.primitives[p], ptr(ptr("/meshes", m) + "/primitives", p), prim, skipped))
        mesh.primitives.push_back(std::move(prim));
    }
    mesh.bounds = meshBounds(mesh.primitives);
    out.push_back(std::move(mesh));
  }
  if (skipped) log::warn(ctx.file + ": skipped " + std::to_string(skipped) + " point/line primitives (only triangles are cooked)");
  return out;
}

}  // namespace bounce::asset::detail
