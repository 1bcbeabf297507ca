#pragma once
// Internal to engine/asset: what every import step needs to report an error in the user's file.
#include <tiny_gltf.h>

#include <cstddef>
#include <string>

namespace bounce::asset::detail {

struct ImportContext {
  const tinygltf::Model& model;
  std::string file;  // file name as shown in messages

  // Throws InputError "file: where: what (expected …)".
  [[noreturn]] void fail(const std::string& where, const std::string& what,
                         const std::string& expected = {}) const;
};

// "/meshes/2/primitives/0" style JSON pointer pieces.
inline std::string ptr(const std::string& base, std::size_t i) { return base + "/" + std::to_string(i); }
inline std::string ptr(const std::string& base, const std::string& key) { return base + "/" + key; }

}  // namespace bounce::asset::detail
