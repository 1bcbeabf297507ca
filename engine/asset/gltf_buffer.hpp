#pragma once
// Writing a tinygltf::Model (bounce export, bounce vlm-make): binary data appended to one buffer in
// 4-byte aligned views (every component type Bounce writes is 4 bytes, and glTF requires accessor
// offsets aligned to their component size), one accessor per call; and floats as legible JSON.
#include <charconv>
#include <cstddef>
#include <tiny_gltf.h>

namespace bounce::asset {

// A bufferView over `bytes` appended to model.buffers[0]; returns its index.
inline int appendBufferView(tinygltf::Model& model, const void* bytes, std::size_t size, int target) {
  auto& data = model.buffers.at(0).data;
  data.resize((data.size() + 3) & ~std::size_t(3), 0);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = data.size();
  v.byteLength = size;
  v.target = target;
  const auto* p = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), p, p + size);
  model.bufferViews.push_back(v);
  return int(model.bufferViews.size() - 1);
}

// An accessor of `count` elements of `elementSize` bytes over a new view of `bytes`; returns its index.
inline int appendAccessor(tinygltf::Model& model, const void* bytes, std::size_t count, std::size_t elementSize,
                          int componentType, int type, int target) {
  tinygltf::Accessor a;
  a.bufferView = appendBufferView(model, bytes, count * elementSize, target);
  a.componentType = componentType;
  a.type = type;
  a.count = count;
  model.accessors.push_back(std::move(a));
  return int(model.accessors.size() - 1);
}

// The double whose shortest decimal form is the float's shortest one: 0.92f is written "0.92", not
// "0.9200000166893005", and still reads back as exactly 0.92f. The JSON stays legible in other tools.
inline double shortestDecimal(float f) {
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, f);
  double d = f;
  std::from_chars(text, r.ptr, d);
  return d;
}

}  // namespace bounce::asset
