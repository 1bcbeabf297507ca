#pragma once
// Small RTF bakes for the tests: a faceted unit-radius sphere (DNRT's test mesh) at tiny settings.
#include "engine/gi/rtf/bake.hpp"
#include "tests/unit/dnrt/test_meshes.hpp"

namespace bounce::gi::rtf::testing {

inline FieldSettings smallSettings() {
  FieldSettings s;
  s.proxies = 2;
  s.spheres = 4;
  s.faceSize = 2;
  s.innerRadius = 0.5f;
  s.outerRadius = 4.0f;
  s.raysPerAxis = 12;
  s.vertexRaysPerAxis = 6;
  s.selfBounces = 1;
  s.clusters = 4;
  s.components = 4;
  return s;
}

inline ref::SceneDesc unitSphere(glm::vec3 rho, int rings = 12) {
  return dnrt::testing::sphere(glm::vec3(0.0f), 1.0f, rho, rings);
}

}  // namespace bounce::gi::rtf::testing
