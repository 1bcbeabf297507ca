#pragma once
// `bounce reference`: a path-traced reference image of one frame of a level or capture script,
// cached by content hash.
//
//   ReferenceRequest r;  r.input = "content/levels/cornell-1.json";  r.frame = 30;
//   r.cacheDir = "build/release/reference";  r.cookCache = "build/release/cooked";
//   ReferenceResult res = renderReference(r);   // res.image, res.cachePath, res.fromCache
//
// The cache key hashes everything the image depends on: the level file's bytes, every asset's
// content key (asset::cacheKey: source bytes, referenced files, cook options), the simulation
// time, the camera as posed at that time (world matrix, yfov, near, far), the resolution, spp,
// bounces and kTracerVersion (assets by content key, never by path). The level's `effects` are not part of it: the reference always
// computes full light transport with exact visibility, whatever the renderer would simulate.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/image_io.hpp"
#include "engine/ref/tracer.hpp"

namespace bounce::ref {

// Time step for `--frame N` on a level (capture scripts give their own dt): the 60 Hz step that
// `bounce play --frames` and `bounce profile` simulate with.
inline constexpr double kLevelFrameDt = 1.0 / 60.0;
inline constexpr std::uint32_t kDefaultResolution = 256;  // per side, for a level
inline constexpr std::uint32_t kDefaultSpp = 64;

struct ReferenceRequest {
  std::filesystem::path input;  // a level (.json with "bounce_level") or a capture script ("bounce_capture")
  std::uint32_t frame = 0;      // simulation time = frame · dt
  std::optional<std::uint32_t> spp;
  std::optional<std::uint32_t> bounces;  // empty: unlimited (kUnlimitedBounces with Russian roulette)
  std::optional<std::pair<std::uint32_t, std::uint32_t>> resolution;  // empty: the script's, else 256×256
  std::optional<std::vector<std::string>> effects;  // validated against the level; see header comment
  std::filesystem::path cacheDir;   // <build>/reference
  std::filesystem::path cookCache;  // <build>/cooked
  bool progress = true;             // draw a progress bar while tracing
};

struct ReferenceResult {
  gpu::FloatImage image;
  std::string key;                  // 16 hex digits
  std::filesystem::path cachePath;  // cacheDir/<key>.pfm
  bool fromCache = false;
  TraceStats stats;                 // zero when fromCache
  std::size_t triangles = 0;
  double timeSeconds = 0.0;         // simulation time of the frame
};

// The key and cache entry a request names, without tracing: steps 1-3 of renderReference (the
// input validated, the scene posed, assets cooked through the cache). What a bake job plans
// (`bounce bake LEVEL --only reference`, game/bake_jobs.hpp).
struct ReferencePlan {
  std::string key;
  std::filesystem::path cachePath;
  std::uint32_t width = 0, height = 0;
};
ReferencePlan planReference(const ReferenceRequest& request);

// The cached image in `file` when it is a readable PFM of width × height; nullopt (with a warning
// when the file exists but is corrupt or of another size: it must be traced again) otherwise.
std::optional<gpu::FloatImage> loadCachedReference(const std::filesystem::path& file, std::uint32_t width,
                                                   std::uint32_t height);

// Loads and validates the input (InputError on bad input: an unknown file kind, a frame at or
// beyond a capture script's `frames`, a bad level), poses the scene at frame·dt, and returns the
// cached image for its key or traces and caches it.
ReferenceResult renderReference(const ReferenceRequest& request);

}  // namespace bounce::ref
