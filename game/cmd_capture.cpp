// bounce capture SCRIPT --out DIR: simulate a capture script with its fixed time step and write
// each captured frame as PNG (tonemapped sRGB) and PFM (linear HDR radiance), plus timings.json.
#include <algorithm>
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/progress.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/scene/capture.hpp"
#include "game/capture_run.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"
#include "game/timing_stats.hpp"
#include "game/viewer_level.hpp"
#include "game/render_limits.hpp"

namespace bounce::game {

CaptureResult runCaptureScript(const std::filesystem::path& scriptPath, const std::filesystem::path& out,
                               const CaptureOverrides& overrides) {
  const scene::CaptureScript script = scene::loadCaptureScript(scriptPath);
  scene::Level level = loadLevelWithEffects(script.level, std::nullopt);
  if (script.effects) level.effects = *script.effects;
  if (overrides.effects) level = loadLevelWithEffects(script.level, overrides.effects);
  VkExtent2D extent{script.resolution.x, script.resolution.y};
  if (overrides.resolution) extent = {std::uint32_t(overrides.resolution->first), std::uint32_t(overrides.resolution->second)};

  gpu::Context ctx({overrides.device});
  checkRenderSize(ctx, extent, overrides.resolution ? "bounce capture" : script.source.string(),
                  overrides.resolution ? "--resolution" : "/resolution");
  Session session(ctx, std::move(level));
  if (script.camera) session.setCameraMotion(*script.camera);
  gpu::OffscreenPresenter presenter(ctx, extent);
  std::filesystem::create_directories(out);

  CaptureResult result;
  TimingCollector timings;
  Progress progress("capture " + scriptPath.filename().string(), script.frames);
  for (std::uint32_t f = 0; f < script.frames; ++f) {
    const bool capture = std::binary_search(script.capture.begin(), script.capture.end(), f);
    session.update(double(f) * script.dt);
    render::FrameSettings settings;
    settings.keepHdr = capture;
    if (capture) presenter.requestCapture();
    session.render(presenter, settings);
    timings.collect(session.renderer().frames(), 0);
    if (capture) {
      char name[32];
      std::snprintf(name, sizeof name, "frame-%04u", f);
      const auto& image = presenter.capture();
      gpu::writePng(out / (std::string(name) + ".png"), image.width, image.height, 4, image.rgba8());
      gpu::FloatImage hdr{extent.width, extent.height, session.renderer().readHdr()};
      gpu::writePfm(out / (std::string(name) + ".pfm"), hdr);
      result.frames.push_back({f, out / (std::string(name) + ".png"), out / (std::string(name) + ".pfm")});
      timings.collect(session.renderer().frames(), 0);
    }
    progress.advance();
  }
  session.renderer().frames().waitIdle();
  timings.collect(session.renderer().frames(), 0);
  progress.finish();
  result.passes = timings.stats();
  result.executedPasses = session.renderer().executedPasses();
  writeFileAtomic(out / "timings.json", formatJson(result.passes));
  return result;
}

int runCapture(const cli::Args& args) {
  if (!args.has("--out")) throwInputError("bounce capture", "--out", "missing", "an output folder");
  CaptureOverrides o;
  o.device = args.str("--device");
  o.effects = args.list("--effects");
  o.resolution = args.resolution("--resolution");
  auto result = runCaptureScript(captureScriptPathFor(args.positional[0]), args.str("--out"), o);
  for (const auto& f : result.frames) std::printf("frame %u: %s %s\n", f.index, f.png.c_str(), f.pfm.c_str());
  std::printf("%s", formatTable(result.passes).c_str());
  return 0;
}

}  // namespace bounce::game
