#include "engine/ecs/entity.hpp"

namespace bounce::ecs {

std::string toString(Entity e) {
  if (e.isNull()) return "null entity";
  return "entity " + std::to_string(e.index()) + "v" + std::to_string(e.generation());
}

}  // namespace bounce::ecs
