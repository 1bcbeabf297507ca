// Checked accessor reads (glTF 2.0 §3.6 "Binary Data Storage", §3.11 "Accessors").
//
// The order of checks follows the chain accessor → bufferView → buffer, and each message names
// the object that is wrong: a bad reference is reported at the referring JSON pointer, a bad
// range at "accessor N" / "bufferView N". Sizes are computed in std::uint64_t with explicit
// overflow checks, because declared counts and offsets come straight from the file.
#include "engine/asset/accessors.hpp"

#include "engine/core/error.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace bounce::asset::detail {

void ImportContext::fail(const std::string& where, const std::string& what, const std::string& expected) const {
  throwInputError(file, where, what, expected);
}

namespace {

using u64 = std::uint64_t;

int componentSize(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "?";
  }
}

bool mulOverflows(u64 a, u64 b, u64* out) { return __builtin_mul_overflow(a, b, out); }
bool addOverflows(u64 a, u64 b, u64* out) { return __builtin_add_overflow(a, b, out); }

// A dense element stream: `count` elements of `elementSize` bytes, `stride` apart, or all zeros
// when base is null (accessor without bufferView).
struct Stream {
  const std::uint8_t* base = nullptr;
  u64 stride = 0;
};

// Checks that bytes [offset, offset + (count-1)*stride + elementSize) lie in a view of `length`.
void checkRange(const ImportContext& ctx, const std::string& where, u64 offset, u64 count, u64 stride,
                u64 elementSize, u64 length, const std::string& viewName) {
  u64 span = 0, end = 0;
  if (count == 0) return;
  if (mulOverflows(count - 1, stride, &span) || addOverflows(span, elementSize, &span) ||
      addOverflows(span, offset, &end) || end > length)
    ctx.fail(where,
             "data of " + std::to_string(count) + " elements (stride " + std::to_string(stride) + ", offset " +
                 std::to_string(offset) + ") runs past the end of " + viewName + " (" + std::to_string(length) +
                 " bytes)",
             "accessor data inside its bufferView");
}

struct Checked {
  AccessorInfo info;
  int componentBytes = 0;
  Stream dense;
};

Checked check(const ImportContext& ctx, int index, const std::string& where, std::initializer_list<int> types) {
  const auto& m = ctx.model;
  if (index < 0 || std::size_t(index) >= m.accessors.size())
    ctx.fail(where, "accessor index " + std::to_string(index) + " out of range",
             "0 ≤ index < " + std::to_string(m.accessors.size()));
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  const std::string here = "accessor " + std::to_string(index);
  Checked c;
  c.info.components = componentCount(a.type);
  c.componentBytes = componentSize(a.componentType);
  c.info.componentType = a.componentType;
  c.info.normalized = a.normalized;
  c.info.count = a.count;
  if (c.info.components == 0) ctx.fail(here, "unknown type " + std::to_string(a.type), "SCALAR, VEC2-4 or MAT2-4");
  if (c.componentBytes == 0)
    ctx.fail(here, "unknown componentType " + std::to_string(a.componentType), "5120-5126 except 5124");
  if (types.size() != 0) {
    bool ok = false;
    std::string list;
    for (int t : types) {
      ok = ok || t == a.type;
      list += (list.empty() ? "" : " or ") + std::string(typeName(t));
    }
    if (!ok) ctx.fail(where, "accessor " + std::to_string(index) + " has type " + typeName(a.type), list);
  }
  if (a.count == 0) ctx.fail(here, "count is 0", "count ≥ 1");
  if (a.count > kMaxAccessorCount)
    ctx.fail(here, "count " + std::to_string(a.count) + " is absurdly large",
             "at most " + std::to_string(kMaxAccessorCount) + " elements");
  const u64 elementSize = u64(c.componentBytes) * u64(c.info.components);
  if (a.bufferView < 0) {
    if (a.bufferView != -1) ctx.fail(here, "bufferView " + std::to_string(a.bufferView) + " is negative", "≥ 0");
    return c;  // zeros, then sparse values (glTF 2.0 §3.11.4)
  }
  std::size_t viewLength = 0;
  const std::uint8_t* view = bufferViewBytes(ctx, a.bufferView, ptr("/accessors", std::size_t(index)) + "/bufferView",
                                             &viewLength);
  const tinygltf::BufferView& bv = m.bufferViews[std::size_t(a.bufferView)];
  u64 stride = bv.byteStride == 0 ? elementSize : u64(bv.byteStride);
  if (stride < elementSize)
    ctx.fail(here, "bufferView " + std::to_string(a.bufferView) + " byteStride " + std::to_string(stride) +
                       " is smaller than one element (" + std::to_string(elementSize) + " bytes)",
             "byteStride ≥ element size");
  checkRange(ctx, here, a.byteOffset, a.count, stride, elementSize, viewLength,
             "bufferView " + std::to_string(a.bufferView));
  c.dense.base = view + a.byteOffset;
  c.dense.stride = stride;
  return c;
}

// Reads component `k` of the element at `p` as double (exact for every glTF component type).
double component(const std::uint8_t* p, int type, int k, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p + k, 1);
      return normalized ? std::max(double(v) / 127.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      std::uint8_t v = p[k];
      return normalized ? double(v) / 255.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p + 2 * k, 2);
      return normalized ? std::max(double(v) / 32767.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p + 2 * k, 2);
      return normalized ? double(v) / 65535.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p + 4 * k, 4);
      return normalized ? double(v) / 4294967295.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p + 4 * k, 4);
      return double(v);
    }
    default: return 0.0;
  }
}

// Dense read then sparse substitution; T is float or uint32.
template <class T>
std::vector<T> read(const ImportContext& ctx, int index, const Checked& c) {
  const auto& a = ctx.model.accessors[std::size_t(index)];
  const std::string here = "accessor " + std::to_string(index);
  const std::size_t n = c.info.components;
  std::vector<T> out(c.info.count * n, T(0));
  if (c.dense.base)
    for (std::size_t i = 0; i < c.info.count; ++i) {
      const std::uint8_t* p = c.dense.base + i * c.dense.stride;
      for (std::size_t k = 0; k < n; ++k) out[i * n + k] = T(component(p, c.info.componentType, int(k), c.info.normalized));
    }
  if (!a.sparse.isSparse) return out;

  const std::string sp = ptr("/accessors", std::size_t(index)) + "/sparse";
  const auto count = a.sparse.count;
  if (count < 1 || std::size_t(count) > c.info.count)
    ctx.fail(sp + "/count", "sparse count " + std::to_string(count) + " out of range",
             "1 ≤ count ≤ accessor count " + std::to_string(c.info.count));
  const int it = a.sparse.indices.componentType;
  if (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    ctx.fail(sp + "/indices/componentType", "component type " + std::to_string(it) + " is not allowed",
             "5121, 5123 or 5125");
  if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
    ctx.fail(sp, "negative byteOffset", "byteOffset ≥ 0");
  std::size_t idxLen = 0, valLen = 0;
  const std::uint8_t* idx = bufferViewBytes(ctx, a.sparse.indices.bufferView, sp + "/indices/bufferView", &idxLen);
  const std::uint8_t* val = bufferViewBytes(ctx, a.sparse.values.bufferView, sp + "/values/bufferView", &valLen);
  const u64 isz = u64(componentSize(it));
  const u64 esz = u64(c.componentBytes) * n;
  checkRange(ctx, sp + "/indices", u64(a.sparse.indices.byteOffset), u64(count), isz, isz, idxLen,
             "bufferView " + std::to_string(a.sparse.indices.bufferView));
  checkRange(ctx, sp + "/values", u64(a.sparse.values.byteOffset), u64(count), esz, esz, valLen,
             "bufferView " + std::to_string(a.sparse.values.bufferView));
  idx += a.sparse.indices.byteOffset;
  val += a.sparse.values.byteOffset;
  for (int s = 0; s < count; ++s) {
    const u64 target = u64(component(idx + s * isz, it, 0, false));
    if (target >= c.info.count)
      ctx.fail(sp + "/indices", "sparse index " + std::to_string(target) + " (entry " + std::to_string(s) +
                                    ") out of range",
               "< accessor count " + std::to_string(c.info.count));
    for (std::size_t k = 0; k < n; ++k)
      out[target * n + k] = T(component(val + s * esz, c.info.componentType, int(k), c.info.normalized));
  }
  return out;
}

}  // namespace

const std::uint8_t* bufferViewBytes(const ImportContext& ctx, int index, const std::string& where, std::size_t* length) {
  const auto& m = ctx.model;
  if (index < 0 || std::size_t(index) >= m.bufferViews.size())
    ctx.fail(where, "bufferView index " + std::to_string(index) + " out of range",
             "0 ≤ index < " + std::to_string(m.bufferViews.size()));
  const tinygltf::BufferView& bv = m.bufferViews[std::size_t(index)];
  const std::string here = "bufferView " + std::to_string(index);
  if (bv.buffer < 0 || std::size_t(bv.buffer) >= m.buffers.size())
    ctx.fail(ptr("/bufferViews", std::size_t(index)) + "/buffer",
             "buffer index " + std::to_string(bv.buffer) + " out of range",
             "0 ≤ index < " + std::to_string(m.buffers.size()));
  const auto& data = m.buffers[std::size_t(bv.buffer)].data;
  u64 end = 0;
  if (addOverflows(bv.byteOffset, bv.byteLength, &end) || end > data.size())
    ctx.fail(here,
             "bytes [" + std::to_string(bv.byteOffset) + ", " + std::to_string(bv.byteOffset) + " + " +
                 std::to_string(bv.byteLength) + ") run past the end of buffer " + std::to_string(bv.buffer) + " (" +
                 std::to_string(data.size()) + " bytes)",
             "bufferView inside its buffer");
  *length = bv.byteLength;
  return data.data() + bv.byteOffset;
}

AccessorInfo checkAccessor(const ImportContext& ctx, int index, const std::string& where, std::initializer_list<int> types) {
  return check(ctx, index, where, types).info;
}

std::vector<float> readFloats(const ImportContext& ctx, int index, const std::string& where,
                              std::initializer_list<int> types, AccessorInfo* info) {
  Checked c = check(ctx, index, where, types);
  if (info) *info = c.info;
  return read<float>(ctx, index, c);
}

std::vector<std::uint32_t> readUints(const ImportContext& ctx, int index, const std::string& where,
                                     std::initializer_list<int> types, AccessorInfo* info) {
  Checked c = check(ctx, index, where, types);
  const int t = c.info.componentType;
  if (t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    ctx.fail(where, "accessor " + std::to_string(index) + " has componentType " + std::to_string(t),
             "an unsigned integer type (5121, 5123 or 5125)");
  if (info) *info = c.info;
  c.info.normalized = false;  // indices and joints are read by value
  return read<std::uint32_t>(ctx, index, c);
}

}  // namespace bounce::asset::detail
