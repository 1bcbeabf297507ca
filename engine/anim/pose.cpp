#include "engine/anim/pose.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/anim/sampling.hpp"
#include "engine/core/error.hpp"

namespace bounce::anim {

namespace {

// scene::nodeLocal's formula (engine/scene/asset_instances.cpp), repeated here so that anim does not
// depend on scene; tests/unit/anim checks the two agree bit for bit.
glm::mat4 trs(const glm::vec3& t, const glm::quat& r, const glm::vec3& s) {
  return glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
}

}  // namespace

bool ClipJob::validate() const {
  if (!asset || !pose) return false;
  return clip >= -1 && (clip < 0 || std::size_t(clip) < asset->animations.size());
}

bool ClipJob::run() const {
  if (!validate()) return false;
  const auto& nodes = asset->nodes;
  std::vector<glm::vec3> t(nodes.size()), s(nodes.size());
  std::vector<glm::quat> r(nodes.size());
  std::vector<std::uint8_t> animated(nodes.size(), 0);
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    t[n] = nodes[n].translation;
    r[n] = nodes[n].rotation;
    s[n] = nodes[n].scale;
  }
  pose->weights.assign(nodes.size(), {});
  if (clip >= 0) {
    const asset::Animation& a = asset->animations[std::size_t(clip)];
    float value[4];
    for (const asset::AnimationChannel& ch : a.channels) {
      const asset::AnimationSampler& smp = a.samplers[std::size_t(ch.sampler)];
      const std::size_t n = std::size_t(ch.node);
      if (ch.path == asset::AnimationPath::Weights) {
        std::vector<float>& w = pose->weights[n];
        w.assign(smp.components, 0.0f);
        if (!SamplingJob{&smp, time, ValueKind::Vector, w}.run()) return false;
        continue;
      }
      const bool rotation = ch.path == asset::AnimationPath::Rotation;
      SamplingJob job{&smp, time, rotation ? ValueKind::Rotation : ValueKind::Vector, std::span<float>(value, rotation ? 4 : 3)};
      if (!job.run()) return false;
      animated[n] = 1;
      if (rotation) r[n] = glm::quat(value[3], value[0], value[1], value[2]);
      else if (ch.path == asset::AnimationPath::Translation) t[n] = glm::vec3(value[0], value[1], value[2]);
      else s[n] = glm::vec3(value[0], value[1], value[2]);
    }
  }
  pose->local.resize(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n)
    pose->local[n] = nodes[n].hasMatrix && !animated[n] ? nodes[n].matrix : trs(t[n], r[n], s[n]);
  return true;
}

bool LocalToModelJob::validate() const { return asset && pose && pose->local.size() == asset->nodes.size(); }

bool LocalToModelJob::run() const {
  if (!validate()) return false;
  const auto& nodes = asset->nodes;
  std::vector<int> parent(nodes.size(), -1);
  for (std::size_t n = 0; n < nodes.size(); ++n)
    for (std::int32_t c : nodes[n].children) parent[std::size_t(c)] = int(n);
  pose->model.resize(nodes.size());
  // Pre-order from every root; the node graph is a forest (validated), so each node is reached once.
  std::vector<std::size_t> stack;
  for (std::size_t n = 0; n < nodes.size(); ++n)
    if (parent[n] == -1) stack.push_back(n);
  while (!stack.empty()) {
    const std::size_t n = stack.back();
    stack.pop_back();
    pose->model[n] = parent[n] == -1 ? pose->local[n] : pose->model[std::size_t(parent[n])] * pose->local[n];
    for (std::int32_t c : nodes[n].children) stack.push_back(std::size_t(c));
  }
  return true;
}

bool JointMatricesJob::validate() const { return asset && pose && pose->model.size() == asset->nodes.size(); }

bool JointMatricesJob::run() const {
  if (!validate()) return false;
  pose->joints.resize(asset->skins.size());
  for (std::size_t s = 0; s < asset->skins.size(); ++s) {
    const asset::Skin& skin = asset->skins[s];
    pose->joints[s].resize(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
      pose->joints[s][j] = pose->model[std::size_t(skin.joints[j])] * skin.inverseBindMatrices[j];
  }
  return true;
}

void evaluatePose(const asset::CookedAsset& asset, int clip, float time, Pose& pose) {
  if (!ClipJob{&asset, clip, time, &pose}.run() || !LocalToModelJob{&asset, &pose}.run() ||
      !JointMatricesJob{&asset, &pose}.run())
    throw InternalError("anim: evaluatePose failed on " + asset.sourceName + " (clip " + std::to_string(clip) + ")");
}

const std::vector<float>& morphWeights(const asset::CookedAsset& asset, const Pose* pose, int node) {
  if (pose && std::size_t(node) < pose->weights.size() && !pose->weights[std::size_t(node)].empty())
    return pose->weights[std::size_t(node)];
  return asset.meshes[std::size_t(asset.nodes[std::size_t(node)].mesh)].morphWeights;
}

}  // namespace bounce::anim
