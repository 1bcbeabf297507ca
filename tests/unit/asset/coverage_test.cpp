// Every sample model variant and every conformance/Positive .gltf cooks without error, and every
// model variant has the triangle count LICENSES.md lists for it.
#include "tests/unit/asset/test_util.hpp"

#include <algorithm>
#include <map>

namespace bounce::asset::test {
namespace {

// Triangles per model, from ../shared/assets/LICENSES.md (summed over all primitives).
const std::map<std::string, std::size_t> kTriangles = {
    {"AnimatedCube", 12},      {"Avocado", 682},     {"BoomBox", 6036},        {"Box", 12},
    {"BoxAnimated", 254},      {"BoxTextured", 12},  {"BrainStem", 61666},     {"CesiumMan", 4672},
    {"CesiumMilkTruck", 2856}, {"DamagedHelmet", 15452}, {"Duck", 4212},      {"Fox", 576},
    {"RiggedFigure", 256},     {"RiggedSimple", 188}, {"Suzanne", 3936},      {"VC", 8383},
    {"WaterBottle", 4510}};

std::vector<fs::path> gltfFiles(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const auto ext = e.path().extension();
    if (e.is_regular_file() && (ext == ".gltf" || ext == ".glb")) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Coverage, EveryModelVariantCooksWithItsTriangleCount) {
  std::size_t variants = 0;
  for (const auto& model : fs::directory_iterator(assets())) {
    if (!model.is_directory() || model.path().filename() == "conformance") continue;
    const std::string name = model.path().filename().string();
    ASSERT_TRUE(kTriangles.count(name)) << "model " << name << " is not in the list";
    for (const auto& variant : fs::directory_iterator(model.path())) {
      if (!variant.is_directory()) continue;
      const auto files = gltfFiles(variant.path());
      ASSERT_EQ(files.size(), 1u) << variant.path();
      const CookedAsset a = cook(files[0], geometryOnly());
      // Kept + repaired = the file's count (quantized Draco variants can hold a few triangles
      // that collapse to zero area; those are dropped and counted).
      EXPECT_EQ(a.triangleCount() + a.droppedTriangleCount(), kTriangles.at(name)) << files[0];
      EXPECT_LE(a.droppedTriangleCount(), kTriangles.at(name) / 1000) << files[0];
      ::testing::Test::RecordProperty(name + "/" + variant.path().filename().string(), int(a.triangleCount()));
      ++variants;
    }
  }
  EXPECT_EQ(variants, 52u);  // the variant folders LICENSES.md lists
}

TEST(Coverage, EveryConformancePositiveFileCooks) {
  std::size_t files = 0, triangles = 0;
  const fs::path root = assets() / "conformance/Positive";
  for (const auto& folder : fs::directory_iterator(root)) {
    if (!folder.is_directory()) continue;
    for (const auto& f : gltfFiles(folder.path())) {
      EXPECT_NO_THROW({
        const CookedAsset a = cook(f, geometryOnly());
        triangles += a.triangleCount();
        EXPECT_FALSE(a.nodes.empty()) << f;
      }) << f;
      ++files;
    }
  }
  EXPECT_EQ(files, 169u);  // conformance/NOTES.md: 169 .gltf in 22 folders
  ::testing::Test::RecordProperty("conformance_triangles", int(triangles));
}

}  // namespace
}  // namespace bounce::asset::test
