#include "engine/gi/dnrt/cluster.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

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

bool eyeInsideOuterCube(const glm::mat4& boxToWorld, const glm::mat4& view, const glm::mat4& proj) {
  // A perspective projection as perspectiveVk makes (glm::perspectiveRH_ZO, y flipped): clip w = −z_view.
  if (proj[2][3] != -1.0f || proj[3][3] != 0.0f || proj[2][2] >= 0.0f) return false;
  const float nearM = proj[3][2] / proj[2][2], farM = proj[3][2] / (proj[2][2] + 1.0f);
  const glm::mat4 worldToBox = glm::inverse(boxToWorld);
  const glm::vec3 eye = glm::vec3(glm::inverse(view)[3]);
  const glm::vec3 u = glm::vec3(worldToBox * glm::vec4(eye, 1.0f));  // the eye in the unit cube's frame
  // The nearest face plane (u_i = ±1): (1 − |u_i|) / |∇u_i| metres away, ∇u_i row i of worldToBox.
  float nearest = std::numeric_limits<float>::infinity();
  for (int i = 0; i < 3; ++i) {
    const glm::vec3 gradient(worldToBox[0][i], worldToBox[1][i], worldToBox[2][i]);
    nearest = std::min(nearest, (1.0f - std::abs(u[i])) / glm::length(gradient));
  }
  // The farthest point of the cube (a corner: distance is convex).
  float farthest = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec4 corner(c & 1 ? 1.0f : -1.0f, c & 2 ? 1.0f : -1.0f, c & 4 ? 1.0f : -1.0f, 1.0f);
    farthest = std::max(farthest, glm::length(glm::vec3(boxToWorld * corner) - eye));
  }
  // A point of the view frustum at distance d lies at depth z ≥ d cos θ, θ the angle of the frustum's
  // corner rays to its axis (tan² θ = tan²(fov_x/2) + tan²(fov_y/2)); and z ≤ d. The relative margins
  // keep the tests clear of the fp32 rounding of the corners the vertex shader computes.
  const float tanX = 1.0f / std::abs(proj[0][0]), tanY = 1.0f / std::abs(proj[1][1]);
  const float cosCorner = 1.0f / std::sqrt(1.0f + tanX * tanX + tanY * tanY);
  constexpr float kMargin = 1e-3f;
  return nearest > 0.0f && nearest * cosCorner > nearM * (1.0f + kMargin) && farthest < farM * (1.0f - kMargin);
}

}  // namespace bounce::gi::dnrt
