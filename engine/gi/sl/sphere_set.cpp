#include "engine/gi/sl/sphere_set.hpp"

#include <cmath>
#include <cstring>

#include "engine/core/binary_io.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"

namespace bounce::gi::sl {
namespace {

constexpr char kMagic[8] = {'B', 'S', 'L', 'S', 'P', 'S', 'E', 'T'};
constexpr std::uint32_t kVersion = 2;  // 2: SlSphere::bounceScale
constexpr std::uint32_t kMaxVertices = 1u << 26;
constexpr std::uint32_t kMaxJoints = 1u << 16;

class Writer : public BinaryWriter {
 public:
  template <class T>
  void putVector(const std::vector<T>& v) {
    put(std::uint32_t(v.size()));
    for (const T& x : v) put(x);
  }
};

// Errors name the byte: "file: where (byte N): what (expected …)".
class Reader : public BinaryReader {
 public:
  Reader(std::span<const std::uint8_t> b, const std::string& file)
      : BinaryReader(b, file, "a complete SL sphere-set file", ByteOffset::Parenthesised) {}
  float getFinite(const std::string& what) {
    const float v = get<float>(what);
    if (!std::isfinite(v)) fail(what, "non-finite value", "finite floats");
    return v;
  }
  glm::vec3 getVec3(const std::string& what) { return {getFinite(what), getFinite(what), getFinite(what)}; }
  std::uint32_t getCount(const std::string& what, std::uint32_t limit) {
    const auto n = get<std::uint32_t>(what);
    if (n > limit) fail(what, "count " + std::to_string(n), "at most " + std::to_string(limit));
    return n;
  }
};

}  // namespace

void checkSettings(const BakeSettings& s) {
  if (s.spheres < kMinSpheres || s.spheres > kMaxSpheres || (s.order != 3 && s.order != 4) || s.directions < 1 ||
      s.directions > kMaxDirections || s.samplesPerAxis < 1 || s.samplesPerAxis > 1024 || s.surfaceSamples < 1 ||
      s.iterations < 0)
    throw InternalError("sl::BakeSettings out of range");
}

std::vector<std::uint8_t> serialize(const SphereSet& set) {
  checkSettings(set.settings);
  const std::size_t nc = std::size_t(set.settings.order) * set.settings.order;
  Writer w;
  writeHeader(w, kMagic, kVersion);
  const BakeSettings& s = set.settings;
  for (int v : {s.spheres, s.order, s.directions, s.samplesPerAxis, s.surfaceSamples, s.iterations})
    w.put(std::int32_t(v));
  w.put(set.boundCentre);
  w.put(set.boundRadius);
  w.put(set.coverageError);
  w.put(set.volumeOvershoot);
  w.put(std::uint32_t(set.spheres.size()));
  for (const SlSphere& sp : set.spheres) {
    w.put(sp.centre);
    w.put(sp.radius);
    w.put(sp.intersects);
    w.putVector(sp.vertices);
    w.putVector(sp.joints);
    w.put(std::uint32_t(sp.samples.size()));
    for (const SurfaceSample& x : sp.samples) {
      w.put(x.position);
      w.put(x.normal);
      w.put(x.direction);
      if (x.basis.size() != nc) throw InternalError("sl::serialize: basis size");
      for (float b : x.basis) w.put(b);
    }
    if (sp.albedo.size() != nc * 3) throw InternalError("sl::serialize: albedo size");
    for (float a : sp.albedo) w.put(a);
    w.put(sp.bounceScale);
    w.put(sp.shadowScale);
  }
  return std::move(w.bytes);
}

SphereSet deserialize(std::span<const std::uint8_t> bytes, const std::string& file) {
  Reader r(bytes, file);
  readHeader(r, kMagic, kVersion, "not an SL sphere set");
  SphereSet set;
  BakeSettings& s = set.settings;
  s.spheres = r.get<std::int32_t>("settings");
  s.order = r.get<std::int32_t>("settings");
  s.directions = r.get<std::int32_t>("settings");
  s.samplesPerAxis = r.get<std::int32_t>("settings");
  s.surfaceSamples = r.get<std::int32_t>("settings");
  s.iterations = r.get<std::int32_t>("settings");
  try {
    checkSettings(s);
  } catch (const InternalError&) {
    r.fail("settings", "out of range", "spheres 1..64, order 3|4, directions 1..1024, positive counts");
  }
  const std::size_t nc = std::size_t(s.order) * s.order;
  set.boundCentre = r.getVec3("bound");
  set.boundRadius = r.getFinite("bound");
  set.coverageError = r.getFinite("coverageError");
  set.volumeOvershoot = r.getFinite("volumeOvershoot");
  if (set.boundRadius < 0.0f) r.fail("bound", "negative radius", "radius >= 0");
  if (set.coverageError < 0.0f || set.coverageError > 1.0f) r.fail("coverageError", "outside [0, 1]", "a fraction");
  const std::uint32_t count = r.getCount("spheres", std::uint32_t(kMaxSpheres));
  if (int(count) != s.spheres) r.fail("spheres", std::to_string(count) + " spheres", std::to_string(s.spheres) + " (the settings)");
  set.spheres.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::string where = "spheres/" + std::to_string(i);
    SlSphere& sp = set.spheres[i];
    sp.centre = r.getVec3(where + "/centre");
    sp.radius = r.getFinite(where + "/radius");
    if (sp.radius < 0.0f) r.fail(where + "/radius", "negative", "radius >= 0");
    sp.intersects = r.get<std::uint64_t>(where + "/intersects");
    if (count < 64 && (sp.intersects >> count) != 0) r.fail(where + "/intersects", "bit beyond the sphere count", "bits < count");
    sp.vertices.resize(r.getCount(where + "/vertices", kMaxVertices));
    for (auto& v : sp.vertices) v = r.get<std::uint32_t>(where + "/vertices");
    sp.joints.resize(r.getCount(where + "/joints", kMaxJoints));
    for (auto& j : sp.joints) j = r.get<std::uint16_t>(where + "/joints");
    sp.samples.resize(r.getCount(where + "/samples", std::uint32_t(s.directions)));
    for (SurfaceSample& x : sp.samples) {
      x.position = r.getVec3(where + "/samples");
      x.normal = r.getVec3(where + "/samples");
      x.direction = r.get<std::uint32_t>(where + "/samples");
      if (x.direction >= std::uint32_t(s.directions)) r.fail(where + "/samples", "direction index out of range", "< directions");
      x.basis.resize(nc);
      for (float& b : x.basis) b = r.getFinite(where + "/samples/basis");
    }
    sp.albedo.resize(nc * 3);
    for (float& a : sp.albedo) a = r.getFinite(where + "/albedo");
    sp.bounceScale = r.getFinite(where + "/bounceScale");
    if (!(sp.bounceScale > 0.0f) || sp.bounceScale > 1.0f) r.fail(where + "/bounceScale", "outside (0, 1]", "a scale in (0, 1]");
    sp.shadowScale = r.getFinite(where + "/shadowScale");
    if (!(sp.shadowScale > 0.0f) || sp.shadowScale > 1.0f) r.fail(where + "/shadowScale", "outside (0, 1]", "a scale in (0, 1]");
  }
  if (!r.atEnd()) r.fail("end", "trailing bytes", "nothing after the last sphere");
  return set;
}

void save(const SphereSet& set, const std::filesystem::path& path) {
  const auto bytes = serialize(set);
  writeFileAtomic(path, std::span<const std::uint8_t>(bytes));
}

SphereSet load(const std::filesystem::path& path) { return deserialize(readFileBytes(path), path.string()); }

}  // namespace bounce::gi::sl
