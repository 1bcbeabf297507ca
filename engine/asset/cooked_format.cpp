// Cooked format writer and reader (layout in cooked_format.hpp). One `io()` function per type
// describes its fields once; the Writer and the Reader both walk it, so the two cannot drift.
#include "engine/asset/cooked_format.hpp"

#include "engine/asset/cook.hpp"
#include "engine/core/binary_io.hpp"
#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"

#include <cstring>
#include <type_traits>

namespace bounce::asset {

namespace {

constexpr char kMagic[8] = {'B', 'C', 'O', 'O', 'K', 'E', 'D', '\0'};
constexpr std::size_t kHeaderSize = 24;
constexpr std::size_t kEntrySize = 24;
constexpr std::size_t kChecksumSize = 8;
constexpr std::uint32_t kSectionCount = 9;

template <class T>
constexpr bool kRaw = std::is_trivially_copyable_v<T> && !std::is_enum_v<T> && !std::is_same_v<T, bool>;

// Field lists, defined below the Writer and Reader that walk them.
template <class S> void io(S& s, Bounds& b);
template <class S> void io(S& s, MorphTarget& t);
template <class S> void io(S& s, LimitStencils& l);
template <class S> void io(S& s, Primitive& p);
template <class S> void io(S& s, Mesh& m);
template <class S> void io(S& s, TextureRef& r);
template <class S> void io(S& s, Material& m);
template <class S> void io(S& s, Texture& t);
template <class S> void io(S& s, Node& n);
template <class S> void io(S& s, Camera& c);
template <class S> void io(S& s, Light& l);
template <class S> void io(S& s, Skin& k);
template <class S> void io(S& s, AnimationSampler& a);
template <class S> void io(S& s, AnimationChannel& c);
template <class S> void io(S& s, Animation& a);

class Writer : public BinaryWriter {
 public:
  template <class T>
    requires kRaw<T>
  void operator()(const T& v) { put(v); }
  void operator()(const bool& v) { bytes.push_back(v ? 1 : 0); }
  template <class E>
    requires std::is_enum_v<E>
  void enumeration(const E& e, std::uint32_t) { (*this)(std::uint32_t(e)); }
  void operator()(const std::string& s) {
    (*this)(std::uint64_t(s.size()));
    raw(s.data(), s.size());
  }
  template <class T>
  void operator()(const std::vector<T>& v) {
    (*this)(std::uint64_t(v.size()));
    if constexpr (kRaw<T>) putAll(v);
    else for (const T& x : v) io(*this, const_cast<T&>(x));
  }
};

class Reader {
 public:
  // A section's errors read "file: section T byte N: what (expected …)", N counted from the section's start.
  Reader(std::span<const std::uint8_t> d, const std::string& file, std::string where)
      : in_(d, file, "", ByteOffset::Suffix), where_(std::move(where)) {}
  std::size_t remaining() const { return in_.remaining(); }
  [[noreturn]] void fail(const std::string& what, const std::string& expected) const { in_.fail(where_, what, expected); }
  void bytes(void* p, std::size_t n) {
    if (n > remaining()) fail("section ends early", std::to_string(n) + " more bytes");
    in_.raw(p, n, where_);
  }
  template <class T>
    requires kRaw<T>
  void operator()(T& v) { bytes(&v, sizeof v); }
  void operator()(bool& v) {
    std::uint8_t b = 0;
    bytes(&b, 1);
    if (b > 1) fail("boolean byte " + std::to_string(b), "0 or 1");
    v = b == 1;
  }
  template <class E>
    requires std::is_enum_v<E>
  void enumeration(E& e, std::uint32_t max) {
    std::uint32_t v = 0;
    (*this)(v);
    if (v > max) fail("enum value " + std::to_string(v), "at most " + std::to_string(max));
    e = E(v);
  }
  // Element count, checked against the bytes left so a corrupt count cannot allocate wildly.
  std::size_t count(std::size_t minElementBytes) {
    std::uint64_t n = 0;
    (*this)(n);
    if (n > remaining() / std::max<std::size_t>(minElementBytes, 1))
      fail("count " + std::to_string(n) + " exceeds the section", "at most " + std::to_string(remaining()) + " bytes of data");
    return std::size_t(n);
  }
  void operator()(std::string& s) {
    s.resize(count(1));
    bytes(s.data(), s.size());
  }
  template <class T>
  void operator()(std::vector<T>& v) {
    if constexpr (kRaw<T>) {
      v.resize(count(sizeof(T)));
      bytes(v.data(), v.size() * sizeof(T));
    } else {
      v.resize(count(1));
      for (T& x : v) io(*this, x);
    }
  }

 private:
  BinaryReader in_;
  std::string where_;
};

template <class S> void io(S& s, Bounds& b) { s(b.min); s(b.max); }
template <class S> void io(S& s, MorphTarget& t) { s(t.positions); s(t.normals); }
template <class S> void io(S& s, Primitive& p) {
  s(p.positions); s(p.normals); s(p.uv0); s(p.indices); s(p.joints); s(p.weights); s(p.joints1); s(p.weights1); s(p.targets); s(p.material); s(p.droppedTriangles);
  io(s, p.stencils);
}
template <class S> void io(S& s, LimitStencils& l) {
  s(l.cagePrimitive); s(l.offsets); s(l.indices); s(l.weights); s(l.duWeights); s(l.dvWeights);
}
template <class S> void io(S& s, Mesh& m) { s(m.name); s(m.primitives); s(m.morphWeights); io(s, m.bounds); s(m.cage); }
template <class S> void io(S& s, TextureRef& r) { s(r.texture); s(r.uvSet); }
template <class S> void io(S& s, Material& m) {
  s(m.name); s(m.baseColorFactor); io(s, m.baseColorTexture); s(m.emissiveFactor); io(s, m.emissiveTexture);
  s(m.doubleSided); s.enumeration(m.alphaMode, 2); s(m.alphaCutoff);
}
template <class S> void io(S& s, Texture& t) { s(t.name); s(t.width); s(t.height); s(t.srgb); s(t.pixels); }
template <class S> void io(S& s, Node& n) {
  s(n.name); s(n.hasMatrix); s(n.matrix); s(n.translation); s(n.rotation); s(n.scale); s(n.children);
  s(n.mesh); s(n.camera); s(n.light); s(n.skin); s.enumeration(n.subdivision.scheme, 2); s(n.subdivision.levels);
  s(n.vlm.present); s(n.vlm.tag); s(n.vlm.hasColor); s(n.vlm.color); s(n.vlm.hasIntensity); s(n.vlm.intensity);
  s(n.vlm.hasReflectance); s(n.vlm.reflectance);
}
template <class S> void io(S& s, Camera& c) {
  s(c.name); s.enumeration(c.type, 1); s(c.yfov); s(c.aspectRatio); s(c.xmag); s(c.ymag); s(c.znear); s(c.zfar);
}
template <class S> void io(S& s, Light& l) {
  s(l.name); s.enumeration(l.type, 2); s(l.color); s(l.intensity); s(l.range); s(l.innerConeAngle); s(l.outerConeAngle);
}
template <class S> void io(S& s, Skin& k) { s(k.name); s(k.joints); s(k.inverseBindMatrices); s(k.skeleton); }
template <class S> void io(S& s, AnimationSampler& a) { s(a.input); s(a.output); s(a.components); s.enumeration(a.interpolation, 2); }
template <class S> void io(S& s, AnimationChannel& c) { s(c.sampler); s(c.node); s.enumeration(c.path, 3); }
template <class S> void io(S& s, Animation& a) { s(a.name); s(a.samplers); s(a.channels); }

// Section `type` of asset `a`, read or written with `s`.
template <class S>
void section(S& s, SectionType type, CookedAsset& a) {
  switch (type) {
    case SectionType::Info: s(a.sourceName); s(a.rootNodes); break;
    case SectionType::Meshes: s(a.meshes); break;
    case SectionType::Materials: s(a.materials); break;
    case SectionType::Textures: s(a.textures); break;
    case SectionType::Nodes: s(a.nodes); break;
    case SectionType::Cameras: s(a.cameras); break;
    case SectionType::Lights: s(a.lights); break;
    case SectionType::Skins: s(a.skins); break;
    case SectionType::Animations: s(a.animations); break;
  }
}

std::uint32_t le32(const std::uint8_t* p) { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
std::uint64_t le64(const std::uint8_t* p) { std::uint64_t v; std::memcpy(&v, p, 8); return v; }

}  // namespace

std::vector<std::uint8_t> serializeCooked(const CookedAsset& asset) {
  std::vector<std::vector<std::uint8_t>> payloads;
  for (std::uint32_t t = 1; t <= kSectionCount; ++t) {
    Writer w;
    section(w, SectionType(t), const_cast<CookedAsset&>(asset));
    payloads.push_back(std::move(w.bytes));
  }
  Writer out;
  out.raw(kMagic, sizeof kMagic);
  out(kCookedFormatVersion);
  out(kCookerVersion);
  out(kSectionCount);
  out(std::uint32_t(0));
  std::uint64_t offset = kHeaderSize + kEntrySize * kSectionCount;
  for (std::uint32_t t = 1; t <= kSectionCount; ++t) {
    out(t);
    out(std::uint32_t(0));
    out(offset);
    out(std::uint64_t(payloads[t - 1].size()));
    offset += payloads[t - 1].size();
  }
  for (const auto& p : payloads) out.putAll(p);
  out(hashBytes(out.bytes));
  return std::move(out.bytes);
}

CookedAsset parseCooked(std::span<const std::uint8_t> bytes, const std::string& name) {
  const std::size_t fixed = kHeaderSize + kEntrySize * kSectionCount + kChecksumSize;
  if (bytes.size() < kHeaderSize) throwInputError(name, "header", "file has " + std::to_string(bytes.size()) + " bytes", "a cooked asset");
  if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) throwInputError(name, "byte 0", "bad magic", "\"BCOOKED\"");
  const std::uint32_t format = le32(bytes.data() + 8), cooker = le32(bytes.data() + 12), sections = le32(bytes.data() + 16);
  if (format != kCookedFormatVersion)
    throwInputError(name, "header", "format version " + std::to_string(format), std::to_string(kCookedFormatVersion));
  if (cooker != kCookerVersion)
    throwInputError(name, "header", "cooked by cooker version " + std::to_string(cooker), std::to_string(kCookerVersion));
  if (sections != kSectionCount)
    throwInputError(name, "header", std::to_string(sections) + " sections", std::to_string(kSectionCount));
  if (bytes.size() < fixed) throwInputError(name, "header", "file has " + std::to_string(bytes.size()) + " bytes", "at least " + std::to_string(fixed));
  const std::size_t checked = bytes.size() - kChecksumSize;
  if (le64(bytes.data() + checked) != hashBytes(bytes.first(checked)))
    throwInputError(name, "checksum", "content does not match its checksum (corrupt or truncated)", "an intact cooked file");
  if (le32(bytes.data() + 20) != 0) throwInputError(name, "header", "reserved field is not 0", "0");

  CookedAsset a;
  std::uint64_t expectOffset = kHeaderSize + kEntrySize * kSectionCount;
  for (std::uint32_t t = 1; t <= kSectionCount; ++t) {
    const std::uint8_t* e = bytes.data() + kHeaderSize + kEntrySize * (t - 1);
    const std::string where = "section " + std::to_string(t);
    const std::uint64_t offset = le64(e + 8), size = le64(e + 16);
    if (le32(e) != t || le32(e + 4) != 0) throwInputError(name, where, "section table entry has type " + std::to_string(le32(e)), "type " + std::to_string(t));
    if (offset != expectOffset || size > checked || offset > checked - size)
      throwInputError(name, where, "offset " + std::to_string(offset) + " size " + std::to_string(size) + " out of place",
                      "sections back to back inside the file");
    Reader r(bytes.subspan(std::size_t(offset), std::size_t(size)), name, where);
    section(r, SectionType(t), a);
    if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes left after parsing", "the section to end");
    expectOffset = offset + size;
  }
  if (expectOffset != checked) throwInputError(name, "payload", "bytes between the last section and the checksum", "none");
  validate(a, name);
  return a;
}

}  // namespace bounce::asset
