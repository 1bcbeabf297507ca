// Fuzz target: bytes → glTF import, once as given (GLB when it starts with "glTF", else JSON) and
// once wrapped as the JSON chunk of a GLB. No base folder, so no external file is ever read.
#include "engine/anim/pose.hpp"
#include "engine/anim/sampling.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/log.hpp"
#include "tests/fuzz/fuzz_target.hpp"

#include <span>

namespace {

// A cooked asset is validated, so its skins and clips must pose without a crash, a failed job or a
// non-finite joint matrix: every clip at its start, middle and past its end, every skinned primitive.
void poseEveryClip(const bounce::asset::CookedAsset& a) {
  using namespace bounce;
  for (int clip = -1; clip < int(a.animations.size()); ++clip) {
    const float d = clip < 0 ? 0.0f : anim::clipDuration(a.animations[std::size_t(clip)]);
    for (float t : {0.0f, 0.5f * d, d + 1.0f}) {
      anim::Pose pose;
      anim::evaluatePose(a, clip, t, pose);  // throws InternalError (a crash for the fuzzer) on a failed job
      for (std::size_t n = 0; n < a.nodes.size(); ++n) {
        if (!anim::isDeformed(a, int(n))) continue;
        std::vector<glm::vec3> p, nrm;
        for (std::size_t pi = 0; pi < a.meshes[std::size_t(a.nodes[n].mesh)].primitives.size(); ++pi)
          anim::posePrimitive(a, int(n), pi, &pose, p, nrm);
      }
    }
  }
}

void importOnce(std::span<const std::uint8_t> bytes, const char* name) {
  bounce::asset::CookOptions options;
  options.decodeImages = true;
  bounce::asset::CookedAsset cooked;
  try {
    cooked = bounce::asset::cookFromMemory(bytes, name, {}, options);
  } catch (const bounce::InputError&) {
    return;  // expected for most inputs
  }
  poseEveryClip(cooked);
}

std::vector<std::uint8_t> asGlbJsonChunk(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> out;
  auto put32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
  };
  const std::size_t padded = (size + 3) / 4 * 4;
  put32(0x46546C67);
  put32(2);
  put32(std::uint32_t(20 + padded));
  put32(std::uint32_t(padded));
  put32(0x4E4F534A);
  out.insert(out.end(), data, data + size);
  out.resize(20 + padded, ' ');
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  bounce::log::setLevel(bounce::log::Level::Quiet);
  importOnce(std::span(data, size), "fuzz.gltf");
  if (size < (std::size_t(1) << 24)) importOnce(asGlbJsonChunk(data, size), "fuzz.glb");
  return 0;
}

std::vector<std::vector<std::uint8_t>> fuzzSeeds(const std::vector<std::string>& assetPaths) {
  std::vector<std::vector<std::uint8_t>> out;
  for (const auto& p : assetPaths) out.push_back(bounce::readFileBytes(p));
  return out;
}
