// KHR_draco_mesh_compression: the primitive's geometry lives in one bufferView holding a Draco
// bitstream; `attributes` maps glTF semantics to Draco attribute unique ids. The glTF accessors of
// such a primitive only declare count/type (they have no bufferView), so everything is read from
// the decoded Draco mesh here. Draco may reorder and deduplicate vertices relative to the
// uncompressed original; only the triangles' geometry is the same (up to quantization).
#include "engine/asset/draco_decode.hpp"

#include "engine/asset/accessors.hpp"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

namespace bounce::asset::detail {

namespace {

constexpr const char* kKnownSemantics[] = {"POSITION", "NORMAL", "TEXCOORD_0", "JOINTS_0", "WEIGHTS_0",
                                           "JOINTS_1", "WEIGHTS_1"};

int expectedComponents(const std::string& semantic) {
  if (semantic == "POSITION" || semantic == "NORMAL") return 3;
  if (semantic == "TEXCOORD_0") return 2;
  return 4;
}

}  // namespace

DracoMesh decodeDraco(const ImportContext& ctx, const tinygltf::Value& extension, const std::string& where) {
  const std::string ext = where + "/extensions/KHR_draco_mesh_compression";
  if (!extension.IsObject()) ctx.fail(ext, "extension is not an object", "{bufferView, attributes}");
  const tinygltf::Value& bvValue = extension.Get("bufferView");
  if (!bvValue.IsInt()) ctx.fail(ext + "/bufferView", "missing or not an integer", "a bufferView index");
  std::size_t length = 0;
  const std::uint8_t* bytes = bufferViewBytes(ctx, bvValue.GetNumberAsInt(), ext + "/bufferView", &length);

  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes), length);
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok() || type.value() != draco::TRIANGULAR_MESH)
    ctx.fail(ext, "Draco payload is not a triangle mesh" + (type.ok() ? std::string() : ": " + type.status().error_msg_string()),
             "a Draco-encoded triangular mesh");
  draco::Decoder decoder;
  auto result = decoder.DecodeMeshFromBuffer(&buffer);
  if (!result.ok()) ctx.fail(ext, "Draco decode failed: " + result.status().error_msg_string(), "a valid Draco bitstream");
  const std::unique_ptr<draco::Mesh>& mesh = result.value();

  DracoMesh out;
  out.vertexCount = mesh->num_points();
  out.indices.reserve(std::size_t(mesh->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh->face(f)[k].value();
      if (v >= out.vertexCount)
        ctx.fail(ext, "decoded face " + std::to_string(f.value()) + " uses point " + std::to_string(v),
                 "< " + std::to_string(out.vertexCount) + " points");
      out.indices.push_back(v);
    }

  const tinygltf::Value& attrs = extension.Get("attributes");
  if (!attrs.IsObject()) ctx.fail(ext + "/attributes", "missing or not an object", "semantic → Draco attribute id");
  for (const char* semantic : kKnownSemantics) {
    if (!attrs.Has(semantic)) continue;
    const std::string at = ext + "/attributes/" + semantic;
    const tinygltf::Value& id = attrs.Get(semantic);
    if (!id.IsInt()) ctx.fail(at, "not an integer", "a Draco attribute unique id");
    const draco::PointAttribute* pa = mesh->GetAttributeByUniqueId(std::uint32_t(id.GetNumberAsInt()));
    if (pa == nullptr) ctx.fail(at, "no Draco attribute with unique id " + std::to_string(id.GetNumberAsInt()),
                                "an id present in the Draco payload");
    const int want = expectedComponents(semantic);
    if (pa->num_components() < 1 || pa->num_components() > 4)
      ctx.fail(at, "Draco attribute has " + std::to_string(int(pa->num_components())) + " components", "1 to 4");
    DracoAttribute a;
    a.components = want;
    const bool joints = std::string(semantic).rfind("JOINTS_", 0) == 0;
    if (joints) a.uints.resize(out.vertexCount * std::size_t(want), 0);
    else a.values.resize(out.vertexCount * std::size_t(want), 0.0f);
    for (draco::PointIndex p(0); p < mesh->num_points(); ++p) {
      const draco::AttributeValueIndex vi = pa->mapped_index(p);
      if (vi.value() >= pa->size()) ctx.fail(at, "point " + std::to_string(p.value()) + " maps to a missing value",
                                             "< " + std::to_string(pa->size()) + " values");
      bool ok = joints ? pa->ConvertValue<std::uint32_t>(vi, std::int8_t(want), &a.uints[p.value() * want])
                       : pa->ConvertValue<float>(vi, std::int8_t(want), &a.values[p.value() * want]);
      if (!ok) ctx.fail(at, "Draco attribute value cannot be converted", "a numeric attribute");
    }
    out.attributes.emplace(semantic, std::move(a));
  }
  return out;
}

}  // namespace bounce::asset::detail
