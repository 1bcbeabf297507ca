// Debug views against closed forms. tests/data/render/plane-debug.json: a camera looking straight
// down from 1 m at a coloured floor (y = 0) and a smaller square occluder (y = 0.5) of another
// colour. For every pixel the test casts the pixel-centre ray through the level file's camera and
// finds what it hits (occluder or floor, pixels within kEdgeMargin of the occluder's outline are
// skipped), then predicts the display value of each view (debug_view.frag writes RGBA8 UNORM):
//   albedo     sRGB(ρ) of the surface hit,
//   normal     n·0.5 + 0.5 with n = +Y for both quads (seen from above),
//   depth      1 − (|p − eye| − dMin)/(dMax − dMin), dMin/dMax: nearest/farthest of the scene bounds,
//   entity id  the hash colour of the entity hit (index + 1, Knuth multiplicative hash),
//   shadow     on plane-shadow.json (the umbra scene of shadow_test.cpp): 0 in the umbra, 1 on
//              the lit floor, margins around the shadow edge skipped.
// The lighting chain is culled whenever a view is on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>

#include "engine/gpu/commands.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/scene/components.hpp"
#include "game/session.hpp"
#include "tests/unit/render/analytic.hpp"

using namespace bounce;
using namespace bounce::rtest;
using render::DebugView;

namespace {

constexpr std::uint32_t kWidth = 96, kHeight = 64;
// One 8-bit step: values are exact up to float rounding before the UNORM conversion rounds to
// nearest (½ step), and normal 0.5 lands exactly between two codes.
constexpr int kUnormStep = 1;
// Albedo passes through the RGBA8 UNORM G-buffer (±½ step in linear) and then sRGB encoding,
// whose slope is ≤ 1.7 for linear values ≥ 0.1 (the darkest channel here): ±0.85 step, plus the
// display's own ½ step of rounding: 2 steps.
constexpr int kAlbedoSteps = 2;
// Pixels whose ray meets the occluder plane within 1.5 pixel footprints of its outline are left
// out: the rasteriser decides them by coverage of the pixel centre, which float rounding of the
// projected edge may move by a fraction of a pixel.
constexpr float kEdgePixels = 1.5f;
// Shadow view: the same margin around the shadow edge as shadow_test.cpp (PCF reach + normal
// offset + edge rasterisation, 4 texels, rounded up to 6).
constexpr float kShadowMarginTexels = 6.0f;
constexpr std::uint32_t kShadowResolution = 1024;

struct Display {
  std::vector<std::uint8_t> rgba;
  std::vector<std::string> passes;
  glm::ivec3 at(std::uint32_t x, std::uint32_t y) const {
    const std::size_t i = (std::size_t(y) * kWidth + x) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2]};
  }
};

struct Quad {
  glm::vec3 centre;
  float halfSize;
  glm::vec3 albedo;
  std::uint32_t entityIndex;
};

// One frame of `level` with `view`, read back from the display image.
Display renderView(const std::filesystem::path& level, DebugView view, std::map<std::string, std::uint32_t>* indices) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, scene::loadLevel(level));
  session.update(0.0);
  gpu::OffscreenPresenter presenter(ctx, {kWidth, kHeight});
  render::FrameSettings settings;
  settings.debugView = view;
  session.render(presenter, settings);
  session.renderer().frames().waitIdle();
  Display d;
  d.rgba = gpu::readback(ctx, session.renderer().displayImage());
  d.passes = session.renderer().executedPasses();
  if (indices)
    session.registry().view<scene::Name>().each(
        [&](ecs::Entity e, scene::Name& n) { (*indices)[n.id] = e.index(); });
  return d;
}

Quad readQuad(const scene::Level& level, const std::string& id, const std::map<std::string, std::uint32_t>& indices) {
  for (const auto& e : level.entities)
    if (e.id == id)
      return {e.transform.translation, 0.5f * e.transform.scale.x, e.material.value().albedo.value(), indices.at(id)};
  ADD_FAILURE() << "no entity " << id;
  return {};
}

glm::vec3 pixelRay(const FloorScene& s, std::uint32_t x, std::uint32_t y) {
  const float t = std::tan(0.5f * s.yfovRad), aspect = float(kWidth) / float(kHeight);
  const float sx = ((float(x) + 0.5f) / float(kWidth) * 2.0f - 1.0f) * t * aspect;
  const float sy = (1.0f - (float(y) + 0.5f) / float(kHeight) * 2.0f) * t;
  return s.cameraRotation * glm::vec3(sx, sy, -1.0f);
}

// What the pixel-centre ray hits first: the occluder (1), the floor (0), or an edge pixel (−1).
int classifyHit(const FloorScene& s, const Quad& occ, std::uint32_t x, std::uint32_t y, glm::vec3& hit) {
  const glm::vec3 dir = pixelRay(s, x, y);
  const float along = (occ.centre.y - s.eye.y) / dir.y;
  const glm::vec3 q = s.eye + along * dir;
  const float footprint = 2.0f * std::tan(0.5f * s.yfovRad) * (s.eye.y - occ.centre.y) / float(kHeight);
  const float sd = std::max(std::abs(q.x - occ.centre.x), std::abs(q.z - occ.centre.z)) - occ.halfSize;
  if (std::abs(sd) < kEdgePixels * footprint) return -1;
  if (sd < 0.0f) {
    hit = q;
    return 1;
  }
  hit = floorPoint(s, kWidth, kHeight, x, y).value();
  return 0;
}

int toUnorm(float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

float srgb(float c) { return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }

glm::ivec3 idColor(std::uint32_t id) {
  const std::uint32_t h = id * 2654435761u;
  return {int(h & 255u), int((h >> 8) & 255u), int((h >> 16) & 255u)};
}

std::string show(glm::ivec3 v) {
  std::ostringstream s;
  s << "(" << v.x << "," << v.y << "," << v.z << ")";
  return s.str();
}

// Compares every classified pixel of plane-debug.json in `view` with `expect(surface, point)`.
void checkView(DebugView view, int tolerance, const std::function<glm::vec3(const Quad&, glm::vec3)>& expect,
               bool exact = false, const std::function<glm::ivec3(const Quad&)>& expectExact = {}) {
  const auto path = kDataDir / "plane-debug.json";
  const scene::Level level = scene::loadLevel(path);
  const FloorScene s = readFloorScene(level);
  std::map<std::string, std::uint32_t> indices;
  const Display d = renderView(path, view, &indices);
  EXPECT_EQ(d.passes, (std::vector<std::string>{"gbuffer", "debug-view"})) << "lighting and tonemap are culled";
  const Quad floor = readQuad(level, "floor", indices), occ = readQuad(level, "occluder", indices);
  int counts[2] = {0, 0}, bad = 0;
  std::string first;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      glm::vec3 p;
      const int hit = classifyHit(s, occ, x, y, p);
      if (hit < 0) continue;
      ++counts[hit];
      const Quad& q = hit ? occ : floor;
      glm::ivec3 want;
      if (exact) {
        want = expectExact(q);
      } else {
        const glm::vec3 v = expect(q, p);
        want = {toUnorm(v.x), toUnorm(v.y), toUnorm(v.z)};
      }
      const glm::ivec3 got = d.at(x, y);
      const bool ok = glm::all(glm::lessThanEqual(glm::abs(got - want), glm::ivec3(tolerance)));
      if (!ok && bad++ == 0) {
        std::ostringstream m;
        m << "pixel (" << x << "," << y << ") on the " << (hit ? "occluder" : "floor") << ": " << show(got)
          << ", expected " << show(want);
        first = m.str();
      }
    }
  // The occluder fills about a third of the view, the floor the rest.
  EXPECT_GT(counts[1], 1000);
  EXPECT_GT(counts[0], 2000);
  EXPECT_EQ(bad, 0) << bad << " pixels differ; first: " << first;
}

}  // namespace

TEST(DebugViews, AlbedoIsTheSrgbEncodedSurfaceColour) {
  checkView(DebugView::Albedo, kAlbedoSteps, [](const Quad& q, glm::vec3) {
    return glm::vec3(srgb(q.albedo.r), srgb(q.albedo.g), srgb(q.albedo.b));
  });
}

TEST(DebugViews, NormalIsPlusYMappedToHalfOneHalf) {
  // 0.5·255 = 127.5 lies between two codes: either rounds within one step.
  checkView(DebugView::Normal, kUnormStep, [](const Quad&, glm::vec3) { return glm::vec3(0.5f, 1.0f, 0.5f); });
}

TEST(DebugViews, DepthIsLinearOverTheSceneBounds) {
  // 1 at the nearest point of the scene bounds, 0 at their farthest corner (or the far plane):
  // render::depthViewRange, recomputed here from the two quads.
  const scene::Level level = scene::loadLevel(kDataDir / "plane-debug.json");
  const FloorScene s = readFloorScene(level);
  float far = 0.0f;
  for (const auto& e : level.entities)
    if (e.camera) far = e.camera->far;
  ASSERT_GT(far, 0.0f);
  std::map<std::string, std::uint32_t> ids{{"floor", 0}, {"occluder", 0}};
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const char* id : {"floor", "occluder"}) {
    const Quad q = readQuad(level, id, ids);
    lo = glm::min(lo, q.centre - glm::vec3(q.halfSize, 0.0f, q.halfSize));
    hi = glm::max(hi, q.centre + glm::vec3(q.halfSize, 0.0f, q.halfSize));
  }
  const float dMin = glm::length(glm::clamp(s.eye, lo, hi) - s.eye);
  float dMax = 0.0f;
  for (int i = 0; i < 8; ++i)
    dMax = std::max(dMax, glm::length(glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z) - s.eye));
  dMax = std::min(dMax, far);
  ASSERT_LT(dMin + 0.1f, dMax);
  checkView(DebugView::Depth, kUnormStep, [&](const Quad&, glm::vec3 p) {
    return glm::vec3(1.0f - (glm::length(p - s.eye) - dMin) / (dMax - dMin));
  });
}

TEST(DebugViews, EntityIdIsTheHashColourOfTheEntityHit) {
  checkView(DebugView::EntityId, 0, {}, true, [](const Quad& q) { return idColor(q.entityIndex + 1); });
  // Two entities, two different colours (the test would pass vacuously if they were equal).
  std::map<std::string, std::uint32_t> indices;
  renderView(kDataDir / "plane-debug.json", DebugView::EntityId, &indices);
  EXPECT_NE(idColor(indices.at("floor") + 1), idColor(indices.at("occluder") + 1));
}

TEST(DebugViews, ShadowIsZeroInTheUmbraAndOneOnTheLitFloor) {
  const auto path = kDataDir / "plane-shadow.json";
  const scene::Level level = scene::loadLevel(path);
  const FloorScene s = readFloorScene(level);
  std::map<std::string, std::uint32_t> indices;
  const Display d = renderView(path, DebugView::Shadow, &indices);
  EXPECT_EQ(d.passes, (std::vector<std::string>{"shadow", "gbuffer", "debug-view"}));
  const Quad occ = readQuad(level, "occluder", indices);
  // As shadow_test.cpp: the light→p ray's crossing of the occluder plane, in −Y cube-face texels.
  const float texel = 2.0f * (s.lightPosition.y - occ.centre.y) / float(kShadowResolution);
  int umbra = 0, lit = 0, bad = 0;
  std::string first;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const glm::vec3 p = floorPoint(s, kWidth, kHeight, x, y).value();
      const glm::vec3 L = s.lightPosition;
      const glm::vec3 q = L + (p - L) * ((L.y - occ.centre.y) / (L.y - p.y));
      const float sd = std::max(std::abs(q.x - occ.centre.x), std::abs(q.z - occ.centre.z)) - occ.halfSize;
      if (std::abs(sd) < kShadowMarginTexels * texel) continue;
      const int want = sd < 0.0f ? 0 : 255;
      (sd < 0.0f ? umbra : lit)++;
      const glm::ivec3 got = d.at(x, y);
      if (got != glm::ivec3(want) && bad++ == 0) first = "pixel (" + std::to_string(x) + "," + std::to_string(y) +
                                                        "): " + show(got) + ", expected " + std::to_string(want);
    }
  EXPECT_GT(umbra, 1000);
  EXPECT_GT(lit, 2000);
  EXPECT_EQ(bad, 0) << bad << " pixels differ; first: " << first;
}
