#pragma once
// The lamp's visibility at the proxies through the other posed objects (issue 14, session 18; README
// "RTF's lamp through the other objects, session 18").
//
// Algorithm 1 (§5) shadows a proxy's source light by the other objects' OOFs only. An order-4 OOF
// cannot shadow a point light (its shadow is a blur of the object's solid angle), and it ends 4 η from
// its object, so on cornell-5 the textured box under the lamp did not shadow the truck 11 η away
// (the truck's lamp light 19× the reference's; README "RTF's first order on cornell-5, session 17").
// Here the lamp's shadow rays from a proxy of object J are traced through the level's static geometry
// AND every other posed object's mesh; J's own mesh is left out, since Eq. 8's transfer already holds
// the object's self-shadowing. The OOFs still multiply the whole source light as Algorithm 1 has it
// (session 17's `lampvis` what-if: cornell-5 0.0976 → 0.0970, cornell-rtf unchanged; the form that
// takes the OOFs off the lamp instead cost cornell-rtf 0.0003).
//
// Cost: one Embree BVH per object in its own (local) frame, built once per session; per frame and
// shadow ray, a bounding-sphere test per other object and, where the segment passes through the
// sphere, one ray in that object's frame (origin and direction mapped by the inverse pose; the
// direction is not renormalised, so the ray's parameter t and its tMax stay the world's).
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/incident/shadow_rays.hpp"
#include "engine/gi/placement.hpp"
#include "engine/ref/scene_bvh.hpp"

namespace bounce::gi::rtf {

// The objects' meshes, each in its own local frame (what its field was baked from: dnrt::objectScene).
class PosedOccluders {
 public:
  // Textures and materials are dropped (shadow rays only). A scene without triangles occludes nothing.
  explicit PosedOccluders(std::vector<ref::SceneDesc> objects);
  ~PosedOccluders();
  std::size_t size() const { return bvh_.size(); }

  // One object placed for a frame: occluder `index` by `world`; its bounding sphere in the world.
  struct Pose {
    std::size_t index = 0;
    gi::Placement placement;
    // The world bounding sphere's radius for the segment cull: radiusLocal × a bound on the 3×3 block's
    // largest singular value (√ of the largest row sum of |MᵀM|, Gershgorin; exact without shear), not
    // Placement's largest column norm, which under shear (a non-uniform parent scale times a child
    // rotation) is smaller than σ_max and would cull rays that hit the mesh (session-18 review).
    float cullRadius = 0.0f;
  };
  // The pose of occluder `index` by `world`; nullopt where gi::tryPlace refuses (no size this frame).
  std::optional<Pose> pose(std::size_t index, const glm::mat4& world) const;

  // True when one of `poses` other than occluder `skip` (its Pose::index; ≥ size(): none left out)
  // lies on the world segment o + t·d, d a unit vector, t in [0, tMax) (tMax may be ∞).
  bool occluded(std::span<const Pose> poses, std::size_t skip, glm::vec3 o, glm::vec3 d, float tMax) const;

 private:
  std::vector<std::unique_ptr<ref::SceneBvh>> bvh_;  // null: no triangles
  std::vector<glm::vec3> centre_;                   // bounding sphere, local frame
  std::vector<float> radius_;
};

// incident::Visibility for the proxies of one object: a shadow ray reaches the light when neither the
// level's static geometry (`level`, may be null) nor another posed object blocks it
// (incident::traceVisibility's rays (shadow_rays.hpp): one at a proxy, which the service asks about at radius 0).
class PosedVisibility final : public incident::Visibility {
 public:
  // Not owned; all must outlive this. `skip`: the occluder index of the object whose proxies ask.
  PosedVisibility(const ref::SceneBvh* level, const PosedOccluders& occluders, std::span<const PosedOccluders::Pose> poses,
                  std::size_t skip)
      : level_(level), occluders_(occluders), poses_(poses), skip_(skip) {}
  float visible(const render::LightGpu& light, glm::vec3 p, float radius) const override;

 private:
  const ref::SceneBvh* level_;
  const PosedOccluders& occluders_;
  std::span<const PosedOccluders::Pose> poses_;
  std::size_t skip_;
};

}  // namespace bounce::gi::rtf
