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

// The closed form the sphere tests check against (issue #4 §6): a sphere of radius R and albedo
// ρ_s under uniform radiance L; a receiver of albedo ρ_r facing the centre at distance d receives
// ρ_r ρ_s L (R/d)² reflected and loses ρ_r L (R/d)² (the sphere's cosine-weighted solid angle is
// π(R/d)²), so L_DNRT = ρ_r L (R/d)² (ρ_s − 1).
glm::vec3 sphereClosedForm(glm::vec3 rhoR, glm::vec3 L, double dOverR, glm::vec3 rhoS);

}  // namespace bounce::gi::dnrt::testing
