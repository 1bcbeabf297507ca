// The VLM node on the GPU (lavapipe on CPU-only machines). A flat white floor seen from straight
// above, a point light, and a cube-shaped Virtual Light Mesh (its 12 triangles emit outwards; the
// VLM itself is never drawn). Each test renders the level with and without the `vlm` effect: the
// difference is the node's term ρ/π · Σ_k π L_k F_k, compared with the CPU mirror
// (engine/gi/vlm/reference.hpp: phase 1 unshadowed — the level has no `shadows` effect — and
// brute-force phase 2 with the double form factor) at pixels whose world position comes from the
// camera ray meeting the floor plane y = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/vlm/reference.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

namespace bounce::gi::vlm {
namespace {

namespace fs = std::filesystem;

constexpr VkExtent2D kExtent{96, 96};
// fp16 HDR target (11-bit mantissa, 4.9e-4 relative) holds direct + VLM light; the difference of
// two such images carries that rounding of the larger (direct) value.
constexpr double kHalfRel = 2e-3;
// Float form factor on the GPU vs double on the CPU (form_factor_gpu_test: ≤ 1e-6 absolute in F)
// and D32 depth reconstruction of x (≈1e-6 m at 3 m) move the VLM term by ≪ 1e-4 relative; the
// absolute floor covers pixels where the term itself is ~0.
constexpr double kTermRel = 1e-3;
constexpr double kTermAbs = 2e-5;
const glm::dvec3 kFloorAlbedo(0.8, 0.8, 0.8);

fs::path outDir() {
  const fs::path d = fs::path(BOUNCE_TEST_OUT) / "vlm";
  fs::create_directories(d);
  return d;
}

std::string boxAsset() { return (fs::path(BOUNCE_SOURCE_DIR) / "content/src/Box/glTF-Binary/Box.glb").generic_string(); }

struct Scene {
  glm::vec3 cube{0.0f, 1.0f, 0.0f};  // VLM cube centre; 0.4 m wide
  int floorTag = 0;                  // 0: the floor has no vlm_tag
  bool moving = false;               // the VLM cube orbits (radius 0.6 m about `cube`, axis +Y, 8 s)
  glm::vec3 lamp{0.6f, 0.6f, 0.1f};  // point light, 2 W/sr
  float range = 100.0f;              // active-hemisphere range: 100 lists every light everywhere
};

fs::path writeLevel(const std::string& name, const Scene& s) {
  const fs::path path = outDir() / (name + ".json");
  std::ofstream f(path);
  // Appended piece by piece: GCC 12 at -O3 warns (-Wstringop-overflow, a false positive) on the "[" + … chain.
  auto v3 = [](glm::vec3 v) {
    std::string out = "[";
    for (int i = 0; i < 3; ++i) (out += std::to_string(v[i])) += i < 2 ? ", " : "]";
    return out;
  };
  f << R"({"bounce_level": 1, "effects": ["direct", "vlm"], "vlm": {"grid": 8, "k": 16, "range": )" << s.range
    << R"(}, "entities": [
    {"id": "floor", "transform": {"translation": [0, -0.01, 0], "scale": [4, 0.02, 4]},
     "mesh": {"asset": ")" << boxAsset() << R"("}, "material": {"albedo": [0.8, 0.8, 0.8]})"
    << (s.floorTag ? ", \"vlm_tag\": " + std::to_string(s.floorTag) : "") << R"(},
    {"id": "camera", "transform": {"translation": [0, 3, 0], "rotation_euler_deg": [-90, 0, 0]},
     "camera": {"yfov_deg": 60, "near": 0.1, "far": 10}},
    {"id": "lamp", "transform": {"translation": )" << v3(s.lamp) << R"(}, "light": {"type": "point", "intensity": 2}},
    {"id": "cube", "transform": {"translation": )" << v3(s.cube) << R"(, "scale": [0.4, 0.4, 0.4]},)"
    << (s.moving ? R"( "motion": {"orbit": {"center": )" + v3(s.cube) + R"(, "radius": 0.6, "period_s": 8}},)" : "")
    << R"( "mesh": {"asset": ")" << boxAsset() << R"("},
     "vlm": {"tag": 7, "reflectance": [0.9, 0.2, 0.1], "color": [1, 1, 1], "intensity": 3}}]})";
  return path;
}

struct Frame {
  std::vector<float> rgb;
  std::vector<std::string> passes;
  render::CameraGpu camera;
};

Frame render(const fs::path& level, const std::vector<std::string>& effects, double t = 0.0) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, game::loadLevelWithEffects(level, effects));
  session.update(t);
  gpu::OffscreenPresenter presenter(ctx, kExtent);
  render::FrameSettings settings;
  settings.keepHdr = true;
  session.render(presenter, settings);
  Frame f{session.renderer().readHdr(), session.renderer().executedPasses(), session.world().camera};
  session.renderer().frames().waitIdle();
  return f;
}

// World point of pixel (px, py) on the floor plane y = 0 (the camera looks straight down at it).
glm::dvec3 floorPoint(const render::CameraGpu& cam, int px, int py) {
  const glm::dvec2 ndc((px + 0.5) / kExtent.width * 2.0 - 1.0, (py + 0.5) / kExtent.height * 2.0 - 1.0);
  const glm::dmat4 inv(cam.invViewProj);
  auto at = [&](double z) {
    const glm::dvec4 w = inv * glm::dvec4(ndc, z, 1.0);
    return glm::dvec3(w) / w.w;
  };
  const glm::dvec3 a = at(0.0), b = at(1.0);
  return a + (b - a) * (a.y / (a.y - b.y));
}

glm::dvec3 pixel(const Frame& f, int px, int py) {
  const std::size_t i = (std::size_t(py) * kExtent.width + px) * 3;
  return {f.rgb[i], f.rgb[i + 1], f.rgb[i + 2]};
}

// The lamp of writeLevel as the renderer packs it (point, radiant intensity 2 W/sr, white).
std::vector<render::LightGpu> lamp() {
  render::LightGpu l{};
  l.positionType = glm::vec4(0.6f, 0.6f, 0.1f, float(render::LightType::Point));
  l.radiance = glm::vec4(2.0f, 2.0f, 2.0f, 0.0f);
  l.shadow = glm::vec4(-1.0f);
  return {l};
}

// The cube's virtual lights at time 0, and their phase-1 radiance, from the level itself.
void cpuLights(const fs::path& level, std::vector<VirtualLight>& lights, std::vector<glm::dvec3>& radiance) {
  ecs::Registry reg;
  scene::instantiate(scene::loadLevel(level), reg);
  for (const VlmMesh& m : collectVlms(reg, fs::path(BOUNCE_TEST_OUT) / "vlm" / "cooked"))
    appendPlaced(m, reg.get<scene::WorldTransform>(m.entity).matrix, lights);
  for (const auto& l : lights) radiance.push_back(emittedRadiance(l, lamp(), NodeSettings{}.shadowLift));
}

TEST(VlmGpu, NodeMatchesCpuSumOnTheFloor) {
  const fs::path level = writeLevel("match", {});
  const Frame with = render(level, {"direct", "vlm"}), without = render(level, {"direct"});
  std::vector<VirtualLight> lights;
  std::vector<glm::dvec3> radiance;
  cpuLights(level, lights, radiance);
  ASSERT_EQ(lights.size(), 12u);
  double peak = 0.0;
  int checked = 0;
  for (int py = 3; py < int(kExtent.height); py += 6)
    for (int px = 3; px < int(kExtent.width); px += 6) {
      const glm::dvec3 x = floorPoint(with.camera, px, py);
      const glm::dvec3 expected = kFloorAlbedo / std::numbers::pi * irradiance(x, {0, 1, 0}, lights, radiance, 0);
      const glm::dvec3 got = pixel(with, px, py) - pixel(without, px, py);
      for (int c = 0; c < 3; ++c) {
        const double tol = kHalfRel * pixel(with, px, py)[c] + kTermRel * expected[c] + kTermAbs;
        EXPECT_NEAR(got[c], expected[c], tol) << "pixel " << px << "," << py << " channel " << c;
      }
      peak = std::max(peak, expected.r);
      ++checked;
    }
  EXPECT_EQ(checked, 256);
  EXPECT_GT(peak, 100 * kTermAbs) << "the VLM must light the floor visibly for the comparison to mean anything";
}

// One-sided emission: a cube straddling the floor shows the receivers inside its footprint only
// the back of its faces, so they get exactly nothing; just outside the lit +X face they get light.
TEST(VlmGpu, ReceiversBehindTheLightsGetNothing) {
  const fs::path level = writeLevel("one-sided", {glm::vec3(0.0f)});
  const Frame with = render(level, {"direct", "vlm"}), without = render(level, {"direct"});
  int inside = 0, litOutside = 0;
  for (int py = 0; py < int(kExtent.height); ++py)
    for (int px = 0; px < int(kExtent.width); ++px) {
      const glm::dvec3 x = floorPoint(with.camera, px, py);
      const glm::dvec3 d = pixel(with, px, py) - pixel(without, px, py);
      if (std::abs(x.x) < 0.19 && std::abs(x.z) < 0.19) {
        ++inside;
        EXPECT_EQ(d, glm::dvec3(0.0)) << "pixel " << px << "," << py;
      } else if (x.x > 0.21 && x.x < 0.4 && std::abs(x.z) < 0.1 && d.r > 1e-3) {
        ++litOutside;
      }
    }
  EXPECT_GT(inside, 50);
  EXPECT_GT(litOutside, 10);
}

// Tag skipping (§3.4): the floor carrying the cube's tag receives nothing from it; with another
// tag it receives the full term.
TEST(VlmGpu, SameTagSkipsTheVirtualLights) {
  const Frame same = render(writeLevel("tag-same", {glm::vec3(0, 1, 0), 7}), {"direct", "vlm"});
  const Frame other = render(writeLevel("tag-other", {glm::vec3(0, 1, 0), 8}), {"direct", "vlm"});
  const Frame none = render(writeLevel("tag-same", {glm::vec3(0, 1, 0), 7}), {"direct"});
  double otherSum = 0.0;
  for (int py = 0; py < int(kExtent.height); ++py)
    for (int px = 0; px < int(kExtent.width); ++px) {
      EXPECT_EQ(pixel(same, px, py), pixel(none, px, py)) << "pixel " << px << "," << py;
      otherSum += (pixel(other, px, py) - pixel(none, px, py)).r;
    }
  EXPECT_GT(otherSum, 1.0);
}

// A VLM on a dynamic entity moves with it (issue 5 §5): the red bleed from the orbiting cube
// follows it. The lamp sits at the orbit centre, so the lit face is the one turned to the centre
// and the bleed lies between the centre and the cube: at t = 0 the cube is at +X, at t = 2 s (a
// quarter turn) at −Z.
TEST(VlmGpu, DynamicVlmBleedMovesWithItsEntity) {
  const fs::path level = writeLevel("moving", {glm::vec3(0.0f, 0.3f, 0.0f), 0, true, glm::vec3(0.0f, 0.3f, 0.0f)});
  const Frame base = render(level, {"direct"});
  const Frame t0 = render(level, {"direct", "vlm"}, 0.0), t2 = render(level, {"direct", "vlm"}, 2.0);
  // Brightest VLM term in each frame: under the cube, and red (reflectance 0.9, 0.2, 0.1).
  auto brightest = [&](const Frame& f) {
    glm::dvec3 best(-1.0), at(0.0);
    for (int py = 0; py < int(kExtent.height); ++py)
      for (int px = 0; px < int(kExtent.width); ++px) {
        const glm::dvec3 d = pixel(f, px, py) - pixel(base, px, py);
        if (d.r > best.r) {
          best = d;
          at = floorPoint(f.camera, px, py);
        }
      }
    EXPECT_GT(best.r, 4.0 * best.g) << "the bleed is red";
    return at;
  };
  // The peak lies on the centre–cube line (within a few pixels, 0.15 m), on the cube's side.
  constexpr double kAcross = 0.15, kAlong = 0.15;
  const glm::dvec3 p0 = brightest(t0), p2 = brightest(t2);
  EXPECT_GT(p0.x, kAlong);
  EXPECT_NEAR(p0.z, 0.0, kAcross);
  EXPECT_LT(p2.z, -kAlong);
  EXPECT_NEAR(p2.x, 0.0, kAcross);
}

// Phase 2 draws a dynamic VLM on its own, scissored to the pixels its lights can reach through the
// grid (issue 5 §7: a per-object row). With a short range (1.5: the grid lists the cube's lights
// near it only) that rectangle is a part of the image; the image must still equal the one where
// the same cube, at the same place, is static (drawn with the static grid over the whole image):
// the same lists, radiance and sums, so the same floats.
TEST(VlmGpu, DynamicVlmDrawEqualsTheSameVlmStatic) {
  const glm::vec3 centre(0.0f, 0.3f, 0.0f), atTimeZero = centre + glm::vec3(0.6f, 0.0f, 0.0f);  // the orbit starts at +X
  Scene moving{centre, 0, true, centre};
  moving.range = 1.5f;
  Scene still{atTimeZero, 0, false, centre};
  still.range = 1.5f;
  const Frame base = render(writeLevel("scissor-base", still), {"direct"});
  const Frame dyn = render(writeLevel("scissor-moving", moving), {"direct", "vlm"}, 0.0);
  const Frame fixed = render(writeLevel("scissor-still", still), {"direct", "vlm"}, 0.0);
  int lit = 0, unlit = 0;
  for (int py = 0; py < int(kExtent.height); ++py)
    for (int px = 0; px < int(kExtent.width); ++px) {
      const glm::dvec3 a = pixel(dyn, px, py), b = pixel(fixed, px, py);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(a[c], b[c]) << px << "," << py;
      (pixel(fixed, px, py).r > pixel(base, px, py).r ? lit : unlit)++;
    }
  EXPECT_GT(lit, 200) << "the cube lights the floor";
  EXPECT_GT(unlit, 1000) << "range 1.5 should leave much of the floor outside the lights' cells";
}

TEST(VlmScreenRect, BoxInFrontIsItsProjectionAndABoxAroundTheCameraIsTheWholeImage) {
  // Camera at the origin looking down −Z, 90° field of view, square 100 × 100 image.
  const glm::mat4 viewProj = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 100.0f);
  const VkRect2D r = screenRect(viewProj, glm::vec3(-1.0f, -1.0f, -4.0f), glm::vec3(1.0f, 1.0f, -2.0f), {100, 100});
  // The near face (z = −2) spans ndc ±0.5: pixels 25 … 75, rounded outwards (±1: tan 45° in float).
  EXPECT_NEAR(r.offset.x, 25, 1);
  EXPECT_NEAR(r.offset.y, 25, 1);
  EXPECT_NEAR(int(r.extent.width), 50, 2);
  EXPECT_NEAR(int(r.extent.height), 50, 2);
  const VkRect2D around = screenRect(viewProj, glm::vec3(-1.0f), glm::vec3(1.0f), {100, 100});
  EXPECT_EQ(around.offset.x, 0);
  EXPECT_EQ(around.extent.width, 100u);
  EXPECT_EQ(around.extent.height, 100u);
  const VkRect2D off = screenRect(viewProj, glm::vec3(10.0f, -1.0f, -4.0f), glm::vec3(12.0f, 1.0f, -2.0f), {100, 100});
  EXPECT_EQ(off.extent.width, 0u) << "a box right of the frustum covers no pixel";
  const VkRect2D empty = screenRect(viewProj, glm::vec3(1.0f), glm::vec3(-1.0f), {100, 100});
  EXPECT_EQ(empty.extent.width, 100u) << "an empty box (no emitting light) falls back to the whole image";
}

// The node exists only for the `vlm` effect: exact pass lists.
TEST(VlmGpu, PassesOnlyWithTheVlmEffect) {
  const fs::path level = writeLevel("passes", {});
  EXPECT_EQ(render(level, {"direct", "vlm"}).passes,
            (std::vector<std::string>{"gbuffer", "lighting", "vlm.lights", "vlm", "tonemap"}));
  EXPECT_EQ(render(level, {"direct"}).passes, (std::vector<std::string>{"gbuffer", "lighting", "tonemap"}));
}

}  // namespace
}  // namespace bounce::gi::vlm

namespace bounce::gi::vlm {
namespace {

// Capture of the shipped Cornell VLM level (content/levels/cornell-vlm.json): the node only adds
// light (every L_k, F_k, ρ ≥ 0), and the bleed takes the colour of the nearer wall's virtual light:
// red-dominated in the left third of the image (red wall); in the right third (near the green wall;
// the big red wall still reaches it) the green share is at least twice the left third's.
TEST(VlmGpu, CornellLevelBleedsWallColours) {
  const fs::path level = fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-vlm.json";
  const Frame with = render(level, {"direct", "shadows", "vlm"}), without = render(level, {"direct", "shadows"});
  glm::dvec3 left(0.0), right(0.0);
  for (int py = 0; py < int(kExtent.height); ++py)
    for (int px = 0; px < int(kExtent.width); ++px) {
      const glm::dvec3 d = pixel(with, px, py) - pixel(without, px, py);
      for (int c = 0; c < 3; ++c) EXPECT_GE(d[c], -kHalfRel * pixel(with, px, py)[c]) << px << "," << py;
      if (px < int(kExtent.width) / 3) left += d;
      if (px >= 2 * int(kExtent.width) / 3) right += d;
    }
  EXPECT_GT(left.r, 2.0 * left.g);
  EXPECT_GT(right.g / right.r, 2.0 * left.g / left.r) << "left " << left.r << "," << left.g << " right " << right.r
                                                       << "," << right.g;
}

}  // namespace
}  // namespace bounce::gi::vlm
