#pragma once
// Entity handles: a 32-bit slot index and a 32-bit generation packed in one uint64.
//
// The registry reuses the slot of a destroyed entity, bumping its generation, so a handle kept
// past destroy() no longer matches: Registry::valid() is false for it and every component access
// through it throws InternalError naming the handle ("entity 7v2"). A slot whose generation
// would wrap around is retired instead of reused, so a stale handle can never become valid again.
#include <cstdint>
#include <functional>
#include <string>

namespace bounce::ecs {

class Entity {
 public:
  static constexpr std::uint32_t kNullIndex = 0xffffffffu;

  constexpr Entity() = default;  // the null entity
  constexpr Entity(std::uint32_t index, std::uint32_t generation)
      : bits_((std::uint64_t(generation) << 32) | index) {}

  static constexpr Entity null() { return Entity(); }
  static constexpr Entity fromBits(std::uint64_t bits) {
    Entity e;
    e.bits_ = bits;
    return e;
  }

  constexpr std::uint32_t index() const { return std::uint32_t(bits_ & 0xffffffffu); }
  constexpr std::uint32_t generation() const { return std::uint32_t(bits_ >> 32); }
  constexpr std::uint64_t bits() const { return bits_; }
  constexpr bool isNull() const { return index() == kNullIndex; }
  constexpr explicit operator bool() const { return !isNull(); }

  friend constexpr bool operator==(Entity a, Entity b) = default;
  // Orders by index, then generation: a deterministic order that does not depend on the
  // order of creation within a slot's history.
  friend constexpr bool operator<(Entity a, Entity b) {
    return a.index() != b.index() ? a.index() < b.index() : a.generation() < b.generation();
  }

 private:
  std::uint64_t bits_ = ~std::uint64_t(0);
};

// "entity 7v2" (index 7, generation 2) or "null entity": used in every error naming an entity.
std::string toString(Entity e);

}  // namespace bounce::ecs

template <>
struct std::hash<bounce::ecs::Entity> {
  std::size_t operator()(bounce::ecs::Entity e) const noexcept { return std::hash<std::uint64_t>()(e.bits()); }
};
