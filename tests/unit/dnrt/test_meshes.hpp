#pragma once
// Small objects for DNRT tests, built by hand in their local frame (no glTF involved).
#include <glm/glm.hpp>

#include "engine/ref/scene_bvh.hpp"

namespace bounce::gi::dnrt::testing {

// A closed UV sphere (rings × 2·rings quads, outward CCW winding, exact normals) of radius r about
// c with one material of albedo rho.
ref::SceneDesc sphere(glm::vec3 c, float r, glm::vec3 rho, int rings = 48);

// The same sphere with two materials: rhoTop for z > c.z, rhoBottom below (no rotational symmetry
// about any axis but z, so rotation tests see every coefficient).
ref::SceneDesc twoToneSphere(glm::vec3 c, float r, glm::vec3 rhoTop, glm::vec3 rhoBottom, int rings = 32);

}  // namespace bounce::gi::dnrt::testing
