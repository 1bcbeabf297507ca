#pragma once
// SL bake, step 1 (paper §4.1): a bounding sphere set of a mesh with little outside volume (Eq. 1).
//
// The paper uses variational sphere sets (Wang et al. 2006: Lloyd clustering that minimises the
// outside volume). Ours keeps the same shape in three steps, each cheap and deterministic:
//  1. cluster (`cluster`): Lloyd iterations on area-uniform surface points with the paper's own
//     distance d(p, S) = |p − x|/r (Eq. 2), each cluster's sphere its points' (near-)minimal
//     enclosing sphere, the iterate of least Σ r³ kept;
//  2. cover the surface (`coverTriangles`): the points are a sample, the surface is not. Every
//     triangle is subdivided (midpoints, 4 children) until each piece lies in one sphere (a sphere
//     holding a triangle's corners holds the triangle), and only pieces shorter than `minEdge` that
//     no sphere holds grow their nearest sphere (Eq. 2) by Ritter's step. Before session 6 the whole
//     triangle grew its sphere: a box's 12 triangles span whole faces and blew the 8 spheres up to
//     6.6× the box's volume (README Results "SL sphere fit").
// Tried and dropped: shrinking each sphere to the points no other sphere holds (Eq. 2's clusters
// barely overlap on the points: Fox 8 spheres 3.98 → 3.94, the box unchanged).
// Units: the mesh's local frame (metres of the asset), radii likewise.
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/sl/evaluate.hpp"

namespace bounce::gi::sl::fit {

// (Near-)minimal enclosing sphere: Ritter's bound, then Bădoiu–Clarkson steps; always encloses.
Sphere enclosing(const std::vector<glm::dvec3>& pts);

// Step 1: `k` spheres bounding `pts` (k ≤ pts.size()).
std::vector<Sphere> cluster(const std::vector<glm::dvec3>& pts, int k, int iterations);

// Step 2: triangles as corner triples (a[i], b[i], c[i]); afterwards every point of every triangle
// lies in some sphere (up to the 1e-7 relative slack of the growth).
void coverTriangles(std::vector<Sphere>& spheres, const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b,
                    const std::vector<glm::dvec3>& c, double minEdge);

// Eq. 2's nearest sphere (index).
std::size_t nearestSphere(const glm::dvec3& p, const std::vector<Sphere>& spheres);

}  // namespace bounce::gi::sl::fit
