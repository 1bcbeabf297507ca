// bounce graph LEVEL --dot FILE: the render graph the level's first frame compiles to.
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"
#include "game/render_limits.hpp"

namespace bounce::game {

int runGraph(const cli::Args& args) {
  if (!args.has("--dot")) throwInputError("bounce graph", "--dot", "missing", "an output file");
  const auto res = args.resolution("--resolution").value_or(std::pair{1280, 720});
  scene::Level level = loadLevelWithEffects(args.positional[0], args.list("--effects"));
  gpu::Context ctx({args.str("--device")});
  checkRenderSize(ctx, {std::uint32_t(res.first), std::uint32_t(res.second)}, "bounce graph", "--resolution");
  Session session(ctx, level);
  session.update(0.0);
  const VkExtent2D extent{std::uint32_t(res.first), std::uint32_t(res.second)};
  session.extractOnly(extent);
  render::FrameSettings settings;
  settings.culling = !args.has("--no-cull");
  writeFileAtomic(args.str("--dot"), session.renderer().graphDot(session.world(), extent, settings));
  std::printf("wrote %s\n", args.str("--dot").c_str());
  return 0;
}

}  // namespace bounce::game
