#pragma once
// A baked SL sphere set for ONE mesh, in the mesh's local frame (metres): the spheres (§4.1), each
// sphere's surface sample points with their precomputed SH basis sums (§4.2, Eq. 10), its surface
// albedo SH vector (§4.2, for Eq. 11), the vertices it covers (for skinned meshes: which joints
// move it, §7.1), and the blocking data (§6.2, §7.2): which spheres of the set intersect (ignored as
// each other's blockers, their occlusion is baked into the samples) and the set's bounding sphere
// (object sorting for per-object blocking, tile culling).
//
// File: versioned binary ("BSLSPSET", version 2: + per-sphere bounce and shadow scales), little-endian as the host writes it (as DNRT's
// field), validated on load: every count against its limit, every float finite, radii ≥ 0, sample
// directions < the direction count, no trailing bytes. A malformed file is an InputError naming it.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::gi::sl {

inline constexpr int kMinSpheres = 1;   // tests use 1; levels ask for 8..64 (issue 13)
inline constexpr int kMaxSpheres = 64;  // the intersection mask is one uint64
inline constexpr int kMaxDirections = 1024;

struct BakeSettings {
  int spheres = 16;           // sphere count, kMinSpheres..kMaxSpheres
  int order = 4;              // SH order of the basis sums and albedo: 3 or 4
  int directions = 92;        // sample directions per SL (paper §8.6: 92), ≤ kMaxDirections
  int samplesPerAxis = 64;    // Eq. 9–10's N = samplesPerAxis² projection directions
  int surfaceSamples = 4096;  // surface points the sphere fit clusters
  int iterations = 12;        // Lloyd iterations of the fit
};
// Throws InternalError when out of range.
void checkSettings(const BakeSettings& s);

struct SurfaceSample {
  glm::vec3 position{0.0f};   // local frame
  glm::vec3 normal{0.0f};     // unit, outward
  std::uint32_t direction = 0;  // index of ω_j in the set's direction list
  std::vector<float> basis;     // (4π/N) Y_j of Eq. 10, order² values: L_S = Σ_j L_pj · basis_j
};

struct SlSphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  std::uint64_t intersects = 0;         // bit j: sphere j of this set overlaps this one
  std::vector<std::uint32_t> vertices;  // covered vertices (index over the mesh's vertices, meshes in order)
  std::vector<std::uint16_t> joints;    // joints of those vertices with weight > 0, ascending
  std::vector<SurfaceSample> samples;
  std::vector<float> albedo;            // c_S (§4.2): RGB SH, order² × 3 floats, coefficient-major
  float bounceScale = 1.0f;             // the set's fitted bounce scale (bounce_scale.hpp), in (0, 1]
  float shadowScale = 1.0f;             // and its shadow's (sl.shadow's caps), in (0, 1]
};

struct SphereSet {
  BakeSettings settings;
  glm::vec3 boundCentre{0.0f};  // bounding sphere of all spheres (per-object blocking, culling)
  float boundRadius = 0.0f;
  float coverageError = 0.0f;   // fraction of surface points outside every sphere
  float volumeOvershoot = 0.0f; // (V(∪ spheres) − V(mesh)) / V(mesh)
  std::vector<SlSphere> spheres;
};

std::vector<std::uint8_t> serialize(const SphereSet& set);
SphereSet deserialize(std::span<const std::uint8_t> bytes, const std::string& fileName);
void save(const SphereSet& set, const std::filesystem::path& path);
SphereSet load(const std::filesystem::path& path);

}  // namespace bounce::gi::sl
