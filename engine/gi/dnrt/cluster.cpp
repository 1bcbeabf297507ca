#include "engine/gi/dnrt/cluster.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace bounce::gi::dnrt {

AtlasLayout atlasLayout(std::span<const Field* const> fields, std::uint32_t maxDepth) {
  AtlasLayout l;
  for (const Field* f : fields) {
    const std::uint32_t side = std::uint32_t(f->n()) + 2u;
    if (l.size.z + side > maxDepth) break;
    l.z0.push_back(l.size.z);
    l.size = glm::uvec3(std::max(l.size.x, side), std::max(l.size.y, side), l.size.z + side);
    l.slots = std::max(l.slots, int(f->textures.size()));
  }
  return l;
}

std::vector<std::uint8_t> atlasTexels(const AtlasLayout& l, std::span<const Field* const> fields, int slot) {
  std::vector<std::uint8_t> out(std::size_t(l.size.x) * l.size.y * l.size.z * 4u, 0u);
  for (std::size_t i = 0; i < l.z0.size(); ++i) {
    const Field& f = *fields[i];
    if (std::size_t(slot) >= f.textures.size()) continue;
    const std::vector<std::uint8_t>& src = f.textures[std::size_t(slot)];
    const int n = f.n();
    // Padded brick texel (x, y, z) ∈ [0, n + 2)³ copies grid vertex clamp(x − 1, 0, n − 1) per axis.
    for (int z = 0; z < n + 2; ++z)
      for (int y = 0; y < n + 2; ++y)
        for (int x = 0; x < n + 2; ++x) {
          const std::size_t from = f.vertexIndex(std::clamp(x - 1, 0, n - 1), std::clamp(y - 1, 0, n - 1),
                                                 std::clamp(z - 1, 0, n - 1));
          const std::size_t to = ((std::size_t(l.z0[i]) + std::size_t(z)) * l.size.y + std::size_t(y)) * l.size.x +
                                 std::size_t(x);
          std::memcpy(out.data() + to * 4u, src.data() + from * 4u, 4u);
        }
  }
  return out;
}

}  // namespace bounce::gi::dnrt
