#pragma once
// Probe bake (effect `probes`): path-traced radiance SH and visibility moments for every probe of
// a grid over the level's STATIC geometry (entities marked dynamic, or moved by a motion script,
// and everything parented to them are left out, as in the DNRT paper: the probes are the static
// solution L_init that dynamic objects later modify).
//
// Per probe, `rays` directions from n×n stratified uniform sphere samples (n = √rays,
// sh::projectMonteCarlo with a seed from the probe index), each traced with ref::tracePathFrom
// (multi-bounce, next-event estimation, Russian roulette) and projected to radiance SH:
//   L_lm = 4π/N Σ_i L(ω_i) Y_lm(ω_i).
// The first hit distance of each ray, clamped to kMaxDistance·spacing, goes into its direction's
// visibility bin (mean and mean square, the DDGI moments). A probe whose rays hit back faces more
// than kBackfaceFraction of the time is inside geometry: it is flagged invalid and gets weight 0.
// Ringing is removed with the smallest Sloan window that makes the probe's irradiance
// non-negative along kWindowDirections directions (sh::minimalWindow, applied to radiance: the
// window and the cosine convolution are both per-band scalings, so they commute).
//
// The same rays also fill each probe's direction map (probe_volume.hpp dirMap, math::kOctMapRes²
// octahedral texels): texel t holds Σ_i w_i L(ω_i) / Σ_i w_i over the probe's rays, with the cone
// weight w_i = max(0, ω_i·c_t − cos kDirMapKernel) about the texel's centre direction c_t; a texel
// no ray reaches (none does at 256 rays; a bound for fewer) takes its nearest ray. Why a kernel and
// not the rays falling inside the texel: 256 rays over 256 texels leave some texels empty and most
// with one path each. No window: the map is not truncated.
//
// Deterministic (seeds from probe indices, each probe summed in sample order), TBB-parallel, with
// a progress bar; cached as <cache>/<key>.bin keyed by every input (loadOrBake).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/gi/probes/probe_volume.hpp"
#include "engine/ref/scene_bvh.hpp"
#include "engine/ref/tracer.hpp"
#include "engine/scene/level.hpp"

namespace bounce::gi::probes {

// Bump whenever the bake's output changes for the same inputs (part of the cache key).
// 2: virtual offset (probes inside or too close to geometry baked from a point moved out of it).
// 3: the direction maps.
inline constexpr std::uint32_t kBakerVersion = 3;
// Back-face hit fraction above which a probe counts as inside geometry (DDGI probe classification
// uses the same 25%: a probe in open space sees no back faces of closed, consistently wound meshes).
inline constexpr double kBackfaceFraction = 0.25;
// Hit distances are clamped to this many spacings: lookups only ever ask about receivers within
// √3 spacings (plus bias) of a probe, and the clamp keeps open-sky bins from inflating σ².
inline constexpr float kMaxDistance = 3.0f;
// The direction maps' cone half-angle (radians): 20°, against 256 rays' mean spacing of ~13°
// (√(4π/256)), so a texel averages ~8 rays (cone area 0.38 sr × 256/4π), tent-weighted.
inline constexpr double kDirMapKernel = 20.0 * 3.14159265358979324 / 180.0;
// Directions checked for negative irradiance when choosing the window (spherical Fibonacci).
inline constexpr int kWindowDirections = 256;

// Virtual offset (Unity's light-probe "virtual offset"; DDGI's probe relocation, Majercik et al.
// 2021, "Scaling Probe-Based Real-Time Dynamic Global Illumination for Production", §5.2): before a
// probe is baked, kOffsetDirections first-hit rays from its grid point look for geometry. A probe
// inside a closed solid (more than kBackfaceFraction back faces) moves through its nearest back face
// to kMinSurfaceDistance beyond it; a probe closer than kMinSurfaceDistance to a front face moves
// straight away from the nearest one; up to kOffsetIterations times (corners), never farther than
// kMaxOffset from its grid point. Its SH and visibility moments are then traced from the moved
// point. Why: a probe 3 cm from a lamp-lit wall (the 0.25 m grid in a 0.56 m box) sees that wall as
// half its sphere and hands the near-field glare to receivers 10+ cm away; a probe inside a block
// is invalid, and its neighbours' weights are renormalised onto far probes. Lookups keep using the
// grid positions (probe_weights.glsl, same data as before): the moments' distances are off by at
// most kMaxOffset for a moved probe, so Chebyshev still cuts what lies behind walls.
inline constexpr float kMinSurfaceDistance = 0.25f;  // × spacing
inline constexpr float kMaxOffset = 0.45f;           // × spacing (stays nearer its grid point than any other's)
inline constexpr int kOffsetDirections = 128;
inline constexpr int kOffsetIterations = 3;

// Seed of probe i's ray strata (sh::projectMonteCarlo in bakeProbes). The relight bake regenerates
// the same directions from it (relight.cpp probeRayDirections), so ray k of both bakes is one ray:
// one definition, or the relight cache's hit surfels stop matching the probe bake's directions.
// Distinct from the path generator's (math::Pcg32::fromIndex: a splitmix64 of the index, its own
// stream), so the strata and the paths are not one random sequence.
constexpr std::uint64_t probeRaySeed(std::size_t i) { return 0x9e3779b97f4a7c15ull ^ std::uint64_t(i); }

// The point a probe at `p` is baked from (virtual offset above); `p` itself when nothing is near.
glm::vec3 virtualOffset(const ref::SceneBvh& bvh, const glm::vec3& p, float spacing);

struct ProbeSettings {
  float spacing = 0.1f;        // metres between probes (0.1 m: 6×6×6 probes in the Cornell box)
  int order = 3;               // SH order: 2 (4 coefficients) or 3 (9, "L2")
  std::uint32_t rays = 256;    // per probe; a square whose root is a multiple of kVisRes (64, 256, 576, 1024, …)
  std::uint32_t bounces = ref::kUnlimitedBounces;  // indirect bounces after the first hit
  bool window = true;          // deringing window (off only to show the ringing it removes)
};

// InputError (`file`: `where`: …) when a setting is out of range.
void validate(const ProbeSettings& settings, const std::string& file, const std::string& where);

// Probes at the centres of cubic cells of side `spacing` covering [lo, hi] (at least one per
// axis), so none sits exactly on a bounding wall.
ProbeGrid gridOverBounds(const glm::vec3& lo, const glm::vec3& hi, float spacing);

struct BakeStats {
  std::size_t probes = 0;
  std::uint64_t rays = 0;     // every ray cast (path segments and shadow rays)
  double seconds = 0.0;
  std::size_t invalid = 0;    // probes flagged inside geometry
  std::size_t moved = 0;      // probes baked from a virtual offset
  double msPerProbe() const { return probes ? 1e3 * seconds / double(probes) : 0.0; }
};

ProbeVolume bakeProbes(const ref::SceneBvh& scene, const ProbeGrid& grid, const ProbeSettings& settings,
                       BakeStats* stats = nullptr, const std::string& label = "probes");

// The level without its dynamic entities (and their descendants): what the probes see.
scene::Level staticLevel(const scene::Level& level);
// staticLevel() instantiated at t = 0, its assets cooked (through the cache) and extracted, world
// space: the probes' scene, and the geometry DNRT's c_j test light visibility against.
ref::SceneDesc staticScene(const scene::Level& level, const std::filesystem::path& cookCache,
                           std::vector<std::string>* assetKeys = nullptr, bool withTextures = true);

// The probe bake settings of a level's "probes" object (InputError when the baker rejects them).
ProbeSettings settingsFrom(const scene::Level& level);

// One probe bake's inputs, gathered and hashed: the level instantiated without its dynamic
// entities, its assets cooked (through the cache), the static scene extracted. Cheap next to the
// bake itself: `bounce bake --job` and Session both start here.
struct BakeInput {
  ref::SceneDesc scene;   // the static scene, world space
  ProbeSettings settings;
  std::filesystem::path source;  // the level file (for messages)
  // Content key, 16 hex digits: the level file, the static scene (geometry, materials, textures,
  // lights, background), every asset's content key, the settings, kBakerVersion, kTracerVersion
  // and the format version.
  std::string key;
  std::vector<std::filesystem::path> files;  // the level file and every asset it instances
};
BakeInput prepare(const scene::Level& level, const std::filesystem::path& cookCache, const ProbeSettings& settings);

// The grid bakeToCache lays over the static scene's bounds (gridOverBounds at the settings' spacing).
ProbeGrid gridOf(const BakeInput& input);

// <probeCache>/<key>.bin
std::filesystem::path cachePath(const BakeInput& input, const std::filesystem::path& probeCache);

struct LoadResult {
  ProbeVolume volume;
  bool fromCache = false;
  std::filesystem::path file;  // the cache entry
  BakeStats stats;             // zero when loaded from the cache
};

// The entry at `file` when it is there and valid (format version, sizes, checksum, finite values);
// a corrupt or foreign entry is reported as a warning and counts as missing.
std::optional<ProbeVolume> loadCached(const std::filesystem::path& file);

// Bakes `input` (ignoring the cache) and writes cachePath(input, probeCache) atomically. Logs one
// info line with its statistics unless `logBake` is false (`bounce bake` prints its own line).
LoadResult bakeToCache(const BakeInput& input, const std::filesystem::path& probeCache, bool logBake = true);

// loadCached(cachePath(prepare(…))), else bakeToCache.
LoadResult loadOrBake(const scene::Level& level, const std::filesystem::path& cookCache,
                      const std::filesystem::path& probeCache, const ProbeSettings& settings);

}  // namespace bounce::gi::probes
