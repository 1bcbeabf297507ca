// bounce reference (LEVEL|SCRIPT) --out FILE.pfm: the path-traced ground truth of one frame
// (engine/ref), linear radiance as PFM, cached under <build>/reference by content hash.
#include <charconv>
#include <cstdio>

#include <tbb/task_arena.h>

#include "engine/core/error.hpp"
#include "engine/core/paths.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/ref/reference.hpp"
#include "game/commands.hpp"
#include "game/display_tonemap.hpp"
#include "game/session.hpp"
#include "game/viewer_level.hpp"

namespace bounce::game {
namespace {

// --frame and --bounces accept 0, which Args::positiveInt does not.
std::optional<std::uint32_t> nonNegative(const cli::Args& args, const std::string& option) {
  if (!args.has(option)) return std::nullopt;
  const std::string v = args.str(option);
  std::uint32_t n = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
  if (v.empty() || ec != std::errc() || end != v.data() + v.size())
    throwInputError("bounce reference", option, "'" + v + "' is not a valid count", "a non-negative integer");
  return n;
}

}  // namespace

int runReference(const cli::Args& args) {
  if (!args.has("--out")) throwInputError("bounce reference", "--out", "missing", "an output file FILE.pfm");
  ref::ReferenceRequest r;
  r.input = levelPathFor(args.positional[0]);  // a glTF file: its viewer level
  r.frame = nonNegative(args, "--frame").value_or(0);
  if (args.has("--spp")) r.spp = static_cast<std::uint32_t>(args.positiveInt("--spp", 1));
  r.bounces = nonNegative(args, "--bounces");
  if (auto res = args.resolution("--resolution")) r.resolution = std::pair{std::uint32_t(res->first), std::uint32_t(res->second)};
  r.effects = args.list("--effects");
  r.cacheDir = cacheDir("reference");
  r.cookCache = cookCacheDir();

  const ref::ReferenceResult res = ref::renderReference(r);
  const std::filesystem::path out = args.str("--out");
  gpu::writePfm(out, res.image);
  // A preview beside it, tonemapped as the renderer's display is (exposure 1).
  std::filesystem::path preview = out;
  preview.replace_extension(".png");
  if (preview != out)
    gpu::writePng(preview, res.image.width, res.image.height, 4, tonemapToSrgb8(res.image));
  const std::string bounces = r.bounces ? std::to_string(*r.bounces) : "unlimited";
  std::printf("reference %s frame %u (t = %.4f s): %ux%u, %u spp, bounces %s\n", r.input.filename().c_str(), r.frame,
              res.timeSeconds, res.image.width, res.image.height, r.spp.value_or(ref::kDefaultSpp), bounces.c_str());
  if (res.fromCache) {
    std::printf("served from the cache: %s\n", res.cachePath.c_str());
  } else {
    std::printf("traced %zu triangles in %.2f s: %.2f M rays, %.2f M rays/s (TBB threads: %d)\n", res.triangles,
                res.stats.seconds, res.stats.rays * 1e-6, res.stats.raysPerSecond() * 1e-6,
                tbb::this_task_arena::max_concurrency());
    std::printf("cached: %s\n", res.cachePath.c_str());
  }
  std::printf("wrote %s%s\n", out.c_str(), preview != out ? (" and the preview " + preview.string()).c_str() : "");
  return 0;
}

}  // namespace bounce::game
