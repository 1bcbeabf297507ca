// Hostile inputs, each generated from a real sample asset: every one must give an InputError
// naming the file and the place, never a crash or a half-built asset. Repairs (degenerate and
// NaN triangles) must be made and counted.
#include "engine/core/log.hpp"
#include "tests/unit/asset/test_util.hpp"

#include <cmath>
#include <limits>

namespace bounce::asset::test {
namespace {

// Box.gltf in a scratch folder; the returned JSON is edited by the test and written back.
struct BoxCopy {
  fs::path dir;
  nlohmann::json doc;
  std::vector<std::uint8_t> bin;
  fs::path write(const nlohmann::json& j, const std::string& name = "Bad.gltf") {
    writeJson(dir / name, j);
    return dir / name;
  }
  void writeBin() { writeFileAtomic(dir / "Box0.bin", bin); }
};

BoxCopy boxCopy() {
  BoxCopy b{scratch(), {}, {}};
  copyFolder(assets() / "Box/glTF", b.dir);
  b.doc = readJson(b.dir / "Box.gltf");
  b.bin = readFileBytes(b.dir / "Box0.bin");
  return b;
}

void cookIt(const fs::path& p) { (void)cook(p, geometryOnly()); }

TEST(Hostile, TruncatedGlbAtSeveralCutPoints) {
  const fs::path dir = scratch();
  const auto glb = readFileBytes(assets() / "Box/glTF-Binary/Box.glb");
  for (std::size_t cut : {std::size_t(0), std::size_t(3), std::size_t(11), std::size_t(19), std::size_t(100),
                          glb.size() / 2, glb.size() - 4, glb.size() - 1}) {
    SCOPED_TRACE(cut);
    writeFileAtomic(dir / "Cut.glb", std::span<const std::uint8_t>(glb.data(), cut));
    expectInputError([&] { cookIt(dir / "Cut.glb"); }, {"Cut.glb: "});
  }
  // A cut inside the file past the header is reported as a length mismatch of the GLB header.
  writeFileAtomic(dir / "Cut.glb", std::span<const std::uint8_t>(glb.data(), glb.size() / 2));
  expectInputError([&] { cookIt(dir / "Cut.glb"); }, {"Cut.glb: GLB header: declared length 1664"});
}

TEST(Hostile, BadGlbMagicLengthAndChunkSizes) {
  const fs::path dir = scratch();
  const auto glb = readFileBytes(assets() / "Box/glTF-Binary/Box.glb");
  auto patched = [&](std::size_t at, std::uint32_t value) {
    auto b = glb;
    std::memcpy(b.data() + at, &value, 4);
    writeFileAtomic(dir / "Bad.glb", b);
    return dir / "Bad.glb";
  };
  expectInputError([&] { cookIt(patched(0, 0x12345678)); }, {"Bad.glb: byte 0: neither GLB magic"});
  expectInputError([&] { cookIt(patched(4, 1)); }, {"Bad.glb: GLB header: version 1"});
  expectInputError([&] { cookIt(patched(8, 5000)); }, {"Bad.glb: GLB header: declared length 5000"});
  expectInputError([&] { cookIt(patched(12, 0xFFFFFFF0u)); }, {"Bad.glb: GLB chunk 0 at byte 12", "runs past the end"});
  expectInputError([&] { cookIt(patched(16, 0x4E4942)); }, {"Bad.glb: GLB chunk 0", "not JSON"});
  // BIN chunk header: after the JSON chunk.
  std::uint32_t jsonLength = 0;
  std::memcpy(&jsonLength, glb.data() + 12, 4);
  expectInputError([&] { cookIt(patched(20 + jsonLength, 0x7FFFFFFF)); },
                   {"Bad.glb: GLB chunk 1 at byte " + std::to_string(20 + jsonLength), "runs past the end"});
}

TEST(Hostile, AccessorIndexOutOfRange) {
  BoxCopy b = boxCopy();
  auto j = b.doc;
  j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
  expectInputError([&] { cookIt(b.write(j)); },
                   {"Bad.gltf: /meshes/0/primitives/0/attributes/POSITION: accessor index 99 out of range", "expected"});
}

TEST(Hostile, AccessorRunsPastItsBufferView) {
  BoxCopy b = boxCopy();
  auto j = b.doc;
  j["accessors"][2]["byteOffset"] = 400;  // POSITION: 24 × 12 bytes from 400 exceeds the view
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: accessor 2: data of 24 elements", "runs past the end of bufferView 1"});
}

TEST(Hostile, BufferShorterThanDeclared) {
  BoxCopy b = boxCopy();
  b.bin.resize(500);
  b.writeBin();
  expectInputError([&] { cookIt(b.write(b.doc)); }, {"Bad.gltf: /buffers/0: buffer file 'Box0.bin' has 500 bytes, declared byteLength 648"});
}

TEST(Hostile, BufferViewOutsideBuffer) {
  BoxCopy b = boxCopy();
  auto j = b.doc;
  j["bufferViews"][1]["byteLength"] = 100000;
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: bufferView 1: bytes", "run past the end of buffer 0 (648 bytes)"});
}

TEST(Hostile, AbsurdVertexCount) {
  BoxCopy b = boxCopy();
  auto j = b.doc;
  j["accessors"][2]["count"] = 4294967296ull;  // 2^32 vertices declared
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: accessor 2: count 4294967296 is absurdly large"});
  j["accessors"][2]["count"] = 1000000;  // plausible count, but not in the buffer
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: accessor 2: data of 1000000 elements"});
}

TEST(Hostile, IndexOutOfRange) {
  BoxCopy b = boxCopy();
  const std::uint16_t bad = 9999;
  std::memcpy(b.bin.data() + elementOffset(b.doc, 0, 7), &bad, 2);
  b.writeBin();
  expectInputError([&] { cookIt(b.write(b.doc)); },
                   {"Bad.gltf: /meshes/0/primitives/0/indices: index 7 is 9999 (expected < vertex count 24)"});
}

TEST(Hostile, CyclicNodeGraph) {
  BoxCopy b = boxCopy();
  auto j = b.doc;
  j["nodes"][1]["children"] = {2};
  j["nodes"].push_back({{"children", {1}}});  // 1 → 2 → 1
  j["scenes"][0]["nodes"] = {0};
  // Node 1 has parents 0 and 2: reported first as a second parent.
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: /nodes/2/children/0: node 1 already has parent 0"});
  // A pure cycle (each node has one parent, no root among them).
  j["nodes"][0]["children"] = nlohmann::json::array();
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: /nodes/", "is its own ancestor (cycle)"});
  j["nodes"][2]["children"] = {2};
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: /nodes/2/children/0: node 2 is its own child (cycle)"});
}

TEST(Hostile, MissingTextureFile) {
  const fs::path dir = scratch();
  copyFolder(assets() / "BoxTextured/glTF", dir);
  fs::remove(dir / "CesiumLogoFlat.png");
  expectInputError([&] { (void)cook(dir / "BoxTextured.gltf"); },
                   {"BoxTextured.gltf: /images/0/uri: texture file 'CesiumLogoFlat.png' not found"});
}

TEST(Hostile, CorruptTextureFile) {
  const fs::path dir = scratch();
  copyFolder(assets() / "BoxTextured/glTF", dir);
  auto png = readFileBytes(dir / "CesiumLogoFlat.png");
  for (std::size_t i = 100; i < png.size(); ++i) png[i] = std::uint8_t(i * 7);
  writeFileAtomic(dir / "CesiumLogoFlat.png", png);
  expectInputError([&] { (void)cook(dir / "BoxTextured.gltf"); }, {"BoxTextured.gltf: /images/0: cannot decode image"});
}

TEST(Hostile, CorruptDracoPayload) {
  const fs::path dir = scratch();
  copyFolder(assets() / "Box/glTF-Draco", dir);
  auto doc = readJson(dir / "Box.gltf");
  const int view = doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"];
  const std::size_t offset = doc["bufferViews"][view].value("byteOffset", 0), length = doc["bufferViews"][view]["byteLength"];
  const auto original = readFileBytes(dir / "0.bin");
  const std::string where = "Box.gltf: /meshes/0/primitives/0/extensions/KHR_draco_mesh_compression";
  // Garbage over the whole payload (header included).
  auto bin = original;
  for (std::size_t i = 0; i < length; ++i) bin[offset + i] = std::uint8_t(0xA5 ^ i);
  writeFileAtomic(dir / "0.bin", bin);
  expectInputError([&] { cookIt(dir / "Box.gltf"); }, {where, "Draco"});
  // Valid header, body cut short.
  writeFileAtomic(dir / "0.bin", original);
  doc["bufferViews"][view]["byteLength"] = 20;
  writeJson(dir / "Box.gltf", doc);
  expectInputError([&] { cookIt(dir / "Box.gltf"); }, {where, "Draco decode failed"});
}

TEST(Hostile, ZeroAreaTrianglesAreDroppedWithOneWarning) {
  BoxCopy b = boxCopy();
  // Triangle 0 gets a repeated index; triangle 1 three collinear corners of one box edge: both
  // zero-area, the other 10 triangles untouched.
  std::uint16_t idx[6];
  std::memcpy(idx, b.bin.data() + elementOffset(b.doc, 0, 0), sizeof idx);
  idx[1] = idx[0];
  std::memcpy(b.bin.data() + elementOffset(b.doc, 0, 0), idx, sizeof idx);
  // Collinear: move vertex idx[5] to the midpoint of idx[3] and idx[4].
  glm::vec3 p3, p4;
  std::memcpy(&p3, b.bin.data() + elementOffset(b.doc, 2, idx[3]), 12);
  std::memcpy(&p4, b.bin.data() + elementOffset(b.doc, 2, idx[4]), 12);
  const glm::vec3 mid = 0.5f * (p3 + p4);
  std::memcpy(b.bin.data() + elementOffset(b.doc, 2, idx[5]), &mid, 12);
  b.writeBin();
  const std::size_t before = log::warningCount();
  const CookedAsset a = cook(b.write(b.doc), geometryOnly());
  EXPECT_EQ(log::warningCount(), before + 1);  // one "dropped 2 zero-area triangles" line
  ASSERT_EQ(a.meshes[0].primitives.size(), 1u);
  // Expected: the triangles of the edited buffer that are zero-area, counted here directly.
  std::size_t degenerate = 0;
  for (std::size_t t = 0; t < 12; ++t) {
    std::uint16_t i[3];
    glm::vec3 q[3];
    for (std::size_t k = 0; k < 3; ++k) {
      std::memcpy(&i[k], b.bin.data() + elementOffset(b.doc, 0, 3 * t + k), 2);
      std::memcpy(&q[k], b.bin.data() + elementOffset(b.doc, 2, i[k]), 12);
    }
    degenerate += glm::length(glm::cross(q[1] - q[0], q[2] - q[0])) == 0.0f;
  }
  EXPECT_EQ(degenerate, 2u);
  EXPECT_EQ(a.triangleCount(), 12u - degenerate);
  for (std::size_t t = 0; t < a.meshes[0].primitives[0].indices.size(); t += 3) {
    const auto& p = a.meshes[0].primitives[0];
    const glm::vec3 n = glm::cross(p.positions[p.indices[t + 1]] - p.positions[p.indices[t]],
                                   p.positions[p.indices[t + 2]] - p.positions[p.indices[t]]);
    EXPECT_GT(glm::length(n), 0.0f);
  }
}

TEST(Hostile, NanVerticesAreDroppedWithTheirTriangles) {
  BoxCopy b = boxCopy();
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::memcpy(b.bin.data() + elementOffset(b.doc, 2, 0), &nan, 4);       // vertex 0: x = NaN
  std::memcpy(b.bin.data() + elementOffset(b.doc, 2, 5) + 8, &inf, 4);   // vertex 5: z = +Inf
  b.writeBin();
  // Triangles that use vertex 0 or 5, counted from the index buffer.
  std::size_t bad = 0;
  for (std::size_t t = 0; t < 12; ++t) {
    bool uses = false;
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint16_t i;
      std::memcpy(&i, b.bin.data() + elementOffset(b.doc, 0, 3 * t + k), 2);
      uses = uses || i == 0 || i == 5;
    }
    bad += uses;
  }
  ASSERT_GT(bad, 0u);
  const std::size_t before = log::warningCount();
  const CookedAsset a = cook(b.write(b.doc), geometryOnly());
  EXPECT_EQ(log::warningCount(), before + 1);
  EXPECT_EQ(a.triangleCount(), 12u - bad);
  for (const auto& p : a.meshes[0].primitives[0].positions) EXPECT_TRUE(std::isfinite(p.x + p.y + p.z));
  EXPECT_EQ(a.meshes[0].bounds.min, glm::vec3(-0.5f));
}

TEST(Hostile, SparseAccessorIsApplied) {
  // A sparse substitution of POSITION vertex 3 by (2, 2, 2): bounds grow to 2.
  BoxCopy b = boxCopy();
  const std::size_t at = b.bin.size();
  const std::uint16_t index = 3;
  const float value[3] = {2.0f, 2.0f, 2.0f};
  b.bin.resize(at + 16);
  std::memcpy(b.bin.data() + at, &index, 2);
  std::memcpy(b.bin.data() + at + 4, value, 12);
  b.writeBin();
  auto j = b.doc;
  j["buffers"][0]["byteLength"] = b.bin.size();
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 2}});
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 4}, {"byteLength", 12}});
  const int iv = int(j["bufferViews"].size()) - 2;
  j["accessors"][2]["sparse"] = {{"count", 1},
                                 {"indices", {{"bufferView", iv}, {"componentType", 5123}}},
                                 {"values", {{"bufferView", iv + 1}}}};
  const CookedAsset a = cook(b.write(j), geometryOnly());
  EXPECT_EQ(a.meshes[0].bounds.max, glm::vec3(2.0f));
  // Sparse index past the accessor count is rejected.
  const std::uint16_t badIndex = 24;
  std::memcpy(b.bin.data() + at, &badIndex, 2);
  b.writeBin();
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: /accessors/2/sparse/indices: sparse index 24"});
}

TEST(Hostile, MalformedJsonAndWrongTypes) {
  BoxCopy b = boxCopy();
  writeFileAtomic(b.dir / "Bad.gltf", std::string("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ {"));
  expectInputError([&] { cookIt(b.dir / "Bad.gltf"); }, {"Bad.gltf: JSON byte", "syntax error"});
  auto j = b.doc;
  j["nodes"][0]["children"] = {7};
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: /nodes/0/children/0: node index 7 out of range"});
  j = b.doc;
  j["meshes"][0]["primitives"][0]["material"] = 3;
  expectInputError([&] { cookIt(b.write(j)); }, {"Bad.gltf: /meshes/0/primitives/0/material: material index 3 out of range"});
}

}  // namespace
}  // namespace bounce::asset::test
