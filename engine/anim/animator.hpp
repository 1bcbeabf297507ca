#pragma once
// Animation in the ECS. Two steps, like a level:
//   attachAnimators(registry, cookCache);   // once: cook, resolve clips (InputError on a bad one)
//   each frame: motionSystem → animationSystem(registry, t) → transformSystem
// An entity gets an Animator when its mesh asset has animations or a skin (a skinned mesh must be
// posed even in its rest pose), and animationSystem() writes its anim::Pose component. Entities
// without a Pose are drawn, traced and exported from the asset's static node transforms as before.
//
// Clip time (simulation time, so captures stay deterministic): u = phase_s + speed·t, mapped onto
// [0, duration] by the mode: loop wraps, ping-pong reflects, once clamps.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/anim/pose.hpp"
#include "engine/asset/cooked_asset.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/scene/components.hpp"

namespace bounce::anim {

struct Animator {
  std::shared_ptr<const asset::CookedAsset> asset;  // as the renderer cooks it (scene::cookForRef)
  int clip = -1;          // playing clip; -1 = rest pose ("animation": false, or no clips)
  float speed = 1.0f;
  scene::PlayMode mode = scene::PlayMode::Loop;
  float phaseS = 0.0f;
  float clipTime = 0.0f;  // clip time of the last animationSystem() run (overlay)

  std::size_t clipCount() const { return asset->animations.size(); }
  // The playing clip's name ("clip N" when unnamed, "rest pose" for -1).
  std::string clipName() const;
};

// The clip-time mapping above. duration ≤ 0: always 0.
float clipTime(scene::PlayMode mode, float duration, double u);

// Cooks every MeshRef asset (through cookCache, as the renderer does) and emplaces an Animator on
// each entity whose asset has animations or skins, with the clip its AnimationClip (or the default:
// first clip) names. Throws InputError "level: /entities/N/animation/clip: no clip named "x" in
// Fox.glb (expected one of: Survey, Walk, Run)" for a name or index the asset does not have.
void attachAnimators(ecs::Registry& registry, const std::filesystem::path& cookCache);

// Pose = evaluatePose(asset, clip, clipTime(t)) for every entity with an Animator.
void animationSystem(ecs::Registry& registry, double timeSeconds);

// Selects the next clip of an Animator (wrapping; the rest pose after the last clip when the asset
// has more than zero clips): the play key that cycles a character's clips.
void cycleClip(Animator& animator);

}  // namespace bounce::anim
