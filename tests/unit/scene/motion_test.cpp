// Motion evaluation against closed forms, transform hierarchy, active camera.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine/core/error.hpp"
#include "engine/scene/motion.hpp"
#include "engine/scene/systems.hpp"
#include "engine/scene/transform_math.hpp"

using namespace bounce;
using namespace bounce::scene;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
// Angles reach ~2π in float and pass through sin/cos/acos: a few ulps of 2π (~5e-7 each).
constexpr float kTol = 2e-6f;

void expectVecNear(const glm::vec3& a, const glm::vec3& b) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], kTol) << "component " << i;
}
// Same rotation: q and -q are equal, so compare |dot| with 1.
void expectSameRotation(const glm::quat& a, const glm::quat& b) { EXPECT_NEAR(std::abs(glm::dot(a, b)), 1.0f, kTol); }

Keyframes twoKeys(PlayMode mode, glm::vec3 from, glm::vec3 to, float t1 = 2.0f) {
  Keyframes k;
  k.times = {0.0f, t1};
  k.translation = {from, to};
  k.mode = mode;
  return k;
}

}  // namespace

TEST(TransformMath, ToMatrixIsTranslateRotateScale) {
  Transform t{glm::vec3(1, 2, 3), axisAngle({0, 0, 1}, kPi / 2), glm::vec3(2, 3, 4)};
  const glm::mat4 m = toMatrix(t);
  // x axis: scaled by 2, rotated 90° about Z to +Y.
  expectVecNear(glm::vec3(m * glm::vec4(1, 0, 0, 0)), {0, 2, 0});
  expectVecNear(glm::vec3(m * glm::vec4(0, 1, 0, 0)), {-3, 0, 0});
  expectVecNear(glm::vec3(m * glm::vec4(0, 0, 1, 0)), {0, 0, 4});
  EXPECT_EQ(m[3], glm::vec4(1, 2, 3, 1));
  EXPECT_EQ(toMatrix(Transform{}), glm::mat4(1.0f));
}

TEST(TransformMath, EulerAppliesXThenYThenZ) {
  const glm::quat q = quatFromEulerDeg({90, 90, 0});
  // +Y --X 90°--> +Z --Y 90°--> +X.
  expectVecNear(q * glm::vec3(0, 1, 0), {1, 0, 0});
}

TEST(Motion, OrbitAtQuarterPeriod) {
  Motion m;
  m.base.translation = {1, 2, 3};
  m.orbit = Orbit{std::nullopt, {0, 1, 0}, 2.0f, 4.0f, 0.0f};  // centre = base translation
  expectVecNear(evaluateMotion(m, 0.0).translation, {3, 2, 3});   // +X at θ = 0
  expectVecNear(evaluateMotion(m, 1.0).translation, {1, 2, 1});   // −Z at a quarter turn
  expectVecNear(evaluateMotion(m, 2.0).translation, {-1, 2, 3});  // −X at half
  m.orbit->phase = 0.25f;
  expectVecNear(evaluateMotion(m, 0.0).translation, {1, 2, 1});  // phase is a fraction of a turn
  m.orbit->center = glm::vec3(0);
  m.orbit->axis = {1, 0, 0};  // closer to X than Z: reference +Z; a quarter turn about X takes +Z to −Y
  expectVecNear(evaluateMotion(m, 0.0).translation, {0, -2, 0});
}

TEST(Motion, SlerpMidpointOfZeroToNinetyAboutYIs45) {
  Motion m;
  Keyframes k;
  k.times = {0.0f, 1.0f};
  k.rotation = {glm::quat(1, 0, 0, 0), axisAngle({0, 1, 0}, kPi / 2)};
  m.keyframes = k;
  const glm::quat mid = evaluateMotion(m, 0.5).rotation;
  expectSameRotation(mid, axisAngle({0, 1, 0}, kPi / 4));
  EXPECT_NEAR(rotationAngle(mid), kPi / 4, kTol);
  EXPECT_NEAR(mid.y, std::sin(kPi / 8), kTol);
}

TEST(Motion, QuaternionSignFlipTakesShortArc) {
  Motion m;
  Keyframes k;
  k.times = {0.0f, 1.0f};
  // -q90 is the same 90° rotation; naive slerp would go the long way (through 225°).
  k.rotation = {glm::quat(1, 0, 0, 0), -axisAngle({0, 1, 0}, kPi / 2)};
  m.keyframes = k;
  const glm::quat mid = evaluateMotion(m, 0.5).rotation;
  EXPECT_NEAR(rotationAngle(mid), kPi / 4, kTol);
  expectSameRotation(mid, axisAngle({0, 1, 0}, kPi / 4));
}

TEST(Motion, LoopWrapsPingPongReversesOnceHolds) {
  Motion m;
  m.keyframes = twoKeys(PlayMode::Loop, {0, 0, 0}, {2, 0, 0});
  EXPECT_NEAR(evaluateMotion(m, 0.5).translation.x, 0.5f, kTol);
  EXPECT_NEAR(evaluateMotion(m, 2.5).translation.x, 0.5f, kTol);  // wrapped
  m.keyframes = twoKeys(PlayMode::PingPong, {0, 0, 0}, {2, 0, 0});
  EXPECT_NEAR(evaluateMotion(m, 1.5).translation.x, 1.5f, kTol);
  EXPECT_NEAR(evaluateMotion(m, 2.5).translation.x, 1.5f, kTol);  // on the way back
  EXPECT_NEAR(evaluateMotion(m, 3.0).translation.x, 1.0f, kTol);
  EXPECT_NEAR(evaluateMotion(m, 4.0).translation.x, 0.0f, kTol);  // back at the start
  EXPECT_NEAR(evaluateMotion(m, 4.5).translation.x, 0.5f, kTol);  // and forward again
  m.keyframes = twoKeys(PlayMode::Once, {0, 0, 0}, {2, 0, 0});
  EXPECT_EQ(evaluateMotion(m, 10.0).translation, glm::vec3(2, 0, 0));  // holds the last key
  EXPECT_EQ(evaluateMotion(m, -1.0).translation, glm::vec3(0, 0, 0));
}

TEST(Motion, KeyframesPickTheRightSegment) {
  Motion m;
  Keyframes k;
  k.times = {1.0f, 2.0f, 4.0f};
  k.scale = {glm::vec3(1), glm::vec3(3), glm::vec3(1)};
  k.mode = PlayMode::Once;
  m.keyframes = k;
  m.base.translation = {5, 6, 7};
  const Transform at3 = evaluateMotion(m, 3.0);
  EXPECT_EQ(at3.scale, glm::vec3(2));
  EXPECT_EQ(at3.translation, glm::vec3(5, 6, 7));  // tracks not given keep the base
}

TEST(Motion, SpinAndBobClosedForms) {
  Motion m;
  m.base.rotation = axisAngle({1, 0, 0}, kPi / 2);
  m.spin = Spin{{0, 1, 0}, 4.0f, 0.0f};
  m.bob = Bob{{0, 1, 0}, 0.5f, 4.0f, 0.0f};
  const Transform x = evaluateMotion(m, 1.0);  // spin a quarter turn, bob at its crest
  expectSameRotation(x.rotation, axisAngle({0, 1, 0}, kPi / 2) * m.base.rotation);
  expectVecNear(x.translation, {0, 0.5f, 0});
  expectVecNear(evaluateMotion(m, 2.0).translation, {0, 0, 0});   // bob back through zero
  expectVecNear(evaluateMotion(m, 3.0).translation, {0, -0.5f, 0});  // and at its trough
}

TEST(Motion, IsAPureFunctionOfTime) {
  ecs::Registry r;
  const ecs::Entity e = r.create();
  Motion m;
  m.base.translation = {1, 0, 0};
  m.orbit = Orbit{std::nullopt, {0, 1, 0}, 1.0f, 3.0f, 0.1f};
  m.spin = Spin{glm::normalize(glm::vec3(1, 1, 0)), 1.7f, 0.0f};
  m.bob = Bob{{0, 1, 0}, 0.2f, 0.9f, 0.3f};
  r.emplace<Motion>(e, m);
  r.emplace<Transform>(e);
  const double dt = 1.0 / 60.0;
  for (int frame = 0; frame <= 600; ++frame) motionSystem(r, frame * dt);
  EXPECT_EQ(r.get<Transform>(e), evaluateMotion(m, 600 * dt));  // bit-identical
  motionSystem(r, 0.0);
  EXPECT_EQ(r.get<Transform>(e), evaluateMotion(m, 0.0));
}

TEST(Hierarchy, ChildOfRotatedScaledParentGetsProduct) {
  ecs::Registry r;
  const ecs::Entity child = r.create();  // created before its parent on purpose
  const ecs::Entity parent = r.create();
  const Transform pt{glm::vec3(1, 2, 3), axisAngle({0, 0, 1}, kPi / 2), glm::vec3(2)};
  const Transform ct{glm::vec3(1, 0, 0), axisAngle({1, 0, 0}, kPi / 2), glm::vec3(1, 1, 3)};
  r.emplace<Transform>(child, ct);
  r.emplace<Parent>(child, parent);
  r.emplace<Transform>(parent, pt);
  transformSystem(r);
  EXPECT_EQ(r.get<WorldTransform>(child).matrix, toMatrix(pt) * toMatrix(ct));
  EXPECT_EQ(r.get<WorldTransform>(parent).matrix, toMatrix(pt));
  // Closed form: child origin = (1,2,3) + Rz90·(2·(1,0,0)) = (1, 4, 3).
  expectVecNear(glm::vec3(r.get<WorldTransform>(child).matrix[3]), {1, 4, 3});
}

TEST(Hierarchy, OrderDoesNotDependOnCreationOrder) {
  // A 3-deep chain created leaf-first and root-first gives identical matrices.
  const Transform ts[3] = {{glm::vec3(1, 0, 0), axisAngle({0, 1, 0}, 0.3f), glm::vec3(2)},
                           {glm::vec3(0, 1, 0), axisAngle({1, 0, 0}, 0.7f), glm::vec3(1, 2, 1)},
                           {glm::vec3(0, 0, 1), axisAngle({0, 0, 1}, 1.1f), glm::vec3(0.5f)}};
  glm::mat4 results[2];
  for (int variant = 0; variant < 2; ++variant) {
    ecs::Registry r;
    ecs::Entity es[3];
    for (int i = 0; i < 3; ++i) es[variant == 0 ? i : 2 - i] = r.create();
    for (int i = 0; i < 3; ++i) {
      r.emplace<Transform>(es[i], ts[i]);
      if (i > 0) r.emplace<Parent>(es[i], es[i - 1]);
    }
    transformSystem(r);
    results[variant] = r.get<WorldTransform>(es[2]).matrix;
  }
  EXPECT_EQ(results[0], results[1]);
  EXPECT_EQ(results[0], toMatrix(ts[0]) * toMatrix(ts[1]) * toMatrix(ts[2]));
}

TEST(Hierarchy, DeadParentOrCycleThrows) {
  ecs::Registry r;
  const ecs::Entity a = r.create(), b = r.create();
  r.emplace<Transform>(a);
  r.emplace<Parent>(a, b);
  r.destroy(b);
  EXPECT_THROW(transformSystem(r), InternalError);
  const ecs::Entity c = r.create();
  r.emplace<Transform>(c);
  r.emplace<Parent>(c, a);
  r.replace<Parent>(a, c);
  EXPECT_THROW(transformSystem(r), InternalError);
}

TEST(Hierarchy, DeepChainDoesNotRecurse) {
  ecs::Registry r;
  ecs::Entity prev = ecs::Entity::null();
  constexpr int kDepth = 200000;  // far beyond what a recursive walk's stack would survive
  for (int i = 0; i < kDepth; ++i) {
    const ecs::Entity e = r.create();
    r.emplace<Transform>(e, Transform{glm::vec3(1, 0, 0)});
    if (!prev.isNull()) r.emplace<Parent>(e, prev);
    prev = e;
  }
  transformSystem(r);
  EXPECT_EQ(r.get<WorldTransform>(prev).matrix[3], glm::vec4(float(kDepth), 0, 0, 1));
}

TEST(ActiveCamera, TaggedThenLowestIndex) {
  ecs::Registry r;
  EXPECT_EQ(activeCamera(r), ecs::Entity::null());
  const ecs::Entity a = r.create(), b = r.create();
  r.emplace<Camera>(b);
  r.emplace<Camera>(a);
  EXPECT_EQ(activeCamera(r), a);
  r.emplace<ActiveCamera>(b);
  EXPECT_EQ(activeCamera(r), b);
}
