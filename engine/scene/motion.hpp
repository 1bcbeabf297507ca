#pragma once
// Motion scripts (README "Motion scripts"): parsing from JSON and evaluation at a time.
//
// evaluateMotion() is a pure function of (motion, time): it starts from motion.base every
// time, never from last frame's pose, so a fixed time step gives bit-identical frames however
// many frames were skipped or repeated. Parts compose in this order:
//   1. keyframes (or the static base TRS): each present track replaces that part of the base;
//   2. spin: rotation' = R(spin.axis, 2π(t/period + phase)) · rotation (axis in the parent frame);
//   3. orbit: translation' = center + radius·(cos θ·u + sin θ·(axis × u)), θ = 2π(t/period + phase),
//      center defaulting to the translation from step 1. u is the reference direction: +X
//      projected onto the orbit plane, or +Z when the axis is closer to X than to Z (|a.x| > |a.z|).
//      With axis +Y this is a counter-clockwise turn seen from above: +X at θ=0, −Z at θ=π/2;
//   4. bob: translation' += axis · amplitude · sin(2π(t/period + phase)).
#include "engine/scene/components.hpp"

namespace bounce::scene {

// Only declared here (as effects.hpp does): json_reader.hpp is for the .cpp files that parse, not
// for every TU that reaches this header through game/session.hpp (CI time).
namespace json {
class Node;
}

// Parses a `motion` object at `node` (base is left default; instantiate() fills it).
Motion parseMotion(const json::Node& node);

// A unit quaternion from [x, y, z, w] (normalised; zero length is an error).
glm::quat parseQuaternion(const json::Node& node);
// A scale [x, y, z] with every component non-zero (negative mirrors).
glm::vec3 parseScale(const json::Node& node);

// The keyframe-time a clip time maps to, per mode: loop wraps, ping-pong reflects, once clamps.
double keyframeTime(const Keyframes& k, double timeSeconds);

Transform evaluateMotion(const Motion& motion, double timeSeconds);

}  // namespace bounce::scene
