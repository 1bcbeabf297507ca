#pragma once
// Internal: checked reads of glTF accessors. Every index, offset, stride, count and component
// type is validated before a byte is touched; all arithmetic on sizes is overflow-checked.
#include "engine/asset/import_context.hpp"

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace bounce::asset::detail {

// Largest element count accepted for one accessor. Real assets are far below this (the largest
// sample model has ~100k vertices); a bigger declared count is a corrupt or hostile file, and
// refusing it early keeps a sparse accessor (no bufferView) from allocating gigabytes of zeros.
inline constexpr std::size_t kMaxAccessorCount = std::size_t(1) << 26;

struct AccessorInfo {
  std::size_t count = 0;
  int components = 0;     // 1 (SCALAR) … 16 (MAT4)
  int componentType = 0;  // TINYGLTF_COMPONENT_TYPE_*
  bool normalized = false;
};

// Validates accessor `index` referenced from `where` and that its type is one of `types`
// (TINYGLTF_TYPE_*; empty = any). Returns its shape.
AccessorInfo checkAccessor(const ImportContext& ctx, int index, const std::string& where,
                           std::initializer_list<int> types = {});

// Every component as float: normalized integers map to [0,1] / [-1,1] (glTF 2.0 §3.11),
// other integers convert by value. Sparse substitutions applied.
std::vector<float> readFloats(const ImportContext& ctx, int index, const std::string& where,
                              std::initializer_list<int> types = {}, AccessorInfo* info = nullptr);

// Every component as uint32; component type must be an unsigned integer type (indices, joints).
std::vector<std::uint32_t> readUints(const ImportContext& ctx, int index, const std::string& where,
                                     std::initializer_list<int> types = {}, AccessorInfo* info = nullptr);

// Checks bufferView `index` (referenced from `where`) lies inside its buffer and returns a pointer
// to its first byte and its length.
const std::uint8_t* bufferViewBytes(const ImportContext& ctx, int index, const std::string& where,
                                    std::size_t* length);

}  // namespace bounce::asset::detail
