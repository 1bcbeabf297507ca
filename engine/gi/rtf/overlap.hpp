#pragma once
// The objects' shared occlusion in the GPU's blocked light (issue 14, README RTF "Seventh pass"), and the
// nearer objects' occlusion of each object's interreflected light (session 24).
//
// The GPU pass adds each object's blocked term on its own (additive blending); Algorithm 1 (§5)
// multiplies the objects' visibilities, and for two objects
//   1 − V_A V_B = (1 − V_A) + (1 − V_B) − (1 − V_A)(1 − V_B),
// so the sum counts the directions both objects hide twice. The shading record's light is the
// indirect light at o (its shape and level, update.hpp packObject); this per-sample factor takes
// half the shared part off each object's term (the other half off the other object's), with the
// light across the hidden directions taken as uniform:
//   s_A(p) = max(0, 1 − ½ Σ_{B≠A} ∫(1 − V_A)(1 − V_B) dω / ∫(1 − V_A) dω),
// V_A the OOF of A's field sample p, V_B B's OOF looked up at p (Eq. 10's weights, the field's end
// included). Both integrals are exact for the order-4 SH: ∫fg dω = Σ_j f_j g_j, ∫f dω = √(4π)·f_0.
// Where no other object's field reaches p, s = 1: the light at o, unscaled. The ξ pass multiplies the
// sample's blocked light by it (shaders/rtf/xi.comp, buffer BlockedScale), the same slot the former
// per-sample light level used (blockedScale in update.hpp, kept for rtf_parts).
//
// The light A sends (its interreflected radiance, ξ) is added on its own as well, where Algorithm 1
// at a receiver q takes Σ_i V_{<i} ⊙ RTF_i(q): each object's light is occluded by the objects nearer
// to q (centre distance, evaluate.cpp incidentRadiance). Per sample p of A, with the same share of
// what A covers that B covers too, and A's light taken as uniform over what A covers (it arrives
// only from there):
//   w_A(p) = Π_{B nearer to p than A} (1 − ∫(1 − V_A)(1 − V_B) dω / ∫(1 − V_A) dω),
// the ξ pass's factor of the interreflected part of X (xi.glsl). Where A is the nearer object, or no
// other field reaches p, w = 1. The factors of several nearer objects multiply, as Algorithm 1's
// visibilities do. Algorithm 1 sorts "the entities except J_q", the receiver's own, so the factor
// depends on the receiver as well as on p. Two per sample, and the shading pass picks one per receiver
// pixel (rtf.frag, by the receiver's entity; session 26):
//  - w_off, every nearer B counted: for receivers that are not on an rtf object's surface (the room,
//    other entities) — Algorithm 1 at p;
//  - w_on, the same product over the B with |p − o_B| ≥ η_B (B left out where p lies inside B's bounding
//    sphere, radius η_B): for receivers on another rtf
//    object's surface. The samples around B's own receivers lie mostly inside B's sphere, so this leaves
//    B's own occlusion out there, as Algorithm 1 does for its own surface (session 24's per-sample form,
//    which the GPU used for every receiver until session 26: counted for every receiver instead, B's
//    occlusion cost cornell-rtf 0.009 on the boxes' own pixels; README "RTF: the nearer object's occlusion
//    of the other's light, session 24", "RTF's nearer-object occlusion per receiver, session 26").
// Without w the GPU's second bounce near cornell-5's red box and truck was 1.25–1.5× shade()'s from
// the same proxy light.
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/rtf/evaluate.hpp"
#include "engine/math/sh_rotate.hpp"

namespace bounce::gi::rtf {

// Per sample of objects[a]'s field, in field.hpp's sample order.
struct OcclusionShares {
  std::vector<glm::vec4> scale;   // (s, s, s, w_off): s the blocked light's factor, w_off the interreflected light's off the objects
  std::vector<float> onObjects;   // w_on: the interreflected light's factor for receivers on another rtf object
};
OcclusionShares sharedOcclusion(std::span<const Object> objects, std::size_t a);

// Object B's occlusion seen from object A's field samples: B's OOF looked up at a world point and
// turned into A's local frame, and the two objects' order in Algorithm 1 there. Built once per pair.
class OtherField {
 public:
  OtherField(std::span<const Object> objects, std::size_t a, std::size_t b);
  // (1 − V_B) at world point p in A's local frame: u·δ_0 − V_B, V_B Eq. 10's lookup faded to V = 1 at
  // the field's end (occlusion()), so all zero beyond B's field.
  ShScalar hiddenInA(glm::vec3 p) const;
  // B comes before A in Algorithm 1's near-to-far order at p: centre distance, ties to the lower index
  // (evaluate.cpp incidentRadiance's stable sort).
  bool nearerThanA(glm::vec3 p) const;
  // Whether any point within `reachA` of o_A lies in B's field (its end or tail included).
  bool reaches(float reachA) const;
  glm::vec3 centre() const { return centre_; }    // o_B, world
  float etaWorld() const { return etaWorld_; }    // η_B, world units (field->radius is the local one)

 private:
  const Field* field_;
  float reach_;       // Object::reach of B (η_B units)
  float reachWorld_;  // where B's field ends, world units
  glm::vec3 centre_, centreA_;
  float etaWorld_;
  bool beforeOnTies_;
  glm::mat4 worldToLocal_;
  // B's local frame → A's local frame: directions M_A⁻¹ M_B = ±R_Aᵀ R_B (gi::Placement), the
  // rotation R_Aᵀ R_B then the inversion (−1)^l when exactly one of the two is mirrored.
  sh::Rotationf toA_;
  bool invert_;
};

}  // namespace bounce::gi::rtf
