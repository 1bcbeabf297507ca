// GLB container parsing and JSON pre-checks (see gltf_json.hpp for why they exist).
#include "engine/asset/gltf_json.hpp"

#include "engine/core/error.hpp"

#include <cstring>

namespace bounce::asset::detail {

namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;     // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;      // "BIN\0"

std::uint32_t le32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

bool isDataUri(const std::string& s) { return s.rfind("data:", 0) == 0; }

// Non-negative integer member `key` of `o`, or `fallback` when absent; anything else is an error.
std::uint64_t uintMember(const nlohmann::json& o, const char* key, std::uint64_t fallback, const std::string& file,
                         const std::string& where) {
  auto it = o.find(key);
  if (it == o.end()) return fallback;
  if (!it->is_number_unsigned()) throwInputError(file, where + "/" + key, "not a non-negative integer", "an integer ≥ 0");
  return it->get<std::uint64_t>();
}

}  // namespace

GltfContainer splitContainer(std::span<const std::uint8_t> bytes, const std::string& file) {
  GltfContainer c;
  if (bytes.size() < 4 || le32(bytes.data()) != kGlbMagic) {
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) != 0 && bytes[0] != '{' && bytes[0] != ' ' &&
        bytes[0] != '\n' && bytes[0] != '\r' && bytes[0] != '\t' && bytes[0] != 0xEF)
      throwInputError(file, "byte 0", "neither GLB magic \"glTF\" nor a JSON object", "a .glb or .gltf file");
    c.json = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return c;
  }
  c.binary = true;
  if (bytes.size() < 12) throwInputError(file, "GLB header", "file has " + std::to_string(bytes.size()) + " bytes", "at least 12");
  const std::uint32_t version = le32(bytes.data() + 4), length = le32(bytes.data() + 8);
  if (version != 2) throwInputError(file, "GLB header", "version " + std::to_string(version), "2");
  if (length != bytes.size())
    throwInputError(file, "GLB header", "declared length " + std::to_string(length) + " but file has " +
                                             std::to_string(bytes.size()) + " bytes (truncated or padded)",
                    "length equal to the file size");
  std::uint64_t at = 12;
  int chunk = 0;
  while (at < bytes.size()) {
    const std::string where = "GLB chunk " + std::to_string(chunk) + " at byte " + std::to_string(at);
    if (bytes.size() - at < 8) throwInputError(file, where, "chunk header cut short", "8 header bytes");
    const std::uint64_t size = le32(bytes.data() + at), type = le32(bytes.data() + at + 4);
    if (size > bytes.size() - at - 8)
      throwInputError(file, where, "chunk length " + std::to_string(size) + " runs past the end of the file",
                      "at most " + std::to_string(bytes.size() - at - 8));
    const std::uint8_t* data = bytes.data() + at + 8;
    if (chunk == 0) {
      if (type != kChunkJson) throwInputError(file, where, "first chunk is not JSON", "chunk type 0x4E4F534A");
      if (size == 0) throwInputError(file, where, "JSON chunk is empty", "a glTF JSON object");
      c.json = std::string_view(reinterpret_cast<const char*>(data), size);
    } else if (chunk == 1 && type == kChunkBin) {
      c.bin = std::span<const std::uint8_t>(data, size);
    }  // other chunk types are skipped, as the specification asks
    at += 8 + size;
    ++chunk;
  }
  if (chunk == 0) throwInputError(file, "GLB", "no JSON chunk", "a JSON chunk after the 12-byte header");
  return c;
}

nlohmann::json parseJson(std::string_view text, const std::string& file) {
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    throwInputError(file, "JSON byte " + std::to_string(e.byte), "syntax error", "valid JSON");
  } catch (const nlohmann::json::exception& e) {
    throwInputError(file, "JSON", e.what(), "valid JSON");
  }
}

void precheckJson(const nlohmann::json& doc, const GltfContainer& container, const std::string& file,
                  const std::filesystem::path& baseDir) {
  if (!doc.is_object()) throwInputError(file, "/", "top level is not an object", "a glTF JSON object");
  std::vector<std::uint64_t> bufferLength;
  if (auto it = doc.find("buffers"); it != doc.end()) {
    if (!it->is_array()) throwInputError(file, "/buffers", "not an array", "an array");
    for (std::size_t i = 0; i < it->size(); ++i) {
      const auto& b = (*it)[i];
      const std::string where = "/buffers/" + std::to_string(i);
      if (!b.is_object()) throwInputError(file, where, "not an object", "a buffer object");
      const std::uint64_t length = uintMember(b, "byteLength", 0, file, where);
      bufferLength.push_back(length);
      auto uri = b.find("uri");
      if (uri == b.end()) {
        if (!container.binary || i != 0)
          throwInputError(file, where, "buffer has no uri", "a uri (only the first buffer of a .glb may omit it)");
        if (length > container.bin.size())
          throwInputError(file, where + "/byteLength",
                          "declared " + std::to_string(length) + " bytes but the GLB BIN chunk has " +
                              std::to_string(container.bin.size()),
                          "byteLength ≤ BIN chunk length");
        continue;
      }
      if (!uri->is_string()) throwInputError(file, where + "/uri", "not a string", "a URI");
      const std::string s = uri->get<std::string>();
      if (isDataUri(s)) continue;  // tinygltf checks the decoded size against byteLength
      const std::filesystem::path p = baseDir / decodeUri(s);
      std::error_code ec;
      const auto size = std::filesystem::file_size(p, ec);
      if (ec) throwInputError(file, where + "/uri", "buffer file '" + s + "' not found", "a readable file next to the glTF");
      if (size < length)
        throwInputError(file, where, "buffer file '" + s + "' has " + std::to_string(size) + " bytes, declared byteLength " +
                                         std::to_string(length),
                        "a file of byteLength bytes");
    }
  }
  auto views = doc.find("bufferViews");
  auto images = doc.find("images");
  if (images == doc.end()) return;
  if (!images->is_array()) throwInputError(file, "/images", "not an array", "an array");
  for (std::size_t i = 0; i < images->size(); ++i) {
    const auto& im = (*images)[i];
    const std::string where = "/images/" + std::to_string(i);
    if (!im.is_object()) throwInputError(file, where, "not an object", "an image object");
    auto bv = im.find("bufferView");
    if (bv == im.end()) continue;
    if (!bv->is_number_unsigned() || views == doc.end() || !views->is_array() || bv->get<std::uint64_t>() >= views->size())
      throwInputError(file, where + "/bufferView", "not a valid bufferView index", "an index into /bufferViews");
    const std::size_t v = bv->get<std::size_t>();
    const auto& view = (*views)[v];
    const std::string vw = "/bufferViews/" + std::to_string(v);
    if (!view.is_object()) throwInputError(file, vw, "not an object", "a bufferView object");
    const std::uint64_t buffer = uintMember(view, "buffer", ~0ull, file, vw);
    const std::uint64_t offset = uintMember(view, "byteOffset", 0, file, vw);
    const std::uint64_t length = uintMember(view, "byteLength", ~0ull, file, vw);
    if (buffer >= bufferLength.size()) throwInputError(file, vw + "/buffer", "not a valid buffer index", "an index into /buffers");
    if (length == ~0ull) throwInputError(file, vw, "byteLength missing", "a byteLength");
    if (offset > bufferLength[buffer] || length > bufferLength[buffer] - offset)
      throwInputError(file, vw, "bytes [" + std::to_string(offset) + ", +" + std::to_string(length) +
                                    ") run past the end of buffer " + std::to_string(buffer),
                      "a bufferView inside its buffer");
  }
}

bool dropDracoIndices(nlohmann::json& doc) {
  bool dropped = false;
  auto meshes = doc.find("meshes");
  if (meshes == doc.end() || !meshes->is_array()) return false;
  for (auto& mesh : *meshes) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (auto& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains("KHR_draco_mesh_compression"))
        continue;
      dropped = prim.erase("indices") > 0 || dropped;
    }
  }
  return dropped;
}

std::vector<std::uint8_t> rebuildContainer(const nlohmann::json& doc, const GltfContainer& original) {
  std::string text = doc.dump();
  if (!original.binary) return std::vector<std::uint8_t>(text.begin(), text.end());
  while (text.size() % 4 != 0) text += ' ';  // chunks are 4-byte aligned, JSON padded with spaces
  std::vector<std::uint8_t> out;
  auto put32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
  };
  const std::size_t binPadded = (original.bin.size() + 3) / 4 * 4;
  const bool hasBin = !original.bin.empty();
  put32(kGlbMagic);
  put32(2);
  put32(std::uint32_t(12 + 8 + text.size() + (hasBin ? 8 + binPadded : 0)));
  put32(std::uint32_t(text.size()));
  put32(kChunkJson);
  out.insert(out.end(), text.begin(), text.end());
  if (hasBin) {
    put32(std::uint32_t(binPadded));
    put32(kChunkBin);
    out.insert(out.end(), original.bin.begin(), original.bin.end());
    out.resize(out.size() + binPadded - original.bin.size(), 0);
  }
  return out;
}

std::vector<std::string> externalUris(const nlohmann::json& doc) {
  std::vector<std::string> out;
  if (!doc.is_object()) return out;
  for (const char* key : {"buffers", "images"}) {
    auto it = doc.find(key);
    if (it == doc.end() || !it->is_array()) continue;
    for (const auto& o : *it) {
      if (!o.is_object()) continue;
      auto uri = o.find("uri");
      if (uri != o.end() && uri->is_string() && !isDataUri(uri->get<std::string>()))
        out.push_back(decodeUri(uri->get<std::string>()));
    }
  }
  return out;
}

std::string decodeUri(const std::string& uri) {
  std::string out;
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += char(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace bounce::asset::detail
