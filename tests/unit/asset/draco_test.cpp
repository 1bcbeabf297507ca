// Draco variants decode to the same triangles as their uncompressed glTF twins, within the
// position quantization bound.
#include "tests/unit/asset/test_util.hpp"

#include <cmath>
#include <map>
#include <tuple>

namespace bounce::asset::test {
namespace {

// gltf-pipeline's default position quantization (LICENSES.md). The upstream glTF-Draco variants
// were encoded with at least this many bits, so the same bound holds for them.
constexpr int kPositionBits = 11;

// Draco quantizes positions on a grid of (largest bounding-box side) / (2^bits - 1); rounding to
// the grid moves a coordinate by at most half a step. The bound allowed here is a full step of
// side / 2^bits ... times 2: still far below any feature size, with room for float rounding of
// the dequantization.
float quantizationBound(const Bounds& b) {
  const glm::vec3 size = b.max - b.min;
  const float side = std::max(size.x, std::max(size.y, size.z));
  return 2.0f * side / float(1 << kPositionBits);
}

// Uniform hash grid over points for nearest-neighbour queries within `cell`.
class Grid {
 public:
  Grid(const std::vector<glm::vec3>& pts, float cell) : pts_(pts), cell_(cell) {
    for (std::size_t i = 0; i < pts.size(); ++i) cells_[key(pts[i])].push_back(i);
  }
  float nearest(const glm::vec3& q) const {
    float best = INFINITY;
    const auto k = key(q);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find({std::get<0>(k) + dx, std::get<1>(k) + dy, std::get<2>(k) + dz});
          if (it == cells_.end()) continue;
          for (std::size_t i : it->second) best = std::min(best, glm::distance(q, pts_[i]));
        }
    return best;
  }

 private:
  using Key = std::tuple<long, long, long>;
  Key key(const glm::vec3& p) const {
    return {long(std::floor(p.x / cell_)), long(std::floor(p.y / cell_)), long(std::floor(p.z / cell_))};
  }
  const std::vector<glm::vec3>& pts_;
  float cell_;
  std::map<Key, std::vector<std::size_t>> cells_;
};

std::vector<glm::vec3> usedPositions(const Primitive& p) {
  std::vector<glm::vec3> out;
  for (std::uint32_t i : p.indices) out.push_back(p.positions[i]);
  return out;
}

void compareTwins(const fs::path& draco, const fs::path& plain) {
  SCOPED_TRACE(draco.string());
  const CookedAsset d = cook(draco, geometryOnly());
  const CookedAsset o = cook(plain, geometryOnly());
  // Quantization may collapse a few tiny triangles to zero area; the cook drops and counts them.
  EXPECT_EQ(d.triangleCount() + d.droppedTriangleCount(), o.triangleCount() + o.droppedTriangleCount());
  ASSERT_EQ(d.meshes.size(), o.meshes.size());
  for (std::size_t m = 0; m < d.meshes.size(); ++m) {
    ASSERT_EQ(d.meshes[m].primitives.size(), o.meshes[m].primitives.size());
    const float bound = quantizationBound(o.meshes[m].bounds);
    for (std::size_t p = 0; p < d.meshes[m].primitives.size(); ++p) {
      const Primitive& dp = d.meshes[m].primitives[p];
      const Primitive& op = o.meshes[m].primitives[p];
      EXPECT_EQ(dp.indices.size() / 3 + dp.droppedTriangles, op.indices.size() / 3 + op.droppedTriangles)
          << "mesh " << m << " primitive " << p;
      EXPECT_EQ(dp.uv0.empty(), op.uv0.empty());
      EXPECT_EQ(dp.joints.size() == dp.positions.size(), op.joints.size() == op.positions.size());
      // Both ways: every used vertex has a counterpart within the bound.
      const auto dv = usedPositions(dp), ov = usedPositions(op);
      const Grid dg(dv, bound), og(ov, bound);
      float worst = 0.0f;
      for (const auto& q : dv) worst = std::max(worst, og.nearest(q));
      for (const auto& q : ov) worst = std::max(worst, dg.nearest(q));
      EXPECT_LE(worst, bound) << "mesh " << m << " primitive " << p;
    }
  }
}

TEST(Draco, EveryDracoVariantMatchesItsUncompressedTwin) {
  std::size_t pairs = 0;
  for (const auto& model : fs::directory_iterator(assets())) {
    for (const char* variant : {"glTF-Draco", "glTF-Draco-gltfpipeline"}) {
      const fs::path dir = model.path() / variant;
      if (!fs::is_directory(dir)) continue;
      const std::string name = model.path().filename().string();
      compareTwins(dir / (name + ".gltf"), model.path() / "glTF" / (name + ".gltf"));
      ++pairs;
    }
  }
  EXPECT_EQ(pairs, 14u);  // 6 upstream glTF-Draco + 8 re-encoded (LICENSES.md)
}

}  // namespace
}  // namespace bounce::asset::test
