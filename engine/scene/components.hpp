#pragma once
// Scene components: plain structs, no behaviour. Units: metres, seconds, radians; linear
// radiance for colours. Right-handed, +Y up (glTF).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/ecs/entity.hpp"

namespace bounce::scene {

// The level's id of the entity (unique within a level).
struct Name {
  std::string id;
};

// Local transform, relative to the Parent (or the world). Applied as T * R * S.
struct Transform {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // glm order: w, x, y, z; unit length
  glm::vec3 scale{1.0f};
  friend bool operator==(const Transform&, const Transform&) = default;
};

struct Parent {
  ecs::Entity entity;
};

// Local-to-world matrix, written by transformSystem().
struct WorldTransform {
  glm::mat4 matrix{1.0f};
};

enum class SubdivisionScheme { CatmullClark, Loop, Bilinear };

struct Subdivision {
  SubdivisionScheme scheme = SubdivisionScheme::CatmullClark;
  int levels = 1;  // 1..4
  friend bool operator==(const Subdivision&, const Subdivision&) = default;
};

struct MeshRef {
  std::filesystem::path asset;  // absolute, lexically normalised; the file existed at load
  // A glTF node whose subtree is instanced: by name or by index. Empty: the default scene.
  std::optional<std::variant<std::string, std::uint32_t>> node;
  std::optional<Subdivision> subdivision;
  friend bool operator==(const MeshRef&, const MeshRef&) = default;
};

struct MaterialOverride {
  std::optional<glm::vec3> albedo;    // base colour factor, each channel in [0, 1]
  std::optional<glm::vec3> emissive;  // emissive factor, linear radiance >= 0
  friend bool operator==(const MaterialOverride&, const MaterialOverride&) = default;
};

// Perspective camera looking down its local -Z (glTF).
struct Camera {
  float yfovRad = 1.0471976f;  // 60 degrees
  float near = 0.05f;          // metres
  float far = 100.0f;          // metres
  friend bool operator==(const Camera&, const Camera&) = default;
};

// Tags the camera a frame renders from (instantiate() gives it to the level's first camera).
struct ActiveCamera {};

enum class LightType { Point, Spot, Directional };

// Punctual light pointing down its local -Z (glTF KHR_lights_punctual). Intensity is radiant
// intensity for point and spot lights (irradiance I·cosθ/d²) and irradiance for directional.
struct Light {
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  std::optional<float> range;      // metres; empty: unbounded
  float innerConeRad = 0.0f;       // spot only
  float outerConeRad = 0.7853982f; // spot only; 45 degrees (glTF default)
  bool shadows = true;
  // "radius": the light as a sphere of this radius (metres, ≥ 0; 0 = a point, the default). Only
  // the SL local lights (Sl::localLights, issue 13 §7.3) and the path-traced reference (its shadow
  // rays aim at the sphere) use it; the shadow maps treat every light as a point.
  float radius = 0.0f;
  friend bool operator==(const Light&, const Light&) = default;
};

enum class PlayMode { Loop, PingPong, Once };

// Keyframed TRS. Every non-empty track has one value per time.
struct Keyframes {
  std::vector<float> times;  // seconds, strictly increasing, >= 2 entries
  std::vector<glm::vec3> translation;
  std::vector<glm::quat> rotation;  // unit quaternions; interpolated along the shorter arc
  std::vector<glm::vec3> scale;
  PlayMode mode = PlayMode::Loop;
  friend bool operator==(const Keyframes&, const Keyframes&) = default;
};

// Rotation about `axis` (the parent's frame) through the entity's origin.
struct Spin {
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // unit
  float periodS = 1.0f;
  float phase = 0.0f;  // fraction of a turn
  friend bool operator==(const Spin&, const Spin&) = default;
};

// Translation replaced by a point on a circle about `center`, in the plane normal to `axis`.
struct Orbit {
  std::optional<glm::vec3> center;  // empty: the entity's (keyframed) translation
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // unit
  float radius = 0.0f;
  float periodS = 1.0f;
  float phase = 0.0f;
  friend bool operator==(const Orbit&, const Orbit&) = default;
};

// Offset amplitude·sin(2π(t/period + phase)) along `axis`.
struct Bob {
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // unit
  float amplitude = 0.0f;            // metres
  float periodS = 1.0f;
  float phase = 0.0f;
  friend bool operator==(const Bob&, const Bob&) = default;
};

// Scripted motion. Evaluated from `base` (the entity's transform when instantiated), never
// incrementally, so the pose is a pure function of time: see evaluateMotion().
struct Motion {
  std::optional<Keyframes> keyframes;
  std::optional<Spin> spin;
  std::optional<Orbit> orbit;
  std::optional<Bob> bob;
  Transform base;
  friend bool operator==(const Motion&, const Motion&) = default;
};

// Level key "animation" on a mesh entity (README "Level format"): which glTF clip of the asset
// plays and how. Composes with Motion: motion moves the entity, the clip moves the nodes inside
// the asset. Played on simulation time: clip time = phase + speed·t, then looped, reflected
// (ping-pong) or clamped (once) over [0, clip duration]. engine/anim/animator.hpp runs it.
struct AnimationClip {
  bool enabled = true;  // "animation": false holds the rest pose
  std::optional<std::variant<std::string, std::uint32_t>> clip;  // empty: the asset's first clip
  float speed = 1.0f;
  PlayMode mode = PlayMode::Loop;
  float phaseS = 0.0f;   // seconds of clip time at t = 0
  std::string file;      // the level file and
  std::string pointer;   // "/entities/N/animation": where an unknown clip is reported
  friend bool operator==(const AnimationClip&, const AnimationClip&) = default;
};

// The entity moves at run time; GI techniques treat it as a dynamic object.
struct Dynamic {};

// How a DNRT object is drawn (run time only, level key "mode"; gi::dnrt::Node): its outer cube
// ("box", the default: the cost follows the pixels the cube covers), the paper's full-screen pass
// per object ("fullscreen", §5.2.2, for comparison), or in the clustered draw ("clustered": one
// full-screen pass for all such objects in which each pixel reads the G-buffer once and visits only
// the objects whose outer cube covers its screen tile; issue 15). All three give the same image.
// Fused (issue 15): the object's term added by the probes pass (gi/dnrt/runtime.hpp Runtime::addFused).
enum class DnrtMode : std::uint8_t { Box, FullScreen, Clustered, Fused };

// A DNRT transfer field request (engine/gi/dnrt; level key "dnrt", README "Level format").
// Extents are half-sizes of cubes about the bounding-sphere centre, in units of its radius R.
struct Dnrt {
  int shCount = 4;            // 4 or 9
  int grid = 32;              // 16, 32 or 64 vertices per axis
  float innerExtent = 3.0f;   // field cube
  float outerExtent = 6.0f;   // fade-out cube, > innerExtent
  bool intrusion = false;     // §5.2.3 cube depth map from o (run-time visibility test)
  bool improvedAntiRadiance = false;  // App. B.2 instead of Eq. 12
  // false: the anti-radiance subtracts only the probes' light, not the lights' (their occlusion is
  // the shadow maps' and, relit, the probes'): gi/dnrt/runtime.hpp, Runtime's constructor.
  bool lightsInAntiRadiance = true;
  int samplesPerAxis = 16;    // bake rays per vertex = samplesPerAxis² ("rays", a square)
  DnrtMode mode = DnrtMode::Box;  // run time only ("mode"), the field is the same

  friend bool operator==(const Dnrt&, const Dnrt&) = default;
};

// A spherical-lights request (engine/gi/sl, issue 13; level key "sl", README "Level format"): the
// entity's mesh is approximated by `spheres` SLs baked with `order` SH bands, and pass 2 accumulates
// blockers per sphere or per object (paper §7.2).
struct Sl {
  int spheres = 16;        // 1..64 (gi::sl::kMaxSpheres; levels use 8..64)
  int order = 4;           // SH order of the basis sums, albedo and intensity: 3 or 4
  bool perObject = false;  // "blocking": "per-object" (true) or "per-sphere" (false, the default)
  // "influence": F of sl::evaluate's rule 0 — a receiver ignores SLs farther than F radii (fading
  // from F/2); 0 = every SL at every pixel. Run time only (pass 2), the bake is the same.
  float influence = 12.0f;
  // "resolution": "full" (1, the default), "half" (2) or "quarter" (4): pass 2 shades one pixel in
  // step × step and an edge-aware upsample fills the rest (engine/gi/resolution.hpp). Run time only.
  int step = 1;
  // "local_lights": the level's point and spot lights become SLs of their own radius (Light::radius)
  // in pass 2 (§7.3): this object's shadow on them is the SLs' SH-exponentiated visibility of the
  // light's sphere ("sl.local", engine/gi/sl/local_light.hpp) instead of the shadow map's (its draws
  // leave those lights' shadow layers). Run time only. Default false.
  bool localLights = false;
  // "hierarchy": §7.3's two levels (engine/gi/sl/hierarchy.hpp, sl/hierarchy.glsl): one parent SL per
  // object stands in for the share of its SLs that the influence cut removes, scaled per screen tile
  // by Eq. 25's reflection ratio. Run time only. Default false (README "SL hierarchy on the GPU").
  bool hierarchy = false;
  // "fused": with the probes running (so "sl.shadow" too) and the hierarchy off, "sl" and "sl.shadow"
  // are one pass that walks each tile's candidates once (shaders/sl/sl_shadow.frag). Run time only.
  // Default true; false keeps the two passes (README "SL: one walk for sl and sl.shadow").
  bool fused = true;
  // Which of pass 2's two terms the fused pass adds (a bit mask, kSlBounce | kSlShadow): not a level
  // key, only `bounce accuracy`'s decomposition rows ("terms=bounce|shadow|none", README "SL on the
  // characters: what the error is made of, session 11") clear a bit, so one render shows one term.
  // Needs the fused pass (probes on, hierarchy off, "fused" true).
  int terms = 3;
  // "blocked_light": "receiver" (false, the default) or "sphere" (true): where pass 2's shadow on the
  // probes' light reads the light the SLs block — the receiver's probe SH (Eq. 6), or each SL's own
  // (the probes' SH at its posed centre, in the receiver → SL direction; engine/gi/sl/probe_shadow.hpp
  // BlockedLight). Run time only. Not with "hierarchy".
  bool blockedAtSphere = false;
  // "blocked_read": "sh" or "map" (true): with "blocked_light": "sphere", how pass 2 reads the light an
  // SL blocks in the receiver → SL direction d_j — the probes' order-3 SH at the SL's posed centre, or
  // the probes' 16² direction maps blended there (probe_volume.hpp dirMap; README "SL's blocked light
  // read from the probes' direction maps, session 19"). Run time only. Default "sh".
  bool blockedMap = false;
  // Whether pass 2's tiles ("sl", "sl.shadow" and the two in one walk, without the hierarchy) cut
  // each tile's SL list by its receivers' world box (shaders/sl/tile_cut.glsl): not a level key,
  // only tests clear it to draw the uncut lists, which give the same image (SlSession.TileCut…).
  bool tileCut = true;
  friend bool operator==(const Sl&, const Sl&) = default;
};

// A radiance transfer field request (engine/gi/rtf, issue 14; level key "rtf", README "Level
// format"): the entity's mesh gets an RTF (Pan et al. 2007) baked at these settings, and its light
// bounces `bounces` times between the rtf objects each frame (§5, Algorithm 1). Defaults are small
// enough for a prop to bake in seconds on 2 cores; the paper's resolution is 16 proxies, 16
// spheres, face 16, 64 rays, 32 clusters × 16 components (`bounce bench rtf` defaults to it).
struct Rtf {
  int proxies = 8;           // m, k-means centres (§3.2; paper 8–24)
  int bounces = 2;           // inter-object bounces in the bouncing step, 1..4
  int spheres = 8;           // concentric spheres of samples (paper 16)
  int face = 8;              // n_r: 6·n_r² samples per sphere (paper 16)
  int rays = 8;              // ITF/OOF projection: 6·rays² directions per sample (paper 64)
  int vertexRays = 8;        // Eq. 8 vertex transfer: vertexRays² rays per vertex
  int clusters = 8;          // CPCA n_c (paper 32)
  int components = 4;        // CPCA n_e (paper 16)
  // CPCA storage: the last byteComponents of the components kept as 8-bit codes with a scale per
  // basis row and per sample (gi::rtf::quantize), 0..components; the rest fp16. 8 × 112 with 88 here
  // is what meets issue 14's ≥ 50:1 at ≤ 1 % on every cornell-5 prop (README "CPCA: the tail in 8 bits").
  int byteComponents = 0;
  float inner = 0.5f;        // innermost sphere, units of the bounding radius η (paper 0.1)
  float outer = 4.0f;        // outermost sphere, units of η (paper 8); the field fades out one spacing beyond
  // Run time: the SH coefficients a receiver's irradiance takes from the field, 9 (bands 0–2 of the
  // clamped cosine: all it has, Â_3 = 0) or 4 (bands 0–1, as DNRT's "sh": 4; 3 fetches, not 7).
  int sh = 9;
  // Run time: where the field ends. 0: it fades to zero one sphere spacing beyond the outermost
  // sphere. τ > 0: beyond it the field goes on as (r_N/|q|)² — the solid angle of the object — until
  // the object covers less than τ·π sr seen from q (τ bounds the share of a facing receiver's
  // irradiance it can block or add; from the field's OOF at r_N, gi::rtf::tailReach), then fades
  // over one spacing. Costs shading pixels only (no more samples).
  float tail = 0.0f;
  friend bool operator==(const Rtf&, const Rtf&) = default;
};

}  // namespace bounce::scene
