#pragma once
// Scene systems. Both are deterministic: their result depends only on the registry's
// components and the time given, never on entity creation order or on previous frames.
#include "engine/ecs/registry.hpp"
#include "engine/scene/components.hpp"

namespace bounce::scene {

// Schedule stages (ecs::Schedule runs ascending): scripts/motion, then transforms.
inline constexpr int kStageMotion = 100;
inline constexpr int kStageTransform = 300;

// Transform = evaluateMotion(motion, timeSeconds) for every entity with Motion and Transform.
void motionSystem(ecs::Registry& registry, double timeSeconds);

// WorldTransform = world(parent) · toMatrix(Transform) for every entity with a Transform
// (emplaced when missing). Parents are evaluated before their children whatever the creation
// order; an entity without Transform on a chain contributes identity. Throws InternalError
// naming the entity when a Parent refers to a dead entity or the chain has a cycle.
void transformSystem(ecs::Registry& registry);

// The camera to render from: the entity with ActiveCamera and Camera, else the Camera entity
// with the lowest index; the null entity when there is no camera.
ecs::Entity activeCamera(ecs::Registry& registry);

}  // namespace bounce::scene
