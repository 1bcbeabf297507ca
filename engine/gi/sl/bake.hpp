#pragma once
// SL precompute for one mesh (paper §4), CPU, deterministic, parallel over spheres, with a progress
// bar.
//
// 1. Sphere set (§4.1): engine/gi/sl/sphere_fit.hpp (Lloyd clusters of surface points with Eq. 2,
//    then every triangle subdivided until each piece lies in a sphere). Why not a greedy
//    medial-axis cover: it needs a robust medial axis of arbitrary (often non-manifold) game meshes;
//    surface clustering only needs the triangles and uses Eq. 2, the same segmentation §4.2 samples
//    with. Reported: coverage error (fraction of an independent set of 2·surfaceSamples surface
//    points outside every sphere) and volume overshoot ((V(∪) − V(mesh))/V(mesh); V(∪) by Monte
//    Carlo on a jittered grid, V(mesh) by the divergence theorem, meaningful for closed meshes).
// 2. Surface samples (§4.2): rays from each centre along `directions` Fibonacci directions (the
//    paper: geodesic-sphere vertices, 92 of them; a Fibonacci lattice is as even and takes any
//    count); the farthest back-face hit in the sphere's Eq. 2 segment, else (no back-face hit at all:
//    centre outside) the first front-face hit in the segment along −ω, else none (that direction
//    emits nothing: the intersecting spheres' baked occlusion, §6.2).
// 3. Eq. 10's basis sums: N = samplesPerAxis² stratified directions, each given to its nearest ω_j
//    (the Voronoi cell); cells of directions without a sample are dropped. Stored pre-multiplied by
//    4π/N.
// 4. Albedo SH (§4.2): the paper renders the segment into a cube map from the centre; we cast the
//    same N directions with the same rules and project the hit albedo (material × texture).
// 5. Covered vertices: each vertex goes to the sphere nearest by Eq. 2; with a skin, that sphere's
//    joints are its vertices' joints of weight > 0 (§7.1 moves it with their average transform).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include "engine/gi/sl/sphere_set.hpp"
#include "engine/ref/scene_bvh.hpp"

namespace bounce::gi::sl {

// Optional skin of `object`: per mesh, per vertex (same lengths as RefMesh::positions), or empty.
struct Skin {
  std::vector<std::vector<glm::u16vec4>> joints;
  std::vector<std::vector<glm::vec4>> weights;
};

// `object`: ONE mesh's triangles in its local frame (every RefMesh of it), with materials and
// textures for the albedo. Throws InternalError when it has no triangles.
SphereSet bake(const ref::SceneDesc& object, const BakeSettings& settings, const Skin& skin = {});

// The `count` sample directions ω_j (Fibonacci lattice), in the order SurfaceSample::direction indexes.
std::vector<glm::vec3> sampleDirections(int count);

}  // namespace bounce::gi::sl
