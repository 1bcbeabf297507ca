#pragma once
// Internal: the glTF container (GLB chunks or plain JSON) and checks made on the raw JSON
// before it is handed to tinygltf, so that tinygltf never sees a structure it would read out
// of bounds (it indexes a buffer with an image's bufferView range unchecked).
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace bounce::asset::detail {

struct GltfContainer {
  bool binary = false;  // a .glb
  std::string_view json;
  std::span<const std::uint8_t> bin;  // GLB BIN chunk payload (empty when absent)
};

// Splits `bytes` into JSON and BIN chunk (glTF 2.0 §4.4 "GLB File Format Specification"), checking
// magic, version, total length and every chunk header. Bytes not starting with "glTF" are JSON.
GltfContainer splitContainer(std::span<const std::uint8_t> bytes, const std::string& file);

// Parses JSON text; a syntax error is reported with its byte offset.
nlohmann::json parseJson(std::string_view text, const std::string& file);

// Checks the parts tinygltf trusts: buffers (external files present and long enough, GLB buffer
// inside the BIN chunk) and bufferViews used by images (inside their buffer).
void precheckJson(const nlohmann::json& doc, const GltfContainer& container, const std::string& file,
                  const std::filesystem::path& baseDir);

// Removes "indices" from every primitive with KHR_draco_mesh_compression; true when any was removed.
bool dropDracoIndices(nlohmann::json& doc);

// The container bytes for `doc`: plain JSON text, or a GLB with `doc` as JSON chunk and the
// original BIN chunk.
std::vector<std::uint8_t> rebuildContainer(const nlohmann::json& doc, const GltfContainer& original);

// Relative URIs of buffers and images (data: URIs excluded), percent-decoded, in file order.
std::vector<std::string> externalUris(const nlohmann::json& doc);

// Percent-decoding of a URI reference ("my%20file.bin" → "my file.bin").
std::string decodeUri(const std::string& uri);

}  // namespace bounce::asset::detail
