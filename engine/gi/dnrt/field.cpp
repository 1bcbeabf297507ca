#include "engine/gi/dnrt/field.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/core/binary_io.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"

namespace bounce::gi::dnrt {

namespace {
constexpr char kMagic[8] = {'B', 'D', 'N', 'R', 'T', 'F', 'L', 'D'};
constexpr std::uint32_t kVersion = 2;  // 2: a checksum of every byte before it ends the file
constexpr int kMaxGrid = 256;  // 256³·4·7 bytes = 470 MB: far beyond any sensible field
// FieldSettings::occlusionOnly rides in the anti-radiance word, so fields written before it read as they were.
constexpr std::uint32_t kOcclusionOnlyBit = 1u << 8;
}  // namespace

void checkSettings(const FieldSettings& s) {
  if (s.shCount != 4 && s.shCount != 9) throw InternalError("dnrt: shCount must be 4 or 9");
  if (s.grid < 2 || s.grid > kMaxGrid) throw InternalError("dnrt: grid must be in [2, 256]");
  if (!(s.innerExtent > 0.0f) || !(s.outerExtent > s.innerExtent) || !std::isfinite(s.outerExtent))
    throw InternalError("dnrt: extents must satisfy 0 < inner < outer");
  if (s.samplesPerAxis < 1 || s.samplesPerAxis > 1024) throw InternalError("dnrt: samplesPerAxis in [1, 1024]");
  if (s.antiRadiance != AntiRadiance::Paper && s.antiRadiance != AntiRadiance::Improved)
    throw InternalError("dnrt: unknown anti-radiance mode");
}

int textureCount(int shCount) { return shCount == 9 ? 7 : 3; }

namespace {
// max over unit vectors of |Y_j| for the real orthonormal basis (index l(l+1)+m): Y_00 = 0.2821;
// band 1 0.4886·(y, z, x) → 0.4886; band 2: 1.0925·xy, yz, xz → 0.5463 (at |xy| = ½),
// 0.3154·(3z² − 1) → 0.6308 (at z = ±1), 0.5463·(x² − y²) → 0.5463.
constexpr float kMaxAbsY[9] = {0.28209479f, 0.48860251f, 0.48860251f, 0.48860251f, 0.54627422f,
                               0.54627422f, 0.63078313f, 0.54627422f, 0.54627422f};
constexpr float kPiF = 3.14159265358979f;
// Table 1 of the paper, [lo, hi] per m_j.
constexpr float kTable1[9][2] = {{-0.2820f, 0.0f},    {-0.9772f, 0.9772f}, {-0.9772f, 0.9772f},
                                 {-0.9772f, 0.9772f}, {-2.1850f, 2.1850f}, {-2.1850f, 2.1850f},
                                 {-1.2615f, 1.2615f}, {-2.1850f, 2.1850f}, {-1.0925f, 1.0925f}};
// Float rounding of the estimator's sums (accumulated in double, stored as float).
constexpr float kBoundSlack = 1e-6f;
}  // namespace

Range analyticRange(int j, AntiRadiance mode) {
  if (j < 0 || j >= 9) throw InternalError("dnrt::analyticRange: j out of range");
  if (j == 0) return {-kMaxAbsY[0] / kPiF, 0.0f};
  const int l = j < 4 ? 1 : 2;
  // s_l = π/Â_l: Â_1 = 2π/3, Â_2 = π/4 (bake.hpp, App. B.2).
  const float s = mode == AntiRadiance::Improved ? (l == 1 ? 1.5f : 4.0f) : 1.0f;
  const float b = (1.0f + s) * kMaxAbsY[j] / kPiF;
  return {-b, b};
}

Range table1Range(int j) {
  if (j < 0 || j >= 9) throw InternalError("dnrt::table1Range: j out of range");
  return {kTable1[j][0], kTable1[j][1]};
}

bool rangesWithinAnalyticBound(const Field& f) {
  for (int j = 0; j < f.settings.shCount; ++j)
    for (int c = 0; c < 3; ++c) {
      const Slot s = slotOf(j, c);
      const Range& r = f.ranges[std::size_t(s.texture) * 4 + s.component];
      const Range b = analyticRange(j, f.settings.antiRadiance);
      if (r.lo < b.lo - kBoundSlack || r.hi > b.hi + kBoundSlack) return false;
    }
  return true;
}

Slot slotOf(int j, int channel) {
  if (j < 4) return {channel, j};
  if (j < 8) return {3 + channel, j - 4};
  return {6, channel};
}

void Field::decodeVertex(std::size_t vertex, std::span<glm::vec3> out) const {
  for (int j = 0; j < settings.shCount; ++j)
    for (int c = 0; c < 3; ++c) {
      const Slot s = slotOf(j, c);
      const Range& r = ranges[std::size_t(s.texture) * 4 + s.component];
      const float byte = textures[std::size_t(s.texture)][vertex * 4 + std::size_t(s.component)];
      out[std::size_t(j)][c] = r.lo + (r.hi - r.lo) * (byte / 255.0f);
    }
}

Field quantize(const FieldSettings& settings, glm::vec3 centre, float radius, std::span<const glm::vec3> values) {
  checkSettings(settings);
  Field f;
  f.settings = settings;
  f.centre = centre;
  f.radius = radius;
  const std::size_t nv = f.vertexCount(), nc = std::size_t(settings.shCount);
  if (values.size() != nv * nc) throw InternalError("dnrt::quantize: value count does not match the grid");
  const int nt = textureCount(settings.shCount);
  f.ranges.assign(std::size_t(nt) * 4, Range{});
  std::vector<bool> seen(f.ranges.size(), false);
  for (std::size_t v = 0; v < nv; ++v)
    for (int j = 0; j < settings.shCount; ++j)
      for (int c = 0; c < 3; ++c) {
        const Slot s = slotOf(j, c);
        Range& r = f.ranges[std::size_t(s.texture) * 4 + s.component];
        const float x = values[v * nc + j][c];
        if (!std::isfinite(x)) throw InternalError("dnrt::quantize: non-finite coefficient");
        const std::size_t k = std::size_t(s.texture) * 4 + s.component;
        if (!seen[k]) r = {x, x}, seen[k] = true;
        r.lo = std::min(r.lo, x), r.hi = std::max(r.hi, x);
      }
  // Decoding computes lo + (hi − lo)·t in float (here and in dnrt.frag): a span that overflows
  // would turn every texel into Inf or NaN.
  for (const Range& r : f.ranges)
    if (!std::isfinite(r.hi - r.lo)) throw InternalError("dnrt::quantize: coefficient range too wide for float");
  f.textures.assign(std::size_t(nt), std::vector<std::uint8_t>(nv * 4, 0));
  for (std::size_t v = 0; v < nv; ++v)
    for (int j = 0; j < settings.shCount; ++j)
      for (int c = 0; c < 3; ++c) {
        const Slot s = slotOf(j, c);
        const Range& r = f.ranges[std::size_t(s.texture) * 4 + s.component];
        const float span = r.hi - r.lo;
        const float t = span > 0.0f ? (values[v * nc + j][c] - r.lo) / span : 0.0f;
        f.textures[std::size_t(s.texture)][v * 4 + s.component] =
            static_cast<std::uint8_t>(std::clamp(std::lround(t * 255.0f), 0L, 255L));
      }
  return f;
}

QuantizationError quantizationError(const Field& field, std::span<const glm::vec3> values) {
  QuantizationError e;
  for (const Range& r : field.ranges) e.bound = std::max(e.bound, (r.hi - r.lo) / 510.0f);
  const std::size_t nc = std::size_t(field.settings.shCount);
  std::vector<glm::vec3> m(nc);
  for (std::size_t v = 0; v < field.vertexCount(); ++v) {
    field.decodeVertex(v, m);
    for (std::size_t j = 0; j < nc; ++j)
      for (int c = 0; c < 3; ++c) e.maxAbs = std::max(e.maxAbs, std::abs(m[j][c] - values[v * nc + j][c]));
  }
  return e;
}

std::vector<std::uint8_t> serialize(const Field& f) {
  checkSettings(f.settings);
  BinaryWriter w;
  writeHeader(w, kMagic, kVersion);
  w.put(std::int32_t(f.settings.shCount));
  w.put(std::int32_t(f.settings.grid));
  w.put(f.settings.innerExtent);
  w.put(f.settings.outerExtent);
  w.put(std::int32_t(f.settings.samplesPerAxis));
  w.put(std::uint32_t(f.settings.antiRadiance) | (f.settings.occlusionOnly ? kOcclusionOnlyBit : 0u));
  w.put(f.centre);
  w.put(f.radius);
  for (const Range& r : f.ranges) w.put(r);
  for (const auto& t : f.textures) w.putAll(t);
  w.put(hashBytes(w.bytes));  // a flipped bit anywhere makes the entry invalid (re-baked, never trusted)
  return std::move(w.bytes);
}

Field deserialize(std::span<const std::uint8_t> bytes, const std::string& file) {
  BinaryReader r(bytes, file, "a complete DNRT field file");
  readHeader(r, kMagic, kVersion, "not a DNRT field");
  Field f;
  f.settings.shCount = r.get<std::int32_t>("shCount");
  f.settings.grid = r.get<std::int32_t>("grid");
  f.settings.innerExtent = r.get<float>("innerExtent");
  f.settings.outerExtent = r.get<float>("outerExtent");
  f.settings.samplesPerAxis = r.get<std::int32_t>("samplesPerAxis");
  const auto mode = r.get<std::uint32_t>("antiRadiance");
  f.settings.antiRadiance = static_cast<AntiRadiance>(mode & ~kOcclusionOnlyBit);
  f.settings.occlusionOnly = (mode & kOcclusionOnlyBit) != 0;
  try {
    checkSettings(f.settings);
  } catch (const InternalError& e) {
    r.fail("settings", e.what(), "shCount 4|9, grid 2..256, 0 < inner < outer");
  }
  f.centre = r.get<glm::vec3>("centre");
  f.radius = r.get<float>("radius");
  if (!std::isfinite(f.radius) || !(f.radius > 0.0f) || !std::isfinite(f.centre.x + f.centre.y + f.centre.z))
    r.fail("radius", "non-finite or non-positive bounding sphere", "a finite centre and radius > 0");
  const int nt = textureCount(f.settings.shCount);
  f.ranges.resize(std::size_t(nt) * 4);
  for (Range& rg : f.ranges) {
    rg = r.get<Range>("ranges");
    if (!std::isfinite(rg.lo) || !std::isfinite(rg.hi) || rg.hi < rg.lo || !std::isfinite(rg.hi - rg.lo))
      r.fail("ranges", "a range is non-finite, inverted or too wide", "finite lo <= hi with a finite hi - lo");
  }
  const std::size_t texBytes = f.vertexCount() * 4;
  for (int t = 0; t < nt; ++t) {
    auto s = r.take(texBytes, "textures");
    f.textures.emplace_back(s.begin(), s.end());
  }
  const std::size_t checked = r.position();
  if (r.get<std::uint64_t>("checksum") != hashBytes(bytes.first(checked)))
    r.fail("checksum", "checksum mismatch (corrupt file)", "the checksum of the bytes before it");
  if (!r.atEnd()) r.fail("checksum", "trailing bytes", "exactly N³·4 bytes per texture, then the checksum");
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

}  // namespace bounce::gi::dnrt
