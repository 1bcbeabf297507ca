#pragma once
// RTF's per-frame CPU work (the "update" of the one technique shape, Pan et al. 2007 §5): the
// bouncing step (Algorithm 1, evaluate.hpp bounce()) for every rtf object of the level, lit by the
// incident-light service (engine/gi/incident: the probes' or background's indirect light plus the
// frame's real lights with their visibility through the static geometry), and the per-object
// records the shading node draws with (node.hpp); with setOccluders, the lights' shadow rays at an
// object's proxies also meet the other posed objects (occluders.hpp). It runs in the node's setup because the lights
// are the frame's (RenderWorld::lights), as DNRT's objectsFor does.
//
// Departures (README "RTF"):
//  - one bounce count for the scene: the largest `bounces` of the participants (Algorithm 1 bounces
//    light between all objects at once, so a per-object count has no meaning);
//  - the shading step's blocked light (Eq. 10's occlusion of the incident light, the OOF) is the
//    INDIRECT light only (probes / background): the real lights' direct light is already removed
//    by the shadow maps, which draw every dynamic object. It is the light at the object's centre
//    (the record's product matrix: the radiance through the object is, in free space, the radiance
//    at o in those directions); shade() takes the whole light at the receiver, so the two agree
//    where the light is the same everywhere;
//  - the GPU pass adds each object's term on its own (additive blending); Algorithm 1 at a receiver
//    multiplies the objects' visibilities (V_{<i}). The two agree for one object (the GPU test);
//    where fields overlap, each object's term is scaled per field sample by sharedOcclusion's s
//    (overlap.hpp: half the directions two objects both hide taken off each), which the lookup
//    carries to the receiver (README RTF "Seventh pass"), and each object's interreflected light ξ by
//    w, the share of it the nearer objects let through (overlap.hpp; session 24), w_off for receivers off
//    the rtf objects and w_on for receivers on one (session 26).
#include <chrono>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/ecs/registry.hpp"
#include "engine/gi/incident/incident.hpp"
#include "engine/gi/rtf/evaluate.hpp"
#include "engine/gi/rtf/occluders.hpp"
#include "engine/gi/rtf/overlap.hpp"
#include "engine/render/gpu_types.hpp"

namespace bounce::gi::rtf {

// One object's shading record, std140 (shaders/rtf/object.glsl RtfObject), in a uniform buffer:
// rtf.vert reads it and hands rtf.frag flat varyings (cheaper per pixel than uniform-block reads,
// which are cheaper than SSBOs: DESIGN.md "What costs what in a fragment shader on llvmpipe").
struct RtfObjectGpu {
  glm::vec4 toQ[3];        // rows: q = toQ · (p, 1): the field's local offset from o in units of η
  glm::vec4 toLocal[3];    // rows: world → object-frame directions (normals; a reflection for a mirrored object)
  glm::vec4 centreWorld;   // xyz: o in the world; w: the field's radius R = (outer + Δr)·η, or its reach·η with a tail (m), the sphere rtf.vert covers
  glm::vec4 grid;          // spheres, face size, inner, outer (η)
  glm::uvec4 ids;          // x: entity index + 1 (its own pixels skip the field); y: SH count 4 or 9 (the pipeline); z: the reach (η, float bits; 0: no tail)
  // Entity index + 1 of the other rtf objects this frame, the kRtfOnObjectIds nearest to this one by
  // centre distance (kRtfNoEntity: none): a receiver on one of them reads the field's on-object X
  // (overlap.hpp w_on; rtf.frag). Receivers on farther ones read the off-object X (the field rarely reaches
  // them). rtf.vert hands them on as two flat uvec4 (8 compares a pixel: within the noise of a draw on
  // llvmpipe, where 16 ids read from the uniform block cost 8–10 %; README "RTF's nearer-object occlusion
  // per receiver, session 26"). nearestOthers() picks them.
  glm::uvec4 onObject[2];
  // blocked[j·9 + i].rgb = Â_{l(i)}/π · T_ij, T the product matrix of the indirect radiance L
  // (object frame, at o): ((u − V) ⊙ L)_i = Σ_j T_ij (u − V)_j (sh_product.hpp productMatrix). Only
  // i < 9: the clamped cosine has Â_3 = 0. The ξ pass folds it into its per-sample X
  // (XiPass::setBlockedLight, xi.comp), so the fragment shader reads only X (7 RGBA8 texels per tap).
  glm::vec4 blocked[kShCount * 9];
};
inline constexpr std::size_t kRtfOnObjectIds = 8;
inline constexpr std::uint32_t kRtfNoEntity = 0xFFFFFFFFu;  // no receiver's entity + 1 (ids + 1 < 2³² − 1)
static_assert(sizeof(RtfObjectGpu) == (11 + kShCount * 9) * 16);
inline constexpr std::size_t kRtfObjectStride = 2560;  // a multiple of every minUniformBufferOffsetAlignment (≤ 256)
static_assert(sizeof(RtfObjectGpu) <= kRtfObjectStride);

// The record of a field placed by `world` with indirect radiance `indirect` (world frame, at o),
// entity `entity` (index; its own pixels skip the field), shaded with `shCount` (4 or 9) SH, with
// lookup()'s `reach` (η; 0: the end at r_N + Δr, tailFade).
RtfObjectGpu packObject(const Field& field, const glm::mat4& world, const ShRgb& indirect, std::uint32_t entity,
                        int shCount = 9, float reach = 0.0f);

// The indices of the `count` points of `centres` nearest to centres[o], o left out, nearest first (ties: lower
// index first): the objects whose surfaces a field's record names (RtfObjectGpu::onObject).
std::vector<std::size_t> nearestOthers(std::span<const glm::vec3> centres, std::size_t o, std::size_t count);

// NOT the GPU's any more (README RTF "Seventh pass": it helped cornell-rtf only where fields overlap,
// by cancelling the sum's double count, and hurt both levels elsewhere; kept for rtf_parts' blocked-level
// form and its tests). The shading step's blocked light at the receiver instead of at o (ours; the departure is the
// scale): Eq. 10 blocks the indirect light L(r) at the receiver r, (u − V(q)) ⊙ L(r); the record's
// product matrix T' holds L(o). Per field sample q (world position p_q), the ξ pass scales T'·(u − V)
// by s_c(q) = L_00,c(p_q) / L_00,c(o) per channel (l = 0: the mean radiance; the directional shape
// of L stays o's), so Eq. 10's lookup interpolates the scaled term to the receiver; with light the
// same everywhere s = 1 and nothing changes. Why: the light at o was 11–75 % brighter than at the
// receivers in front of cornell-rtf's boxes, where RTF blocked 30 % more than the black-box
// reference (README Results "RTF"). s is 1 where L_00(o) ≤ 1e-6, and ≥ 0. With `staticScene`, a
// sample that static geometry hides from o (under a floor, inside a wall: no receiver lies there,
// and the probes' light there is not a receiver's) takes the s of the last sample before it on its
// ray from o, so receivers on that surface interpolate between values in front of it.
std::vector<glm::vec4> blockedScale(const Field& field, const glm::mat4& world, const incident::IndirectSource& indirect,
                                    const ref::SceneBvh* staticScene = nullptr);

// The incident-light service as the bouncing step's source: indirect + lights at a point (radius 0).
class LitSource final : public incident::IndirectSource {
 public:
  LitSource(const incident::Service& service, std::span<const render::LightGpu> lights)
      : service_(service), lights_(lights) {}
  incident::RadianceSH radianceSH(glm::vec3 p) const override { return service_.radianceSH(p, 0.0f, lights_); }

 private:
  const incident::Service& service_;
  std::span<const render::LightGpu> lights_;
};

struct Participant {
  ecs::Entity entity;
  std::string name;  // the entity id: timestamp scopes "rtf/<name>", "rtf.bounce/<name>"
  Field field;
  int bounces = 2;
  int sh = 9;  // receiver SH count (scene::Rtf::sh): the record's ids.y
  float reach = 0.0f;  // tailReach(field, scene::Rtf::tail), η: the record's ids.z and Object::reach
};

// One frame's objects after the bouncing step, in participant order (objects without a world
// transform are left out).
struct FrameObjects {
  std::vector<std::size_t> participant;            // index into Update::participants()
  std::vector<std::vector<glm::vec3>> proxyLight;  // m·16 RGB per object, object frame (for the ξ pass)
  std::vector<RtfObjectGpu> records;
  std::vector<OcclusionShares> shares;             // per object: sharedOcclusion() of its field (overlap.hpp)
  std::vector<double> bounceEnergy;                // BounceResult::bounceEnergy
  int bounces = 0;
};

class Update {
 public:
  Update(ecs::Registry& registry, std::vector<Participant> participants);
  // Not owned. Null indirect: none; null visibility: every light unoccluded.
  void setIndirect(const incident::IndirectSource* indirect) { service_.setIndirect(indirect); }
  void setLightVisibility(const incident::Visibility* visibility) { service_.setVisibility(visibility); }
  // The lights' visibility at each object's proxies traced through the level's static geometry
  // (`level`, not owned, may be null) and the OTHER posed objects (occluders.hpp; occluder i is
  // participant i's mesh), in place of setLightVisibility's. Null occluders: setLightVisibility's.
  void setOccluders(std::unique_ptr<PosedOccluders> occluders, const ref::SceneBvh* level) {
    occluders_ = std::move(occluders), level_ = level;
  }
  // With occluders and `surfaces` (the static scene with its textures, not owned; null: off): the
  // proxies' source light also loses the lamp light the posed objects' shadows take off the room around
  // them (room_shadows.hpp; for an indirect source that holds the room's lamp bounce without them: the
  // baked probes).
  void setRoomShadows(const ref::SceneBvh* surfaces) { surfaces_ = surfaces; }
  const std::vector<Participant>& participants() const { return participants_; }
  int bounces() const;

  // The bouncing step for the frame's lights; its CPU time is appended to bounceMs().
  FrameObjects frame(std::span<const render::LightGpu> lights);
  const std::vector<double>& bounceMs() const { return bounceMs_; }

 private:
  ecs::Registry& registry_;
  std::vector<Participant> participants_;
  incident::Service service_;
  std::unique_ptr<PosedOccluders> occluders_;
  const ref::SceneBvh* level_ = nullptr;
  const ref::SceneBvh* surfaces_ = nullptr;
  std::vector<double> bounceMs_;
};

}  // namespace bounce::gi::rtf
