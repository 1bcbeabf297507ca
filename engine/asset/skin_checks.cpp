// Skins and animations of a CookedAsset, checked once at cook and at every read (validate()), so
// that the animation jobs (engine/anim) may index without checks. Issue 12's bad-input list:
// joint index ≥ joint count, non-invertible or NaN inverse bind matrices, a skeleton that is not
// one tree, too many joints for the GPU, sampler times not strictly increasing, output counts that
// do not match, channels to missing nodes or morph weights on a mesh without targets.
#include "engine/asset/cooked_asset.hpp"

#include "engine/core/error.hpp"

#include <cmath>
#include <set>

namespace bounce::asset {

namespace {

std::string at(const std::string& base, std::size_t i) { return base + "/" + std::to_string(i); }

bool finiteMatrix(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// Morph target count of a mesh (every primitive must have the same, glTF 2.0 §3.7.2.2). A subdivided
// deformed mesh keeps its targets on its cage (Mesh::cage), which is what the weights morph.
std::size_t targetCount(const CookedAsset& a, const Mesh& m) {
  const Mesh& t = m.cage >= 0 && std::size_t(m.cage) < a.meshes.size() ? a.meshes[std::size_t(m.cage)] : m;
  return t.primitives.empty() ? 0 : t.primitives[0].targets.size();
}

}  // namespace

void validateSkinsAndAnimations(const CookedAsset& a, const std::string& file) {
  std::vector<int> parent(a.nodes.size(), -1);
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    for (std::int32_t c : a.nodes[i].children) parent[std::size_t(c)] = int(i);
  auto rootOf = [&](int n) {
    while (parent[std::size_t(n)] != -1) n = parent[std::size_t(n)];
    return n;
  };
  auto descends = [&](int n, int ancestor) {
    for (; n != -1; n = parent[std::size_t(n)])
      if (n == ancestor) return true;
    return false;
  };
  // The default scene is the joints' common root when the skin names no `skeleton` (glTF allows
  // joints that are scene roots themselves, e.g. conformance Animation_Skin_06): a joint must hang
  // under one of its roots, else it is never posed with the mesh.
  std::vector<char> inScene(a.nodes.size(), 0);
  for (std::int32_t r : a.rootNodes) inScene[std::size_t(r)] = 1;
  for (std::size_t s = 0; s < a.skins.size(); ++s) {
    const Skin& skin = a.skins[s];
    const std::string where = at("/skins", s);
    if (skin.joints.empty()) throwInputError(file, where + "/joints", "a skin without joints", "at least one joint");
    if (skin.joints.size() > kMaxSkinJoints)
      throwInputError(file, where + "/joints", std::to_string(skin.joints.size()) + " joints",
                      "at most " + std::to_string(kMaxSkinJoints) + ", the GPU skinning limit per skin");
    std::set<std::int32_t> seen;
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
      if (!seen.insert(skin.joints[j]).second)
        throwInputError(file, at(where + "/joints", j), "node " + std::to_string(skin.joints[j]) + " listed twice",
                        "each joint once");
    // One tree: every joint under the default scene (and under `skeleton` when the file names it).
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      if (!inScene[std::size_t(rootOf(skin.joints[j]))])
        throwInputError(file, at(where + "/joints", j),
                        "joint node " + std::to_string(skin.joints[j]) + " is outside the default scene's tree "
                            "(skeleton is not a tree)",
                        "every joint a descendant of a scene root");
      if (skin.skeleton >= 0 && !descends(skin.joints[j], skin.skeleton))
        throwInputError(file, at(where + "/joints", j),
                        "joint node " + std::to_string(skin.joints[j]) + " is not a descendant of skeleton node " +
                            std::to_string(skin.skeleton),
                        "every joint under the skin's skeleton root");
    }
    for (std::size_t j = 0; j < skin.inverseBindMatrices.size(); ++j) {
      const glm::mat4& m = skin.inverseBindMatrices[j];
      const float det = finiteMatrix(m) ? glm::determinant(m) : std::nanf("");
      if (!std::isfinite(det) || std::fabs(det) < kMinInverseBindDeterminant)
        throwInputError(file, at(where + "/inverseBindMatrices", j),
                        std::isfinite(det) ? "matrix is not invertible (determinant " + std::to_string(det) + ")"
                                           : "matrix has NaN/Inf entries",
                        "an invertible finite matrix");
    }
  }

  // Skinned mesh nodes: every influencing joint index inside the node's skin.
  for (std::size_t n = 0; n < a.nodes.size(); ++n) {
    const Node& node = a.nodes[n];
    if (node.skin < 0 || node.mesh < 0) continue;
    const std::size_t count = a.skins[std::size_t(node.skin)].joints.size();
    const Mesh& mesh = a.meshes[std::size_t(node.mesh)];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& prim = mesh.primitives[p];
      auto check = [&](const std::vector<glm::u16vec4>& joints, const std::vector<glm::vec4>& weights, const char* name) {
        for (std::size_t v = 0; v < joints.size(); ++v)
          for (int k = 0; k < 4; ++k)
            if (weights[v][k] > 0.0f && joints[v][k] >= count)
              throwInputError(file, at(at("/meshes", std::size_t(node.mesh)) + "/primitives", p) + "/attributes/" + name,
                              "vertex " + std::to_string(v) + " uses joint " + std::to_string(joints[v][k]) + " of skin " +
                                  std::to_string(node.skin) + " (node " + std::to_string(n) + ")",
                              "a joint index < " + std::to_string(count));
      };
      check(prim.joints, prim.weights, "JOINTS_0");
      check(prim.joints1, prim.weights1, "JOINTS_1");
    }
  }

  for (std::size_t i = 0; i < a.animations.size(); ++i) {
    const Animation& an = a.animations[i];
    const std::string where = at("/animations", i);
    for (std::size_t s = 0; s < an.samplers.size(); ++s) {
      const AnimationSampler& smp = an.samplers[s];
      const std::string sw = at(where + "/samplers", s);
      if (smp.input.empty()) throwInputError(file, sw + "/input", "no keys", "at least one key time");
      for (std::size_t k = 0; k < smp.input.size(); ++k) {
        if (!std::isfinite(smp.input[k])) throwInputError(file, sw + "/input", "key " + std::to_string(k) + " is NaN/Inf", "finite times");
        if (k > 0 && !(smp.input[k] > smp.input[k - 1]))
          throwInputError(file, sw + "/input", "key times not strictly increasing at key " + std::to_string(k),
                          "strictly increasing times");
      }
      for (float v : smp.output)
        if (!std::isfinite(v)) throwInputError(file, sw + "/output", "a NaN/Inf value", "finite values");
    }
    for (std::size_t c = 0; c < an.channels.size(); ++c) {
      const AnimationChannel& ch = an.channels[c];
      const std::string cw = at(where + "/channels", c);
      const AnimationSampler& smp = an.samplers[std::size_t(ch.sampler)];
      const Node& node = a.nodes[std::size_t(ch.node)];
      std::size_t want = ch.path == AnimationPath::Rotation ? 4 : 3;
      if (ch.path == AnimationPath::Weights) {
        want = node.mesh >= 0 ? targetCount(a, a.meshes[std::size_t(node.mesh)]) : 0;
        if (want == 0)
          throwInputError(file, cw + "/target", "a weights channel on node " + std::to_string(ch.node) + ", which has no morph targets",
                          "a node whose mesh has morph targets");
      }
      if (smp.components != want)
        throwInputError(file, cw, "sampler " + std::to_string(ch.sampler) + " has " + std::to_string(smp.components) +
                                      " values per key",
                        std::to_string(want) + " for this path");
    }
  }
}

}  // namespace bounce::asset
