#include "engine/scene/systems.hpp"

#include <vector>

#include "engine/core/error.hpp"
#include "engine/scene/motion.hpp"
#include "engine/scene/transform_math.hpp"

namespace bounce::scene {

void motionSystem(ecs::Registry& registry, double timeSeconds) {
  registry.view<Motion, Transform>().each([&](const Motion& m, Transform& t) { t = evaluateMotion(m, timeSeconds); });
}

void transformSystem(ecs::Registry& registry) {
  const std::vector<ecs::Entity> targets = registry.view<Transform>().entities();
  // Per slot index: 0 = not computed, 1 = on the chain being walked (cycle check), 2 = done.
  std::vector<std::uint8_t> state;
  std::vector<glm::mat4> world;
  auto slot = [&](ecs::Entity e) -> std::size_t {
    if (e.index() >= state.size()) {
      state.resize(std::size_t(e.index()) + 1, 0);
      world.resize(std::size_t(e.index()) + 1, glm::mat4(1.0f));
    }
    return e.index();
  };
  std::vector<ecs::Entity> chain;
  for (ecs::Entity target : targets) {
    // Walk up to the first computed ancestor (or a root), then evaluate back down: iterative,
    // so a deep hierarchy cannot overflow the stack.
    chain.clear();
    ecs::Entity cur = target;
    glm::mat4 above(1.0f);
    while (true) {
      const std::size_t i = slot(cur);
      if (state[i] == 2) {
        above = world[i];
        break;
      }
      if (state[i] == 1) throw InternalError("scene: transformSystem: parent cycle through " + ecs::toString(cur));
      state[i] = 1;
      chain.push_back(cur);
      const Parent* p = registry.tryGet<Parent>(cur);
      if (!p) break;
      if (!registry.valid(p->entity))
        throw InternalError("scene: transformSystem: " + ecs::toString(cur) + " has a dead parent " +
                            ecs::toString(p->entity));
      cur = p->entity;
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const Transform* t = registry.tryGet<Transform>(*it);
      above = t ? above * toMatrix(*t) : above;
      world[it->index()] = above;
      state[it->index()] = 2;
    }
  }
  for (ecs::Entity e : targets) registry.emplaceOrReplace<WorldTransform>(e, world[e.index()]);
}

ecs::Entity activeCamera(ecs::Registry& registry) {
  if (const ecs::Entity e = registry.view<ActiveCamera, Camera>().front(); !e.isNull()) return e;
  ecs::Entity best = ecs::Entity::null();
  registry.view<Camera>().each([&](ecs::Entity e, Camera&) {
    if (best.isNull() || e.index() < best.index()) best = e;
  });
  return best;
}

}  // namespace bounce::scene
