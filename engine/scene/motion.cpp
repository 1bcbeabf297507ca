#include "engine/scene/motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/scene/json_reader.hpp"
#include "engine/scene/transform_math.hpp"

namespace bounce::scene {

namespace {

constexpr std::size_t kMaxKeys = 1u << 20;  // bounds memory on hostile input; clips use tens

// 2π times the fractional part of t/period + phase. Reducing to one turn in double first keeps
// the float angle precise however long the simulation runs.
float turnAngle(double t, float periodS, float phase) {
  const double turns = t / double(periodS) + double(phase);
  return float(2.0 * std::numbers::pi * (turns - std::floor(turns)));
}

double positiveMod(double x, double m) {
  const double r = std::fmod(x, m);
  return r < 0.0 ? r + m : r;
}

template <class T, class Lerp>
T sampleTrack(const std::vector<float>& times, const std::vector<T>& values, double local, Lerp lerp) {
  const auto hi = std::upper_bound(times.begin(), times.end(), float(local));
  if (hi == times.begin()) return values.front();
  if (hi == times.end()) return values.back();
  const std::size_t i = std::size_t(hi - times.begin()) - 1;
  const float s = float((local - times[i]) / double(times[i + 1] - times[i]));
  return lerp(values[i], values[i + 1], std::clamp(s, 0.0f, 1.0f));
}

Keyframes parseKeyframes(const json::Node& node) {
  const auto obj = node.object({"times", "translation", "rotation", "scale", "mode"});
  Keyframes k;
  const auto times = obj.required("times", "an array of 2 or more strictly increasing times (s)")
                         .array(2, kMaxKeys, "2 or more strictly increasing times (s)");
  for (std::size_t i = 0; i < times.size(); ++i) {
    const float t = times[i].real();
    if (i > 0 && !(t > k.times.back()))
      times[i].fail("time " + json::formatNumber(t) + " is not after the previous " + json::formatNumber(k.times.back()),
                    "strictly increasing times");
    k.times.push_back(t);
  }
  const std::size_t n = k.times.size();
  const std::string perTime = std::to_string(n) + " values, one per time";
  if (auto tr = obj.optional("translation"))
    for (const auto& v : tr->array(n, n, perTime)) k.translation.push_back(v.vec3());
  if (auto rot = obj.optional("rotation"))
    for (const auto& v : rot->array(n, n, perTime)) k.rotation.push_back(parseQuaternion(v));
  if (auto sc = obj.optional("scale"))
    for (const auto& v : sc->array(n, n, perTime)) k.scale.push_back(parseScale(v));
  if (k.translation.empty() && k.rotation.empty() && k.scale.empty())
    node.fail("no tracks", "at least one of translation, rotation, scale");
  if (auto mode = obj.optional("mode")) {
    const std::string m = mode->string();
    if (m == "loop")
      k.mode = PlayMode::Loop;
    else if (m == "ping-pong")
      k.mode = PlayMode::PingPong;
    else if (m == "once")
      k.mode = PlayMode::Once;
    else
      mode->fail("unknown mode " + json::inQuotes(m), "one of: loop, ping-pong, once");
  }
  return k;
}

const json::Range kPeriod = json::Range::greaterThan(0);

}  // namespace

glm::quat parseQuaternion(const json::Node& node) {
  const auto c = node.array(4, 4, "a quaternion [x, y, z, w]");
  const double x = c[0].real(), y = c[1].real(), z = c[2].real(), w = c[3].real();
  const double len = std::sqrt(x * x + y * y + z * z + w * w);
  // Below this length normalising in float is meaningless; 0 is the documented error.
  constexpr double kMinLength = 1e-6;
  if (!(len >= kMinLength)) node.fail("zero-length quaternion", "a non-zero quaternion [x, y, z, w]");
  return glm::quat(float(w / len), float(x / len), float(y / len), float(z / len));
}

glm::vec3 parseScale(const json::Node& node) {
  const glm::vec3 s = node.vec3();
  for (int i = 0; i < 3; ++i)
    if (s[i] == 0.0f) node.element(std::size_t(i)).fail("scale 0", "a non-zero scale");
  return s;
}

Motion parseMotion(const json::Node& node) {
  const auto obj = node.object({"keyframes", "spin", "orbit", "bob"});
  Motion m;
  if (auto k = obj.optional("keyframes")) m.keyframes = parseKeyframes(*k);
  if (auto n = obj.optional("spin")) {
    const auto o = n->object({"axis", "period_s", "phase"});
    Spin s;
    s.axis = o.required("axis", "a non-zero [x, y, z]").direction();
    s.periodS = o.required("period_s", kPeriod.describe()).real(kPeriod);
    if (auto p = o.optional("phase")) s.phase = p->real();
    m.spin = s;
  }
  if (auto n = obj.optional("orbit")) {
    const auto o = n->object({"center", "axis", "radius", "period_s", "phase"});
    Orbit s;
    if (auto c = o.optional("center")) s.center = c->vec3();
    if (auto a = o.optional("axis")) s.axis = a->direction();
    s.radius = o.required("radius", "a number >= 0").real(json::Range::atLeast(0));
    s.periodS = o.required("period_s", kPeriod.describe()).real(kPeriod);
    if (auto p = o.optional("phase")) s.phase = p->real();
    m.orbit = s;
  }
  if (auto n = obj.optional("bob")) {
    const auto o = n->object({"axis", "amplitude", "period_s", "phase"});
    Bob s;
    if (auto a = o.optional("axis")) s.axis = a->direction();
    s.amplitude = o.required("amplitude", "a number (m)").real();
    s.periodS = o.required("period_s", kPeriod.describe()).real(kPeriod);
    if (auto p = o.optional("phase")) s.phase = p->real();
    m.bob = s;
  }
  return m;
}

double keyframeTime(const Keyframes& k, double t) {
  const double t0 = k.times.front(), t1 = k.times.back(), d = t1 - t0;
  switch (k.mode) {
    case PlayMode::Once: return std::clamp(t, t0, t1);
    case PlayMode::PingPong: {
      const double u = positiveMod(t - t0, 2.0 * d);
      return u <= d ? t0 + u : t0 + 2.0 * d - u;
    }
    case PlayMode::Loop:
    default: return t0 + positiveMod(t - t0, d);
  }
}

Transform evaluateMotion(const Motion& m, double t) {
  Transform x = m.base;
  if (m.keyframes) {
    const Keyframes& k = *m.keyframes;
    const double local = keyframeTime(k, t);
    auto mixVec = [](const glm::vec3& a, const glm::vec3& b, float s) { return a + (b - a) * s; };
    if (!k.translation.empty()) x.translation = sampleTrack(k.times, k.translation, local, mixVec);
    if (!k.rotation.empty()) x.rotation = sampleTrack(k.times, k.rotation, local, slerpShortest);
    if (!k.scale.empty()) x.scale = sampleTrack(k.times, k.scale, local, mixVec);
  }
  if (m.spin) x.rotation = glm::normalize(axisAngle(m.spin->axis, turnAngle(t, m.spin->periodS, m.spin->phase)) * x.rotation);
  if (m.orbit) {
    const Orbit& o = *m.orbit;
    const glm::vec3 a = o.axis;
    const glm::vec3 ref = std::abs(a.x) > std::abs(a.z) ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    const glm::vec3 u = glm::normalize(ref - a * glm::dot(ref, a));
    const glm::vec3 v = glm::cross(a, u);
    const float theta = turnAngle(t, o.periodS, o.phase);
    x.translation = o.center.value_or(x.translation) + o.radius * (std::cos(theta) * u + std::sin(theta) * v);
  }
  if (m.bob) x.translation += m.bob->axis * (m.bob->amplitude * std::sin(turnAngle(t, m.bob->periodS, m.bob->phase)));
  return x;
}

}  // namespace bounce::scene
