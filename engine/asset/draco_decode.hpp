#pragma once
// Internal: KHR_draco_mesh_compression decoding with the Draco library.
#include "engine/asset/import_context.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace bounce::asset::detail {

struct DracoAttribute {
  int components = 0;
  std::vector<float> values;  // vertexCount * components, normalized integers mapped to [0,1]/[-1,1]
  std::vector<std::uint32_t> uints;  // JOINTS_n only: the integer values
};

struct DracoMesh {
  std::size_t vertexCount = 0;
  std::vector<std::uint32_t> indices;  // triangle list, every index < vertexCount
  std::map<std::string, DracoAttribute> attributes;  // by glTF semantic ("POSITION", …)
};

// Decodes the primitive's Draco payload. `extension` is the primitive's
// extensions["KHR_draco_mesh_compression"] object; `where` the primitive's JSON pointer. The
// extension's attribute map gives, per glTF semantic, the Draco attribute unique id.
DracoMesh decodeDraco(const ImportContext& ctx, const tinygltf::Value& extension, const std::string& where);

}  // namespace bounce::asset::detail
