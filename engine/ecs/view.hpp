#pragma once
// View<Ts...>: the entities that have every component in Ts, with those components.
//
//   registry.view<Transform, Motion>().each([&](Entity e, Transform& t, Motion& m) { ... });
//   registry.view<Transform>().each([&](Transform& t) { ... });   // entity argument optional
//
// each() walks the dense array of the smallest pool among Ts front to back and checks the
// others, so a pass costs O(size of the smallest pool). The visiting order is that pool's dense
// order: insertion order, permuted only by swap-and-pop removals, so the same sequence of
// registry operations always gives the same order.
//
// What a callback may do while a view iterates (each rule has a test in tests/unit/ecs):
//  1. Read and write the components it was handed, and get/tryGet/has on any entity.
//  2. Remove components from, or destroy, the CURRENT entity: safe. Its references stay valid
//     until the callback returns (the payload is only tombstoned until the pass ends).
//  3. Remove components from, or destroy, OTHER entities: safe. While any view iterates, every
//     pool defers removals (it leaves a tombstone instead of swap-and-pop), so no element moves
//     and no reference handed out in this pass dangles. An entity that loses a component in Ts
//     before its turn is not visited; one already visited is not visited again. The pools are
//     compacted when the outermost iteration ends.
//  4. Create entities and add components (any type, any entity): safe. An entity that joins the
//     iterated pool during the pass is not visited in this pass (it lands past the end recorded
//     when the pass began). This includes an entity whose component was removed and re-added
//     during the pass. Storage keeps payloads in a deque, so growth moves nothing either.
//  5. Nested views: allowed; deferral lasts until the outermost pass ends.
// Net guarantee: every entity that holds all of Ts from the start of the pass until its turn
// is visited exactly once; no entity is visited twice.
#include <cstddef>
#include <limits>
#include <tuple>
#include <type_traits>
#include <vector>

#include "engine/ecs/registry.hpp"

namespace bounce::ecs {

template <class... Ts>
class View {
  static_assert(sizeof...(Ts) > 0, "a view needs at least one component type");

 public:
  explicit View(Registry& registry) : registry_(&registry) {}

  template <class F>
  void each(F&& fn) {
    auto pools = std::make_tuple(registry_->template storage<Ts>()...);
    if (!std::apply([](auto*... p) { return (p && ...); }, pools)) return;  // some type never used
    SparseSet* driver = smallest(pools);
    Registry::IterationLock lock(*registry_);
    const std::size_t end = driver->size();  // entries appended during the pass are skipped
    for (std::size_t pos = 0; pos < end; ++pos) {
      const Entity e = driver->dense()[pos];
      if (e.isNull()) continue;  // tombstone: removed earlier in this pass
      if (!std::apply([e](auto*... p) { return (p->contains(e) && ...); }, pools)) continue;
      if constexpr (std::is_invocable_v<F&, Entity, Ts&...>)
        std::apply([&](auto*... p) { fn(e, p->get(e)...); }, pools);
      else
        std::apply([&](auto*... p) { fn(p->get(e)...); }, pools);
    }
  }

  // The matching entities, in the order each() would visit them.
  std::vector<Entity> entities() {
    std::vector<Entity> out;
    each([&](Entity e, Ts&...) { out.push_back(e); });
    return out;
  }
  // Number of matching entities.
  std::size_t count() {
    std::size_t n = 0;
    each([&](Entity, Ts&...) { ++n; });
    return n;
  }
  // The first entity each() would visit, or the null entity.
  Entity front() {
    auto pools = std::make_tuple(registry_->template storage<Ts>()...);
    if (!std::apply([](auto*... p) { return (p && ...); }, pools)) return Entity::null();
    SparseSet* driver = smallest(pools);
    for (Entity e : driver->dense())
      if (!e.isNull() && std::apply([e](auto*... p) { return (p->contains(e) && ...); }, pools)) return e;
    return Entity::null();
  }

 private:
  template <class Tuple>
  static SparseSet* smallest(const Tuple& pools) {
    SparseSet* best = nullptr;
    std::apply(
        [&](auto*... p) {
          ((best = (!best || p->count() < best->count()) ? static_cast<SparseSet*>(p) : best), ...);
        },
        pools);
    return best;
  }

  Registry* registry_;
};

}  // namespace bounce::ecs
