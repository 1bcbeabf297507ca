#include "engine/gi/rtf/field.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "engine/core/binary_io.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/math/sh_project.hpp"

namespace bounce::gi::rtf {

namespace {
constexpr char kMagic[8] = {'B', 'R', 'T', 'F', 'F', 'L', 'D', '\0'};
// v2: the CPCA basis and α as IEEE halves (v1: fp32). A v1 file fails the version check and is
// re-baked through loadOrBake with its one warning (its cache key changed too: bake.cpp).
// v3: n₈ (byteComponents) in the settings; the last n₈ components as 8-bit codes and scales.
constexpr std::uint32_t kVersion = 3;
}  // namespace

void checkSettings(const FieldSettings& s) {
  if (s.proxies < 1 || s.proxies > 64) throw InternalError("rtf: proxies must be in [1, 64]");
  if (s.spheres < 2 || s.spheres > 64) throw InternalError("rtf: spheres must be in [2, 64]");
  if (s.faceSize < 1 || s.faceSize > 64) throw InternalError("rtf: faceSize must be in [1, 64]");
  if (!(s.innerRadius > 0.0f) || !(s.outerRadius > s.innerRadius) || !std::isfinite(s.outerRadius))
    throw InternalError("rtf: radii must satisfy 0 < inner < outer");
  if (s.raysPerAxis < 1 || s.raysPerAxis > 256 || s.vertexRaysPerAxis < 1 || s.vertexRaysPerAxis > 256)
    throw InternalError("rtf: rays per axis must be in [1, 256]");
  if (s.selfBounces < 0 || s.selfBounces > 8) throw InternalError("rtf: selfBounces must be in [0, 8]");
  if (s.clusters < 1 || s.clusters > 4096 || s.components < 0 || s.components > 256)
    throw InternalError("rtf: clusters in [1, 4096], components in [0, 256]");
  if (s.byteComponents < 0 || s.byteComponents > s.components) throw InternalError("rtf: byteComponents in [0, components]");
}

float sphereRadius(const FieldSettings& s, int index) {
  return s.innerRadius + (s.outerRadius - s.innerRadius) * float(index) / float(s.spheres - 1);
}
int samplesPerSphere(const FieldSettings& s) { return 6 * s.faceSize * s.faceSize; }
std::size_t sampleCount(const FieldSettings& s) { return std::size_t(s.spheres) * std::size_t(samplesPerSphere(s)); }
glm::vec3 sampleDirection(const FieldSettings& s, std::size_t index) {
  const int n2 = s.faceSize * s.faceSize, rest = int(index % std::size_t(samplesPerSphere(s)));
  return glm::vec3(sh::cubeTexelDirection(rest / n2, rest % n2 % s.faceSize, rest % n2 / s.faceSize, s.faceSize));
}
glm::vec3 samplePosition(const FieldSettings& s, std::size_t index) {
  return sphereRadius(s, int(index / std::size_t(samplesPerSphere(s)))) * sampleDirection(s, index);
}
std::size_t itfDimension(const FieldSettings& s) { return std::size_t(s.proxies) * kShCount * kShCount * 3; }

namespace {

bool allFinite(const std::vector<float>& v) {
  for (float x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

std::vector<std::uint16_t> halves(const std::vector<float>& v) {
  std::vector<std::uint16_t> h(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) h[i] = glm::packHalf1x16(v[i]);
  return h;
}

std::vector<float> floats(const std::vector<std::uint16_t>& h) {
  std::vector<float> v(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) v[i] = glm::unpackHalf1x16(h[i]);  // exact; inf/NaN stay so (checked)
  return v;
}

}  // namespace

std::vector<std::uint8_t> serialize(const Field& f) {
  checkSettings(f.settings);
  const FieldSettings& s = f.settings;
  if (f.proxies.size() != std::size_t(s.proxies) || f.itf.samples() != sampleCount(s) ||
      std::size_t(f.itf.dimension) != itfDimension(s) || f.oof.size() != sampleCount(s) * kShCount)
    throw InternalError("rtf::serialize: field does not match its settings");
  // The file holds halves and codes: a Cpca not rounded by quantize would load as another field.
  if (f.itf.byteComponents != s.byteComponents || !isQuantized(f.itf))
    throw InternalError("rtf::serialize: CPCA not quantized to the settings' storage (rtf::quantize)");
  BinaryWriter w;
  writeHeader(w, kMagic, kVersion);
  w.put(std::int32_t(s.proxies)), w.put(std::int32_t(s.spheres)), w.put(std::int32_t(s.faceSize));
  w.put(s.innerRadius), w.put(s.outerRadius);
  w.put(std::int32_t(s.raysPerAxis)), w.put(std::int32_t(s.vertexRaysPerAxis)), w.put(std::int32_t(s.selfBounces));
  w.put(std::int32_t(s.clusters)), w.put(std::int32_t(s.components)), w.put(std::int32_t(s.byteComponents));
  w.put(f.centre), w.put(f.radius);
  w.putAll(f.proxies);
  w.put(std::int32_t(f.itf.clusters));  // ≤ settings.clusters (fewer when there are fewer samples)
  const CpcaParts parts = storedParts(f.itf);
  w.putAll(halves(parts.basisHalves));
  w.putAll(parts.basisCodes);
  w.putAll(f.itf.basisScale);
  w.putAll(f.itf.cluster);
  w.putAll(halves(parts.alphaHalves));
  w.putAll(parts.alphaCodes);
  w.putAll(f.itf.alphaScale);
  w.putAll(f.oof);
  w.put(f.frobenius);
  w.put(hashBytes(w.bytes));  // a flipped bit anywhere makes the file invalid (re-baked, never trusted)
  return std::move(w.bytes);
}

Field deserialize(std::span<const std::uint8_t> bytes, const std::string& file) {
  BinaryReader r(bytes, file, "a complete RTF field file");
  readHeader(r, kMagic, kVersion, "not an RTF field");
  Field f;
  FieldSettings& s = f.settings;
  s.proxies = r.get<std::int32_t>("proxies"), s.spheres = r.get<std::int32_t>("spheres");
  s.faceSize = r.get<std::int32_t>("faceSize");
  s.innerRadius = r.get<float>("innerRadius"), s.outerRadius = r.get<float>("outerRadius");
  s.raysPerAxis = r.get<std::int32_t>("raysPerAxis"), s.vertexRaysPerAxis = r.get<std::int32_t>("vertexRaysPerAxis");
  s.selfBounces = r.get<std::int32_t>("selfBounces");
  s.clusters = r.get<std::int32_t>("clusters"), s.components = r.get<std::int32_t>("components");
  s.byteComponents = r.get<std::int32_t>("byteComponents");
  try {
    checkSettings(s);
  } catch (const InternalError& e) {
    r.fail("settings", e.what(), "settings within field.cpp checkSettings ranges");
  }
  f.centre = r.get<glm::vec3>("centre");
  f.radius = r.get<float>("radius");
  if (!std::isfinite(f.radius) || !(f.radius > 0.0f) || !std::isfinite(f.centre.x + f.centre.y + f.centre.z))
    r.fail("radius", "non-finite or non-positive bounding sphere", "a finite centre and radius > 0");
  f.proxies = r.getAll<glm::vec3>(std::size_t(s.proxies), "proxies");
  for (const glm::vec3& p : f.proxies)
    if (!std::isfinite(p.x + p.y + p.z)) r.fail("proxies", "non-finite proxy", "finite proxy positions");
  const std::size_t N = sampleCount(s), D = itfDimension(s);
  const int nc = r.get<std::int32_t>("cpca");
  if (nc < 1 || nc > s.clusters || std::size_t(nc) > N)
    r.fail("cpca", "cluster count " + std::to_string(nc), "1.." + std::to_string(s.clusters));
  f.itf.dimension = int(D), f.itf.clusters = nc, f.itf.components = s.components, f.itf.byteComponents = s.byteComponents;
  const std::size_t ne = std::size_t(s.components), n8 = std::size_t(s.byteComponents), head = ne - n8;
  const std::vector<float> basisHalves = floats(r.getAll<std::uint16_t>(std::size_t(nc) * (head + 1) * D, "cpca basis"));
  const std::vector<std::int8_t> basisCodes = r.getAll<std::int8_t>(std::size_t(nc) * n8 * D, "cpca basis codes");
  f.itf.basisScale = r.getAll<float>(std::size_t(nc) * n8, "cpca basis scales");
  f.itf.cluster = r.getAll<std::uint32_t>(N, "cpca clusters");
  const std::vector<float> alphaHalves = floats(r.getAll<std::uint16_t>(N * head, "cpca coefficients"));
  const std::vector<std::int8_t> alphaCodes = r.getAll<std::int8_t>(N * n8, "cpca coefficient codes");
  f.itf.alphaScale = r.getAll<float>(n8 > 0 ? N : 0, "cpca coefficient scales");
  f.oof = r.getAll<float>(N * kShCount, "oof");
  f.frobenius = r.get<double>("frobenius");
  const std::size_t checked = r.position();
  if (r.get<std::uint64_t>("checksum") != hashBytes(bytes.first(checked)))
    r.fail("checksum", "checksum mismatch (corrupt file)", "the checksum of the bytes before it");
  if (!r.atEnd()) r.fail("checksum", "trailing bytes", "the checksum as the last 8 bytes");
  for (std::uint32_t c : f.itf.cluster)
    if (c >= std::uint32_t(nc)) r.fail("cpca clusters", "cluster index out of range", "< " + std::to_string(nc));
  for (const std::vector<float>* v : {&f.itf.basisScale, &f.itf.alphaScale})
    for (float x : *v)
      if (!std::isfinite(x) || x < 0.0f) r.fail("cpca scales", "negative or non-finite scale", "finite scales >= 0");
  for (const std::vector<std::int8_t>* v : {&basisCodes, &alphaCodes})
    for (std::int8_t q : *v)
      if (q == -128) r.fail("cpca codes", "code -128", "codes in -127..127 (cpca.hpp quantize)");
  // Decoded as quantize leaves them: the halves and float(scale·code) in the in-memory layout.
  f.itf.basis.resize(std::size_t(nc) * (ne + 1) * D);
  for (std::size_t h = 0; h < std::size_t(nc); ++h) {
    std::copy_n(basisHalves.begin() + std::ptrdiff_t(h * (head + 1) * D), (head + 1) * D, f.itf.basis.begin() + std::ptrdiff_t(h * (ne + 1) * D));
    for (std::size_t t = 0; t < n8; ++t)
      for (std::size_t d = 0; d < D; ++d)
        f.itf.basis[(h * (ne + 1) + head + 1 + t) * D + d] = f.itf.basisScale[h * n8 + t] * float(basisCodes[(h * n8 + t) * D + d]);
  }
  f.itf.alpha.resize(N * ne);
  for (std::size_t s8 = 0; s8 < N; ++s8) {
    std::copy_n(alphaHalves.begin() + std::ptrdiff_t(s8 * head), head, f.itf.alpha.begin() + std::ptrdiff_t(s8 * ne));
    for (std::size_t t = 0; t < n8; ++t) f.itf.alpha[s8 * ne + head + t] = f.itf.alphaScale[s8] * float(alphaCodes[s8 * n8 + t]);
  }
  if (!allFinite(f.itf.basis) || !allFinite(f.itf.alpha) || !allFinite(f.oof) || !std::isfinite(f.frobenius))
    r.fail("data", "non-finite value", "finite floats");
  return f;
}

void save(const Field& field, const std::filesystem::path& path) {
  const auto bytes = serialize(field);
  writeFileAtomic(path, std::span<const std::uint8_t>(bytes));
}

Field load(const std::filesystem::path& path) {
  const auto bytes = readFileBytes(path);
  return deserialize(bytes, path.string());
}

}  // namespace bounce::gi::rtf
