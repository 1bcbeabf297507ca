#pragma once
// The reference path tracer's scene: plain world-space data (SceneDesc) and its Embree 3 BVH
// (SceneBvh). SceneDesc is what the rasteriser draws, flattened: reference_scene.hpp builds it
// from a level exactly as GpuScene::extract expands entities; tests build it by hand (a closed
// cube, a plane under a lamp) with no glTF involved.
//
// Conventions match the rasteriser (shaders/passes/gbuffer.frag, shaders/common/lights.glsl):
// albedo = clamp(albedo factor × base colour texture, 0, 1); emission = emissive factor ×
// emissive texture (linear radiance); textures are sampled bilinearly with REPEAT wrap after
// sRGB → linear decoding of each texel (what an sRGB VkFormat does); shading normals are the
// barycentric interpolation of the transformed vertex normals, flipped towards the viewer.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/hash.hpp"

namespace bounce::ref {

// Linear RGB texels, rows top to bottom (glTF: uv (0,0) is the top-left corner of the image).
struct RefTexture {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<glm::vec3> texels;

  // Bilinear filter, REPEAT addressing, texel centres at (i + ½)/width — VK_FILTER_LINEAR on mip 0.
  glm::vec3 sample(glm::vec2 uv) const;
};

// RGBA8 pixels → linear texels; `srgb` decodes with the sRGB EOTF (IEC 61966-2-1). A pixel buffer
// of the wrong size gives a 1×1 white texture, as GpuScene does.
RefTexture makeTexture(std::uint32_t width, std::uint32_t height, const std::vector<std::uint8_t>& rgba8, bool srgb);

struct RefMaterial {
  glm::vec3 albedo{1.0f};    // base colour factor (linear), multiplied by the texture when present
  int albedoTexture = -1;    // index into SceneDesc::textures, -1 = none
  glm::vec3 emissive{0.0f};  // emitted radiance factor (linear)
  int emissiveTexture = -1;
};

// One mesh primitive instance, already in world space.
struct RefMesh {
  std::vector<glm::vec3> positions;  // metres, world space
  std::vector<glm::vec3> normals;    // world space (normal matrix applied), one per position
  std::vector<glm::vec2> uvs;        // empty, or one per position
  std::vector<std::uint32_t> indices;  // triangle list; every index < positions.size()
  std::uint32_t material = 0;          // index into SceneDesc::materials
};

enum class RefLightType { Directional, Point, Spot };

// A punctual light in the renderer's units (README "Level format"): point/spot `radiance` is
// colour × radiant intensity (irradiance I·cosθ/d²), directional is colour × irradiance.
struct RefLight {
  RefLightType type = RefLightType::Point;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit; the direction light travels (spot, directional)
  glm::vec3 radiance{1.0f};
  float range = 0.0f;     // metres, 0 = unbounded
  float cosOuter = 0.0f;  // spot cone: cos(outer angle), cos(inner angle)
  float cosInner = 1.0f;
  // scene::Light::radius (metres; point and spot): the light's sphere, whose visible fraction the
  // shadow rays estimate (tracer.cpp); 0 = a point.
  float radius = 0.0f;
};

// The active camera: `world` is its world matrix with unit axes (scale removed, as
// GpuScene::extract does); it looks down its local −Z.
struct RefCamera {
  glm::mat4 world{1.0f};
  float yfovRad = 1.0471976f;
  float near = 0.05f;
  float far = 100.0f;
};

struct SceneDesc {
  std::vector<RefMesh> meshes;
  std::vector<RefMaterial> materials;
  std::vector<RefTexture> textures;
  std::vector<RefLight> lights;
  RefCamera camera;
  glm::vec3 background{0.0f};  // radiance of every ray that leaves the scene (camera or bounce)
  // What the scene was made from, as a content key, when its maker knows one (empty: unknown).
  // gi::dnrt::objectScene sets it (the cooked asset's content key, node and material override),
  // so the field's cache key need not hash every vertex and texel (gi::dnrt::cacheKey).
  std::string sourceKey;
};

// Adds the scene's meshes, materials and textures (not lights, camera or sourceKey) to a bake's
// cache key, byte for byte: the one object hash of the DNRT, SL and RTF bakes.
void hashGeometry(Hasher& h, const SceneDesc& scene);

// Irradiance at p from one light on a surface facing it, before the cosine and visibility.
// lights.glsl incidentIrradiance() itself, compiled as C++ (scene_bvh.cpp): 1/d² with d² ≥ 1e-12,
// the glTF range window, and the spot cone falloff t², t the clamped linear ramp from cos(outer)
// to cos(inner). Writes the unit direction towards the light and the distance (1e30 for
// directional).
glm::vec3 incidentIrradiance(const RefLight& light, const glm::vec3& p, glm::vec3& toLight, float& dist);

struct Hit {
  float t = 0.0f;
  glm::vec3 position{0.0f};
  glm::vec3 geometricNormal{0.0f};  // unit, from the triangle's world corners
  glm::vec3 shadingNormal{0.0f};    // unit, interpolated vertex normals
  glm::vec2 uv{0.0f};
  std::uint32_t material = 0;
  // The triangle hit, for per-vertex data interpolated as the rasteriser does (gi::rtf's bake):
  // its mesh (index into SceneDesc::meshes), its corners RefMesh::indices[3·triangle + c], and
  // their barycentric weights (sum 1; position = Σ_c barycentric[c]·positions[corner c]).
  std::uint32_t mesh = 0;
  std::uint32_t triangle = 0;
  glm::vec3 barycentric{0.0f};
};

// Embree 3 BVH over every triangle of a SceneDesc (robust mode: closed meshes have no cracks).
// Thread-safe for concurrent queries once built. Keeps its own copy of the scene data.
class SceneBvh {
 public:
  explicit SceneBvh(SceneDesc scene);
  ~SceneBvh();
  SceneBvh(const SceneBvh&) = delete;
  SceneBvh& operator=(const SceneBvh&) = delete;

  // Closest hit along o + t·d, t in [tMin, tMax); false when nothing is hit.
  bool intersect(const glm::vec3& o, const glm::vec3& d, float tMin, float tMax, Hit& hit) const;
  // True when anything lies on o + t·d, t in [tMin, tMax).
  bool occluded(const glm::vec3& o, const glm::vec3& d, float tMin, float tMax) const;

  const SceneDesc& scene() const { return scene_; }
  std::size_t triangleCount() const { return triangles_; }

 private:
  struct Embree;
  SceneDesc scene_;
  std::unique_ptr<Embree> embree_;
  std::size_t triangles_ = 0;
};

}  // namespace bounce::ref
