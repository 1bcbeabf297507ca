// Per-tag VLM overrides on the GPU (level "vlm.overrides", thesis §3.5 / Fig. 5.5): an override
// doubling a tag's intensity doubles the VLM term in the image, pixel by pixel, and doubles the
// packed light values the runtime uploads; setOverrides() (the `bounce play` keys) takes effect on
// the next frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "engine/gi/vlm/make.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

namespace bounce::gi::vlm {
namespace {

namespace fs = std::filesystem;

constexpr VkExtent2D kExtent{64, 64};
// fp16 HDR target (4.9e-4 relative): the difference of two images carries that rounding of the
// larger (direct + VLM) value; the absolute floor covers pixels where the term itself is ~0.
constexpr double kHalfRel = 2e-3;
constexpr double kTermAbs = 2e-5;

fs::path writeLevel(const std::string& name, const std::string& overrides) {
  const fs::path dir = fs::path(BOUNCE_TEST_OUT) / "vlm";
  fs::create_directories(dir);
  const fs::path path = dir / (name + ".json");
  const std::string box = (fs::path(BOUNCE_SOURCE_DIR) / "content/src/Box/glTF-Binary/Box.glb").generic_string();
  std::ofstream(path) << R"({"bounce_level": 1, "effects": ["direct", "vlm"],
    "vlm": {"grid": 8, "k": 16, "range": 100, "overrides": )" << overrides << R"(}, "entities": [
    {"id": "floor", "transform": {"translation": [0, -0.01, 0], "scale": [4, 0.02, 4]},
     "mesh": {"asset": ")" << box << R"("}, "material": {"albedo": [0.8, 0.8, 0.8]}},
    {"id": "camera", "transform": {"translation": [0, 3, 0], "rotation_euler_deg": [-90, 0, 0]},
     "camera": {"yfov_deg": 60, "near": 0.1, "far": 10}},
    {"id": "lamp", "transform": {"translation": [0.6, 0.6, 0.1]}, "light": {"type": "point", "intensity": 2}},
    {"id": "cube", "transform": {"translation": [0, 1, 0], "scale": [0.4, 0.4, 0.4]},
     "mesh": {"asset": ")" << box << R"("}, "vlm": {"tag": 7, "reflectance": [0.9, 0.2, 0.1]}}]})";
  return path;
}

std::vector<float> render(game::Session& session) {
  gpu::OffscreenPresenter presenter(gpu::testkit::sharedContext(), kExtent);
  render::FrameSettings settings;
  settings.keepHdr = true;
  session.render(presenter, settings);
  auto rgb = session.renderer().readHdr();
  session.renderer().frames().waitIdle();
  return rgb;
}

TEST(VlmGpu, IntensityOverrideDoublesTheVlmTerm) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session plain(ctx, game::loadLevelWithEffects(writeLevel("override-none", "{}"), {}));
  game::Session doubled(ctx, game::loadLevelWithEffects(writeLevel("override-x2", R"({"7": {"intensity": 2}})"), {}));
  game::Session direct(ctx, game::loadLevelWithEffects(writeLevel("override-none", "{}"), std::vector<std::string>{"direct"}));
  for (game::Session* s : {&plain, &doubled, &direct}) s->update(0.0);
  const std::vector<float> a = render(plain), b = render(doubled), d = render(direct);

  // CPU side: the packed lights of the overridden level carry twice the scale.
  ASSERT_TRUE(plain.vlm() && doubled.vlm());
  const FrameData fa = plain.vlm()->prepare(plain.world()), fb = doubled.vlm()->prepare(doubled.world());
  ASSERT_EQ(fa.lights.size(), 12u);
  ASSERT_EQ(fb.lights.size(), 12u);
  for (std::size_t i = 0; i < fa.lights.size(); ++i) EXPECT_EQ(pack(fb.lights[i]).scale, 2.0f * pack(fa.lights[i]).scale) << i;

  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double termA = a[i] - d[i], termB = b[i] - d[i];
    EXPECT_NEAR(termB, 2.0 * termA, kHalfRel * b[i] + kTermAbs) << "value " << i;
    sum += termA;
  }
  EXPECT_GT(sum, 1.0) << "the VLM lights the floor visibly";

  // The live path (`bounce play` keys): clearing the overrides brings the plain image back.
  doubled.vlm()->setOverrides({});
  const std::vector<float> back = render(doubled);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(back[i], a[i], kHalfRel * a[i] + kTermAbs) << "value " << i;
}

// A plain `mesh` entity whose glTF node carries extras.bounce_vlm (here written by vlm-make's
// writer: a 0.4 m quad at y = 1 facing down onto the floor, tag 7) is a VLM: the VLM passes run
// and the floor receives light in the quad's colour.
TEST(VlmGpu, GltfExtrasNodeLightsTheFloor) {
  const fs::path dir = fs::path(BOUNCE_TEST_OUT) / "vlm";
  fs::create_directories(dir);
  MakeResult r;
  MadeMesh quad;
  quad.source = "quad";
  quad.tag = 7;
  quad.albedo = glm::vec3(0.9f, 0.2f, 0.1f);
  quad.positions = {{-0.2f, 1.0f, -0.2f}, {0.2f, 1.0f, -0.2f}, {-0.2f, 1.0f, 0.2f}, {0.2f, 1.0f, 0.2f}};
  quad.normals.assign(4, glm::vec3(0, -1, 0));
  quad.indices = {0, 1, 2, 1, 3, 2};  // counter-clockwise seen from below: emits towards −Y
  r.meshes.push_back(quad);
  writeVlmGltf(r, dir / "extras-quad.gltf");
  const fs::path level = dir / "extras.json";
  const std::string box = (fs::path(BOUNCE_SOURCE_DIR) / "content/src/Box/glTF-Binary/Box.glb").generic_string();
  std::ofstream(level) << R"({"bounce_level": 1, "effects": ["direct", "vlm"], "vlm": {"grid": 8, "k": 16, "range": 100},
    "entities": [
    {"id": "floor", "transform": {"translation": [0, -0.01, 0], "scale": [4, 0.02, 4]},
     "mesh": {"asset": ")" << box << R"("}, "material": {"albedo": [0.8, 0.8, 0.8]}},
    {"id": "camera", "transform": {"translation": [0, 3, 0], "rotation_euler_deg": [-90, 0, 0]},
     "camera": {"yfov_deg": 60, "near": 0.1, "far": 10}},
    {"id": "lamp", "transform": {"translation": [0, 0.5, 0]}, "light": {"type": "point", "intensity": 2}},
    {"id": "lights", "mesh": {"asset": "extras-quad.gltf"}}]})";
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session with(ctx, game::loadLevelWithEffects(level, {}));
  game::Session without(ctx, game::loadLevelWithEffects(level, std::vector<std::string>{"direct"}));
  ASSERT_TRUE(with.vlm());
  EXPECT_EQ(with.vlm()->lightCount(), 2u);
  EXPECT_EQ(with.vlm()->tags(), std::vector<std::uint32_t>{7});
  with.update(0.0);
  without.update(0.0);
  const std::vector<float> a = render(with), b = render(without);
  EXPECT_EQ(with.renderer().executedPasses(),
            (std::vector<std::string>{"gbuffer", "lighting", "vlm.lights", "vlm", "tonemap"}));
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_GE(a[i] - b[i], -kHalfRel * a[i]) << "the VLM only adds light";
    sum[i % 3] += a[i] - b[i];
  }
  EXPECT_GT(sum.r, 1.0) << "the quad (lit from below by the lamp) lights the floor";
  EXPECT_GT(sum.r, 4.0 * sum.g) << "in the quad's reflectance: red (no paired real geometry for tag 7)";
}

}  // namespace
}  // namespace bounce::gi::vlm
