#pragma once
// CookedAsset: everything the engine keeps from a glTF 2.0 file, as plain data (no pointers,
// no glTF types). Produced by cook() (engine/asset/cook.hpp), written to and read from the
// versioned binary format (engine/asset/cooked_format.hpp).
//
// Index conventions: every cross reference is an index into a vector of this CookedAsset, -1 for
// "none". validate() (below) checks them all; cook() and readCooked() call it before returning,
// so a CookedAsset a caller holds is always internally consistent.
//
// Units and frames as glTF: metres, right-handed, +Y up, radians, linear colour factors.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace bounce::asset {

struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  bool operator==(const Bounds&) const = default;
};

// Per-vertex offsets added with a weight (glTF morph target). Empty vectors = attribute absent.
struct MorphTarget {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  bool operator==(const MorphTarget&) const = default;
};

// A refined primitive that follows a deformed cage (a skinned or morphed mesh with subdivision):
// its vertices are evaluated every frame from the posed vertices of cage primitive
// `cagePrimitive` of Mesh::cage, as OpenSubdiv limit stencils (Far::LimitStencilTable's layout,
// composed at cook time with the uniform refinement, engine/asset/subdivision.cpp). For vertex v
// and k in [offsets[v], offsets[v+1]), with P the posed cage positions:
//   position  S(v)     = Σ_k weights[k]   · P[indices[k]]
//   tangents  ∂S/∂u(v) = Σ_k duWeights[k] · P[indices[k]],   ∂S/∂v likewise with dvWeights
//   normal    normalize(∂S/∂u × ∂S/∂v), or normalize(Σ_k weights[k] · N[indices[k]]) (posed cage
//             normals) where the limit tangents are parallel (some boundary corners)
// Units: the weights are dimensionless (position weights sum to 1); P in the cage's frame.
struct LimitStencils {
  std::int32_t cagePrimitive = -1;      // -1: not a stencil primitive (every vector empty)
  std::vector<std::uint32_t> offsets;   // vertex count + 1, non-decreasing, offsets[0] = 0
  std::vector<std::uint32_t> indices;   // cage vertex of each weight
  std::vector<float> weights;           // position weights, one per index
  std::vector<float> duWeights;         // limit tangent ∂/∂u weights
  std::vector<float> dvWeights;         // limit tangent ∂/∂v weights
  bool present() const { return cagePrimitive >= 0; }
  bool operator==(const LimitStencils&) const = default;
};

// One indexed triangle list. positions/normals always present and of equal length; uv0, joints,
// weights, joints1, weights1 either empty or of the same length (joints1 only with joints); indices.size() % 3 == 0, every index < vertex count.
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // unit length; generated (area-weighted) when the file has none
  std::vector<glm::vec2> uv0;      // TEXCOORD_0
  std::vector<std::uint32_t> indices;
  std::vector<glm::u16vec4> joints;  // JOINTS_0, kept for skinning
  std::vector<glm::vec4> weights;    // WEIGHTS_0; with weights1 non-negative and summing to 1 (renormalised at cook)
  std::vector<glm::u16vec4> joints1;  // JOINTS_1: influences 5-8 (empty, or as many as joints)
  std::vector<glm::vec4> weights1;    // WEIGHTS_1
  std::vector<MorphTarget> targets;
  std::int32_t material = -1;  // index into CookedAsset::materials, -1 = default material
  // Triangles the cook removed as repairs (zero-area or non-finite; engine/asset/mesh_repair.cpp).
  // triangles kept + dropped = triangles in the source file.
  std::uint32_t droppedTriangles = 0;
  // Present on the primitives of a mesh with a cage (Mesh::cage): positions/normals above are then
  // the bind (rest) pose of the same evaluation, what a draw without a pose uses.
  LimitStencils stencils;
  bool operator==(const Primitive&) const = default;
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
  std::vector<float> morphWeights;  // default morph target weights
  Bounds bounds;                    // over every position of every primitive
  // A subdivided mesh of a deformed (skinned or morphed) mesh: the index of that control mesh
  // ("cage"), whose posed vertices every primitive's LimitStencils read each frame; -1 otherwise.
  // The cage has no cage of its own, and its bounds contain the rest-pose limit surface (limit
  // stencil weights are convex).
  std::int32_t cage = -1;
  bool operator==(const Mesh&) const = default;
};

enum class AlphaMode : std::uint32_t { Opaque = 0, Mask = 1, Blend = 2 };

struct TextureRef {
  std::int32_t texture = -1;  // index into CookedAsset::textures, -1 = none
  std::int32_t uvSet = 0;     // TEXCOORD_n the texture is sampled with (only uv0 is kept)
  bool operator==(const TextureRef&) const = default;
};

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};
  TextureRef baseColorTexture;
  glm::vec3 emissiveFactor{0.0f};
  TextureRef emissiveTexture;
  bool doubleSided = false;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool operator==(const Material&) const = default;
};

// A decoded glTF image, RGBA8 row-major from the top row. `pixels` is empty when the cook was
// asked not to decode images (CookOptions::decodeImages = false); width/height are still set.
struct Texture {
  std::string name;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  bool srgb = false;  // true when a material uses it as base colour or emissive colour
  std::vector<std::uint8_t> pixels;
  bool operator==(const Texture&) const = default;
};

enum class SubdivisionScheme : std::uint32_t { CatmullClark = 0, Loop = 1, Bilinear = 2 };

struct Subdivision {
  SubdivisionScheme scheme = SubdivisionScheme::CatmullClark;
  std::uint32_t levels = 0;  // 0 = not subdivided
  bool operator==(const Subdivision&) const = default;
};

// A node's extras.bounce_vlm (README "Virtual Light Meshes", VLM thesis §3.4–3.5): when the asset
// is referenced from a level entity, this node's mesh is a Virtual Light Mesh (one-sided diffuse
// virtual lights), never real geometry: the renderer, the reference and the exporter skip it and
// engine/gi/vlm collects it. The has* flags say which keys the file gave (an entity's `vlm`
// component overrides those, and fills in the others: engine/gi/vlm/vlm_mesh.hpp).
struct NodeVlm {
  bool present = false;
  std::uint32_t tag = 0;  // ≥ 1 when present (§3.4 id)
  bool hasColor = false;
  glm::vec3 color{1.0f};  // HDR hue (§3.5)
  bool hasIntensity = false;
  float intensity = 1.0f;  // scale (§3.5)
  bool hasReflectance = false;
  glm::vec3 reflectance{1.0f};  // in [0, 1]
  bool operator==(const NodeVlm&) const = default;
};

struct Node {
  std::string name;
  // Local transform: `matrix` when hasMatrix, else T * R * S (glTF order).
  bool hasMatrix = false;
  glm::mat4 matrix{1.0f};
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // glm order (w, x, y, z)
  glm::vec3 scale{1.0f};
  std::vector<std::int32_t> children;
  std::int32_t mesh = -1;
  std::int32_t camera = -1;
  std::int32_t light = -1;
  std::int32_t skin = -1;
  Subdivision subdivision;  // as requested (extras.subdivision or CookOptions); mesh is already refined
  NodeVlm vlm;              // extras.bounce_vlm; real-geometry consumers skip nodes with vlm.present
  bool operator==(const Node&) const = default;
};

enum class CameraType : std::uint32_t { Perspective = 0, Orthographic = 1 };

struct Camera {
  std::string name;
  CameraType type = CameraType::Perspective;
  float yfov = 0.8f;         // perspective, radians
  float aspectRatio = 0.0f;  // perspective, 0 = use the viewport's
  float xmag = 1.0f, ymag = 1.0f;  // orthographic half extents, metres
  float znear = 0.01f;
  float zfar = 0.0f;  // 0 = infinite (perspective only)
  bool operator==(const Camera&) const = default;
};

enum class LightType : std::uint32_t { Directional = 0, Point = 1, Spot = 2 };

// KHR_lights_punctual. Lights shine down their node's local -Z.
struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;  // candela (point/spot) or lux (directional), per the extension
  float range = 0.0f;      // metres, 0 = infinite
  float innerConeAngle = 0.0f;               // radians, spot only
  float outerConeAngle = 0.7853981634f;      // radians, spot only (glTF default pi/4)
  bool operator==(const Light&) const = default;
};

struct Skin {
  std::string name;
  std::vector<std::int32_t> joints;  // node indices
  std::vector<glm::mat4> inverseBindMatrices;  // one per joint (identity when the file has none)
  std::int32_t skeleton = -1;
  bool operator==(const Skin&) const = default;
};

enum class AnimationPath : std::uint32_t { Translation = 0, Rotation = 1, Scale = 2, Weights = 3 };
enum class Interpolation : std::uint32_t { Linear = 0, Step = 1, CubicSpline = 2 };

struct AnimationSampler {
  std::vector<float> input;   // key times, seconds
  std::vector<float> output;  // key values, `components` floats per value (x3 for cubic spline)
  std::uint32_t components = 0;
  Interpolation interpolation = Interpolation::Linear;
  bool operator==(const AnimationSampler&) const = default;
};

struct AnimationChannel {
  std::int32_t sampler = 0;
  std::int32_t node = -1;
  AnimationPath path = AnimationPath::Translation;
  bool operator==(const AnimationChannel&) const = default;
};

struct Animation {
  std::string name;
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;
  bool operator==(const Animation&) const = default;
};

struct CookedAsset {
  std::string sourceName;  // file name (no folders) the asset was cooked from, for messages
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Node> nodes;
  std::vector<Camera> cameras;
  std::vector<Light> lights;
  std::vector<Skin> skins;
  std::vector<Animation> animations;
  std::vector<std::int32_t> rootNodes;  // of the default scene
  bool operator==(const CookedAsset&) const = default;

  std::size_t triangleCount() const;         // kept, over all meshes and primitives
  std::size_t droppedTriangleCount() const;  // removed by repairs
};

// Checks every cross reference, vector length and index of `a`; throws InputError naming `file`
// and the first bad place ("meshes/2/primitives/0/indices") otherwise. Ends with
// validateSkinsAndAnimations().
void validate(const CookedAsset& a, const std::string& file);

// Joints per skin the GPU skinning pass accepts: one skin's joint matrices fit the smallest
// maxUniformBufferRange Vulkan guarantees (16 KiB = 256 × mat4), as Filament's 256 per renderable.
inline constexpr std::size_t kMaxSkinJoints = 256;
// |det| below this makes an inverse bind matrix "not invertible" (a joint scaled by 1e-8 per axis).
inline constexpr float kMinInverseBindDeterminant = 1e-24f;

// Skins and animations (engine/asset/skin_checks.cpp): joints in one tree and ≤ kMaxSkinJoints,
// finite invertible inverse bind matrices, influencing joint indices inside the skin, finite
// strictly increasing key times, finite outputs, value counts matching each channel's path
// (3, 4, or the mesh's morph target count), `weights` channels only on meshes with targets.
void validateSkinsAndAnimations(const CookedAsset& a, const std::string& file);

}  // namespace bounce::asset
