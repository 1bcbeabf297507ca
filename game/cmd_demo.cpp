// bounce demo: the README's first command. With a display it plays the default level in a window;
// headless it runs the default level's capture script into build/demo and prints the per-pass
// GPU cost table.
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstdlib>

#include "engine/core/paths.hpp"
#include "game/capture_run.hpp"
#include "game/commands.hpp"

namespace bounce::game {

namespace {
// The combined level: Fox and CesiumMan (skinned, animated, CesiumMan subdivided) with cornell-5's
// five DNRT props, in the Cornell room scaled ×6 to character size.
const char* kDefaultLevel = "levels/demo.json";
const char* kDefaultCapture = "captures/demo.json";

bool displayAvailable() {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) return false;
  if (!glfwInit()) return false;
  glfwTerminate();
  return true;
}
}  // namespace

int runDemo(const cli::Args& args) {
  const std::filesystem::path content = contentDir();
  if (displayAvailable()) {
    const std::string level = (content / kDefaultLevel).string();
    const char* argv[] = {level.c_str()};
    cli::Args play = cli::parse(commandSpecs()[0], 1, argv, 0);
    if (args.has("--device")) play.values["--device"] = args.str("--device");
    return runPlay(play);
  }
  const std::filesystem::path out =
      args.has("--out") ? std::filesystem::path(args.str("--out")) : defaultOutputRoot() / "demo";
  std::printf("no display: capturing %s into %s\n", (content / kDefaultCapture).c_str(), out.c_str());
  CaptureOverrides o;
  o.device = args.str("--device");
  CaptureResult r = runCaptureScript(content / kDefaultCapture, out, o);
  for (const auto& f : r.frames) std::printf("  %s\n  %s\n", f.png.c_str(), f.pfm.c_str());
  std::printf("per-pass GPU cost (all frames of the capture):\n%s", formatTable(r.passes).c_str());
  return 0;
}

}  // namespace bounce::game
