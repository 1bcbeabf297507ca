#pragma once
// Levels (README "Level format"). Two steps, so that nothing is ever half-loaded:
//   Level level = loadLevel(path);           // parse + validate everything; throws InputError
//   auto entities = instantiate(level, reg); // create entities; cannot fail on a loaded Level
//
// Every error is one line "file: /json/pointer: what is wrong (expected …)" (see
// json_reader.hpp). loadLevel() checks: JSON syntax (byte position), unknown keys, types,
// missing required keys, non-finite and out-of-range numbers, duplicate ids, unknown parent ids,
// parent cycles, unknown or repeated effect names, and that mesh assets exist (paths are relative
// to the level file).
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/ecs/registry.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/effects.hpp"

namespace bounce::scene {

// A Virtual Light Mesh (engine/gi/vlm, VLM thesis §3.1; level key "vlm", README "Level format"):
// every triangle of `mesh` is a one-sided diffuse virtual light (emitting on its counter-clockwise
// side). The entity is NOT drawn as real geometry and is not part of the path-traced reference: it
// only stands for light bounced by the real geometry tagged `tag` (§3.4). Emitted radiance per
// triangle: L = reflectance · E / π × color × intensity (§3.3, §3.5), E the irradiance from the real
// lights. Lives here (not components.hpp) while the VLM work owns only the level files.
// Keys not given (color, intensity, reflectance) come from the glTF node's extras.bounce_vlm when it
// has them (given keys override the extras), else the defaults: color [1,1,1], intensity 1,
// reflectance as engine/gi/vlm/vlm_mesh.hpp says.
struct Vlm {
  MeshRef mesh;                          // the virtual-light geometry (glTF)
  int tag = 0;                           // ≥ 1; real geometry with the same vlm_tag skips it
  std::optional<glm::vec3> color;        // HDR hue override (§3.5); default [1,1,1]
  std::optional<float> intensity;        // scale override (§3.5); default 1
  std::optional<glm::vec3> reflectance;  // default: see engine/gi/vlm/vlm_mesh.hpp
  std::optional<glm::vec3> albedoOverride;  // the entity's "material" albedo, when given
  friend bool operator==(const Vlm&, const Vlm&) = default;
};

// Real geometry's VLM id (§3.4): a pixel of this entity ignores virtual lights with the same tag.
struct VlmTag {
  int tag = 0;  // ≥ 1
  friend bool operator==(const VlmTag&, const VlmTag&) = default;
};

// One entity of the level file, as plain data (file order).
struct EntityDesc {
  std::string id;
  std::string pointer;                // "/entities/3": where it came from, for later messages
  std::optional<std::string> parent;  // id of another entity
  bool dynamic = false;               // "dynamic": true, or implied by motion
  Transform transform;                // identity when the key is absent
  std::optional<MeshRef> mesh;
  std::optional<MaterialOverride> material;
  std::optional<Camera> camera;
  std::optional<Light> light;
  std::optional<Motion> motion;  // base = transform
  std::optional<AnimationClip> animation;  // "animation" (needs a mesh); absent = the first clip
  std::optional<Dnrt> dnrt;      // needs a mesh and a dynamic entity
  std::optional<Sl> sl;          // needs a mesh and a dynamic entity
  std::optional<Rtf> rtf;        // needs a mesh and a dynamic entity
  std::optional<Vlm> vlm;        // needs a mesh (then not drawn); moves with a dynamic entity
  std::optional<VlmTag> vlmTag;  // on real geometry (not on a vlm entity)
};

// The level's "probes" object (used when effects name `probes`): the irradiance volume's probe
// spacing in metres, SH order (2: 4 coefficients, 3: 9) and rays per probe (a square whose root
// is a multiple of 8, checked by the probe baker).
struct ProbesConfig {
  float spacing = 0.1f;
  int order = 3;
  std::uint32_t rays = 256;
  // Relit each frame (engine/gi/probes/relight.hpp): the dynamic objects' shadows on the static
  // surfels reach the probes' light. Off by default.
  bool relight = false;
  // "sl_bounce" (needs relight and the `sl` effect to do anything): the relit surfels also take the
  // SLs' bounce (pass "sl.relight_bounce", relight_pass.hpp setSlBounce), so the room carries the
  // SL objects' bounce on to its 2nd+ bounces. Off by default (README "SL's bounce in relight's
  // transport, session 15").
  bool slBounce = false;
};

// The level's "dnrt" object (used when effects name `dnrt`; the per-entity fields are each entity's
// own "dnrt"): the resolution of the DNRT draw, as G-buffer pixels per shaded sample along each axis —
// 1 (full, default), 2 (half) or 4 (quarter); below full the draw shades a reduced target and
// "dnrt.upsample" spreads it over every pixel (engine/gi/dnrt/node.hpp).
struct DnrtConfig {
  std::uint32_t step = 1;
};

// The level's "rtf" object (used when effects name `rtf`; the per-entity fields are each entity's own
// "rtf"): the resolution of the RTF shading draws, as DnrtConfig's — 1 (full, default), 2 (half) or 4
// (quarter); below full the draws shade a reduced target and "rtf.upsample" spreads it over every pixel
// (engine/gi/rtf/node.hpp).
struct RtfConfig {
  std::uint32_t step = 1;
};

// The level's "vlm" object (used when effects name `vlm`): the acceleration grid (thesis ch. 4):
// cells per axis over the scene bounds, candidates per cell K and the active-hemisphere range.
// Per-tag artistic overrides (§3.5, thesis Fig. 5.5): every virtual light with tag `t` emits
//   L' = hueRotate(L, hueDeg) · color · intensity
// on top of its own colour and intensity; hueDeg rotates the hue about the grey axis (0 = none).
// `bounce play` changes them live (game/play_controls.hpp).
struct VlmOverride {
  float intensity = 1.0f;
  glm::vec3 color{1.0f};
  float hueDeg = 0.0f;
  friend bool operator==(const VlmOverride&, const VlmOverride&) = default;
};

struct VlmConfig {
  int grid = 16;
  int k = 32;
  float range = 2.5f;
  std::map<int, VlmOverride> overrides;  // "overrides": {"TAG": {...}}, by tag
  float conservativeThreshold = 0.0f;  // "conservative_threshold"; 0 = off (engine/gi/vlm/grid.hpp)
};

struct Level {
  std::string name;  // "name", or the file's stem
  EffectSet effects;
  glm::vec3 background{0.0f};
  ProbesConfig probes;
  DnrtConfig dnrt;
  RtfConfig rtf;
  VlmConfig vlm;
  std::vector<EntityDesc> entities;
  std::filesystem::path source;  // the level file, absolute
};

Level loadLevel(const std::filesystem::path& path);
// loadLevel on text already in memory (the level fuzz target, tests/fuzz): `path` names the file
// in messages and anchors the relative asset paths; it need not exist.
Level parseLevel(std::string_view text, const std::filesystem::path& path);

// Replaces level.effects by a comma-separated list (the CLI's --effects LIST). Errors read
// "<level file>: --effects: unknown effect "x" (expected one of: …)".
void overrideEffects(Level& level, std::string_view list);

// Creates the level's entities in file order and returns them in that order. Each gets Name,
// Transform and WorldTransform (computed, parents first); Parent, Dynamic, MeshRef,
// MaterialOverride, Camera, Light, Motion as described; the first camera also gets ActiveCamera
// unless the registry already has one. Throws InternalError (before creating anything) if the
// Level was not produced by loadLevel and breaks its invariants (duplicate/dangling ids).
std::vector<ecs::Entity> instantiate(const Level& level, ecs::Registry& registry);

}  // namespace bounce::scene
