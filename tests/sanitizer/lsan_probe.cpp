// LeakSanitizer probe for tests/sanitizer/CMakeLists.txt: draws one full-screen triangle on the
// Vulkan device (the work after which lavapipe leaves blocks behind that look leaked once the loader
// has unloaded it), tears everything down, and with --leak then leaks one 4242-byte block of ours.
//   lsan_probe           must exit 0: the driver's leftovers are covered (cmake/Bounce.cmake);
//   lsan_probe --leak    must be reported ("Direct leak of 4242 byte(s)"): ours are not hidden.
#include <cstdio>
#include <cstring>

#include "engine/gpu/commands.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "tests/unit/gpu/draw_helpers.hpp"

namespace {

// Not inlined, so the leak's stack names a function of ours (the report shows it).
[[gnu::noinline]] void leakOnPurpose() {
  char* volatile block = new char[4242];
  block[0] = 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bounce::gpu;
  const bool leak = argc > 1 && std::strcmp(argv[1], "--leak") == 0;
  {
    Context ctx;
    Image target(ctx, {ImageType::Tex2D, VK_FORMAT_R8G8B8A8_UNORM, 64, 64, 1, 1, 1, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                       VK_SAMPLE_COUNT_1_BIT, "lsan target"});
    testkit::SolidPipeline solid(ctx, VK_FORMAT_R8G8B8A8_UNORM);
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
      testkit::beginColor(ctx, cmd, target, testkit::Color{0, 0, 0, 0});
      solid.draw(cmd, {1, 1, 1, 1});
      ctx.cmdEndRendering(cmd);
    });
    if (ctx.validationErrorCount() != 0) {
      std::fprintf(stderr, "lsan_probe: %llu validation errors\n",
                   static_cast<unsigned long long>(ctx.validationErrorCount()));
      return 1;
    }
  }
  if (leak) leakOnPurpose();
  std::printf("lsan_probe: drew one triangle%s\n", leak ? ", leaked 4242 bytes of ours" : "");
  return 0;
}
