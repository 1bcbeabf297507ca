#include "engine/gi/probes/probe_volume.hpp"

#include <cmath>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/math/sh.hpp"

namespace bounce::gi::probes {

namespace glsl {
using namespace glm;
// GLSL parameter qualifiers: `out int probe[8]` decays to a pointer, so writes reach the caller.
#define in
#define out
#define PROBE_DATA_PARAM const ProbeVolume &volume,
#define PROBE_DATA_ARG volume,
#define PROBE_VALID(i) (volume.valid[std::size_t(i)] != 0u)
#define PROBE_MOMENTS(i, b) volume.moments[std::size_t(i) * kVisBins + std::size_t(b)]
#include "shaders/probes/probe_weights.glsl"
#undef PROBE_MOMENTS
#undef PROBE_VALID
#undef PROBE_DATA_PARAM
#undef PROBE_DATA_ARG
#undef in
#undef out
static_assert(kVisRes == 8 && kVisBins == 64, "keep in step with probe_weights.glsl");
}  // namespace glsl

int visBin(const glm::vec3& dir) { return glsl::probeVisBin(dir); }

glm::vec3 ProbeGrid::position(std::size_t index) const {
  const std::size_t x = index % count.x, y = (index / count.x) % count.y, z = index / (std::size_t(count.x) * count.y);
  return origin + spacing * glm::vec3(float(x), float(y), float(z));
}

void ProbeVolume::weights(const glm::vec3& pos, const glm::vec3& normal, const glm::vec3& view, int probe[8],
                          float weight[8]) const {
  const glm::vec3 q = pos + grid.spacing * (bias.normal * normal + bias.view * view);
  glsl::probeWeights(*this, grid.count, grid.origin, grid.spacing, minVariance(), q, normal, probe, weight);
}

std::vector<glm::vec3> ProbeVolume::radianceSH(const glm::vec3& pos, const glm::vec3& normal) const {
  std::vector<glm::vec3> out;
  radianceAt(pos, normal, out, nullptr);
  return out;
}

glm::vec3 ProbeVolume::dirMapTexel(std::size_t probe, int texel) const {
  const std::uint16_t* h = &dirMap[(probe * math::kOctMapTexels + std::size_t(texel)) * 3];
  return {glm::unpackHalf1x16(h[0]), glm::unpackHalf1x16(h[1]), glm::unpackHalf1x16(h[2])};
}

void ProbeVolume::radianceAt(const glm::vec3& pos, const glm::vec3& normal, std::vector<glm::vec3>& out,
                             std::vector<glm::vec3>* map) const {
  int probe[8];
  float weight[8];
  weights(pos, normal, glm::vec3(0.0f), probe, weight);
  out.assign(std::size_t(coeffs()), glm::vec3(0.0f));
  for (int k = 0; k < 8; ++k) {
    if (weight[k] == 0.0f) continue;
    const glm::vec3* c = &sh[std::size_t(probe[k]) * coeffs()];
    for (int i = 0; i < coeffs(); ++i) out[i] += weight[k] * c[i];
  }
  if (!map) return;
  map->assign(math::kOctMapTexels, glm::vec3(0.0f));
  if (hasDirMap()) {
    for (int k = 0; k < 8; ++k) {
      if (weight[k] == 0.0f) continue;
      for (int t = 0; t < math::kOctMapTexels; ++t) (*map)[std::size_t(t)] += weight[k] * dirMapTexel(std::size_t(probe[k]), t);
    }
  } else {
    for (int t = 0; t < math::kOctMapTexels; ++t)
      (*map)[std::size_t(t)] = sh::evalSum<glm::vec3, float>(out, math::octTexelDirection(t));
  }
}

glm::vec3 ProbeVolume::irradiance(const glm::vec3& pos, const glm::vec3& normal, const glm::vec3& view) const {
  int probe[8];
  float weight[8];
  weights(pos, normal, view, probe, weight);
  std::vector<glm::vec3> l(std::size_t(coeffs()), glm::vec3(0.0f));
  for (int k = 0; k < 8; ++k) {
    if (weight[k] == 0.0f) continue;
    const glm::vec3* c = &sh[std::size_t(probe[k]) * coeffs()];
    for (int i = 0; i < coeffs(); ++i) l[i] += weight[k] * c[i];
  }
  return sh::evalIrradiance<glm::vec3, float>(l, normal);
}

namespace {

constexpr char kMagic[4] = {'B', 'P', 'R', 'B'};
// Refuse absurd headers before allocating: 2^24 probes is far beyond any level (a 0.02 m grid over
// a 5 m room is 1.6e7).
constexpr std::uint64_t kMaxProbes = 1u << 24;

struct Header {
  char magic[4];
  std::uint32_t version;
  std::int32_t count[3];
  float origin[3];
  float spacing;
  std::int32_t order;
  std::int32_t visBins;
  float bias[2];
  std::int32_t dirMapRes;  // math::kOctMapRes, or 0: no direction maps
};

// resize + memcpy, not vector::insert: GCC 12 at -O3 reads insert's reallocating path into the
// reserved vector as a write past a 52-byte (one Header) allocation (-Wstringop-overflow, a false
// positive); the bytes are the same.
template <class T>
void append(std::vector<std::uint8_t>& out, const T* data, std::size_t n) {
  if (n == 0) return;
  const std::size_t at = out.size();
  out.resize(at + n * sizeof(T));
  std::memcpy(out.data() + at, data, n * sizeof(T));
}

}  // namespace

std::vector<std::uint8_t> serialize(const ProbeVolume& v) {
  Header h{};
  std::memcpy(h.magic, kMagic, 4);
  h.version = kProbeFormatVersion;
  for (int i = 0; i < 3; ++i) h.count[i] = v.grid.count[i], h.origin[i] = v.grid.origin[i];
  h.spacing = v.grid.spacing;
  h.order = v.order;
  h.visBins = kVisBins;
  h.bias[0] = v.bias.normal, h.bias[1] = v.bias.view;
  h.dirMapRes = v.hasDirMap() ? math::kOctMapRes : 0;
  std::vector<std::uint8_t> out;
  // Sized up front: one allocation.
  out.reserve(sizeof h + v.sh.size() * sizeof(glm::vec3) + v.moments.size() * sizeof(glm::vec2) +
              v.valid.size() * sizeof(std::uint32_t) + v.dirMap.size() * sizeof(std::uint16_t) + sizeof(std::uint64_t));
  append(out, &h, 1);
  append(out, v.sh.data(), v.sh.size());
  append(out, v.moments.data(), v.moments.size());
  append(out, v.valid.data(), v.valid.size());
  if (h.dirMapRes != 0) append(out, v.dirMap.data(), v.dirMap.size());
  const std::uint64_t sum = hashBytes(out);
  append(out, &sum, 1);
  return out;
}

ProbeVolume deserialize(std::span<const std::uint8_t> bytes, const std::string& name) {
  auto fail = [&](const std::string& what) { throwInputError(name, "probe volume", what, "a probe cache written by this build"); };
  if (bytes.size() < sizeof(Header) + sizeof(std::uint64_t)) fail("file too short");
  Header h;
  std::memcpy(&h, bytes.data(), sizeof h);
  if (std::memcmp(h.magic, kMagic, 4) != 0) fail("bad magic");
  if (h.version != kProbeFormatVersion) fail("format version " + std::to_string(h.version));
  if (h.order < 2 || h.order > 3) fail("SH order " + std::to_string(h.order));
  if (h.visBins != kVisBins) fail("visibility bin count " + std::to_string(h.visBins));
  if (h.dirMapRes != 0 && h.dirMapRes != math::kOctMapRes) fail("direction map resolution " + std::to_string(h.dirMapRes));
  std::uint64_t probes = 1;
  for (int i = 0; i < 3; ++i) {
    if (h.count[i] < 1 || !std::isfinite(h.origin[i])) fail("bad grid");
    probes *= std::uint64_t(h.count[i]);
    if (probes > kMaxProbes) fail("too many probes");
  }
  if (!std::isfinite(h.spacing) || !(h.spacing > 0.0f) || !std::isfinite(h.bias[0]) || !std::isfinite(h.bias[1]))
    fail("bad spacing or bias");
  const std::size_t nSh = std::size_t(probes) * h.order * h.order, nMom = std::size_t(probes) * kVisBins;
  const std::size_t nMap = h.dirMapRes != 0 ? std::size_t(probes) * math::kOctMapTexels * 3 : 0;
  const std::size_t expected = sizeof(Header) + nSh * sizeof(glm::vec3) + nMom * sizeof(glm::vec2) +
                               std::size_t(probes) * sizeof(std::uint32_t) + nMap * sizeof(std::uint16_t) +
                               sizeof(std::uint64_t);
  if (bytes.size() != expected) fail("size " + std::to_string(bytes.size()) + ", header implies " + std::to_string(expected));
  std::uint64_t sum;
  std::memcpy(&sum, bytes.data() + expected - sizeof sum, sizeof sum);
  if (sum != hashBytes(bytes.first(expected - sizeof sum))) fail("checksum mismatch");

  ProbeVolume v;
  v.grid.count = {h.count[0], h.count[1], h.count[2]};
  v.grid.origin = {h.origin[0], h.origin[1], h.origin[2]};
  v.grid.spacing = h.spacing;
  v.order = h.order;
  v.bias = {h.bias[0], h.bias[1]};
  v.sh.resize(nSh);
  v.moments.resize(nMom);
  v.valid.resize(std::size_t(probes));
  const std::uint8_t* p = bytes.data() + sizeof(Header);
  std::memcpy(v.sh.data(), p, nSh * sizeof(glm::vec3));
  p += nSh * sizeof(glm::vec3);
  std::memcpy(v.moments.data(), p, nMom * sizeof(glm::vec2));
  p += nMom * sizeof(glm::vec2);
  std::memcpy(v.valid.data(), p, v.valid.size() * sizeof(std::uint32_t));
  p += v.valid.size() * sizeof(std::uint32_t);
  v.dirMap.resize(nMap);
  if (nMap != 0) std::memcpy(v.dirMap.data(), p, nMap * sizeof(std::uint16_t));  // no maps: data() may be null (UB)
  for (std::uint16_t half : v.dirMap)
    if (!std::isfinite(glm::unpackHalf1x16(half))) fail("non-finite direction map texel");
  for (const glm::vec3& c : v.sh)
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) fail("non-finite SH coefficient");
  for (const glm::vec2& m : v.moments)
    if (!std::isfinite(m.x) || !std::isfinite(m.y) || m.x < 0.0f) fail("bad visibility moments");
  for (std::uint32_t f : v.valid)
    if (f > 1u) fail("bad valid flag");
  return v;
}

}  // namespace bounce::gi::probes
