#include "engine/gi/sl/update.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/anim/instances.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/core/error.hpp"
#include "engine/gi/sl/hierarchy.hpp"
#include "engine/scene/asset_instances.hpp"

namespace bounce::gi::sl {

std::vector<InstancedPrimitive> instancedPrimitives(const asset::CookedAsset& asset, const scene::MeshRef& ref) {
  std::vector<InstancedPrimitive> out;
  std::uint32_t next = 0;
  // The same walk as ref::extractScene: pre-order, meshes of virtual-light nodes skipped.
  scene::forEachInstancedNode(asset, ref, glm::mat4(1.0f), [&](int n, const glm::mat4& world) {
    const asset::Node& node = asset.nodes[std::size_t(n)];
    if (node.mesh < 0 || node.vlm.present) return;
    const auto& prims = asset.meshes[std::size_t(node.mesh)].primitives;
    for (std::size_t p = 0; p < prims.size(); ++p) {
      InstancedPrimitive ip;
      ip.node = n;
      ip.primitive = p;
      ip.bakeFrame = world;
      ip.firstVertex = next;
      ip.vertexCount = std::uint32_t(prims[p].positions.size());
      next += ip.vertexCount;
      out.push_back(ip);
    }
  });
  return out;
}

Skin skinOf(const asset::CookedAsset& asset, const std::vector<InstancedPrimitive>& primitives) {
  Skin skin;
  bool any = false;
  for (const auto& ip : primitives) {
    const auto& p = asset.meshes[std::size_t(asset.nodes[std::size_t(ip.node)].mesh)].primitives[ip.primitive];
    const bool skinned = anim::isSkinned(asset, ip.node) && p.weights.size() == p.positions.size();
    skin.joints.push_back(skinned ? p.joints : std::vector<glm::u16vec4>{});
    skin.weights.push_back(skinned ? p.weights : std::vector<glm::vec4>{});
    any = any || skinned;
  }
  return any ? skin : Skin{};
}

glm::dmat3 closestRotation(const glm::dmat3& m) {
  if (!(std::abs(glm::determinant(m)) > 1e-30)) return glm::dmat3(1.0);
  // X_{k+1} = (X_k + X_k^{-T}) / 2 converges quadratically to the orthogonal polar factor; the
  // scaled variant (γ = |det X|^(-1/3)) makes it insensitive to the overall scale.
  glm::dmat3 x = m;
  for (int i = 0; i < 30; ++i) {
    const double g = std::pow(std::abs(glm::determinant(x)), -1.0 / 3.0);
    const glm::dmat3 next = 0.5 * (g * x + glm::inverse(glm::transpose(x)) / g);
    double change = 0.0;
    for (int c = 0; c < 3; ++c) change = std::max(change, glm::length(next[c] - x[c]));
    x = next;
    if (change < 1e-14) break;
  }
  return x;
}

SpherePoser::SpherePoser(const asset::CookedAsset& asset, const scene::MeshRef& ref, const SphereSet& set)
    : asset_(asset), ref_(ref), primitives_(instancedPrimitives(asset, ref)) {
  std::vector<std::uint32_t> starts;  // firstVertex per primitive, for the vertex → primitive lookup
  std::vector<bool>& skinned = skinned_;
  for (const auto& ip : primitives_) {
    bakeFrameInverse_.push_back(glm::inverse(glm::dmat4(ip.bakeFrame)));
    starts.push_back(ip.firstVertex);
    const auto& p = asset.meshes[std::size_t(asset.nodes[std::size_t(ip.node)].mesh)].primitives[ip.primitive];
    skinned.push_back(anim::isSkinned(asset, ip.node) && p.weights.size() == p.positions.size());
  }
  const std::uint32_t total = primitives_.empty() ? 0 : primitives_.back().firstVertex + primitives_.back().vertexCount;
  auto add = [&](Covered& c, std::map<std::uint32_t, std::uint32_t>& rigidCount, std::uint32_t v) {
    if (v >= total) throw InternalError("sl::SpherePoser: covered vertex " + std::to_string(v) + " of " +
                                        std::to_string(total) + " (sphere set baked from another mesh)");
    const auto prim = std::uint32_t(std::upper_bound(starts.begin(), starts.end(), v) - starts.begin() - 1);
    if (skinned[prim]) c.skinned.emplace_back(prim, v - starts[prim]);
    else ++rigidCount[prim];
  };
  auto finish = [](Covered& c, const std::map<std::uint32_t, std::uint32_t>& rigidCount) {
    c.rigid.assign(rigidCount.begin(), rigidCount.end());
  };
  for (const SlSphere& s : set.spheres) {
    Covered c;
    std::map<std::uint32_t, std::uint32_t> counts;
    for (std::uint32_t v : s.vertices) add(c, counts, v);
    finish(c, counts);
    covered_.push_back(std::move(c));
    centres_.push_back(s.centre);
    radii_.push_back(s.radius);
  }
  std::map<std::uint32_t, std::uint32_t> counts;
  for (std::uint32_t v = 0; v < total; ++v) add(all_, counts, v);
  finish(all_, counts);
}

SpherePoser::FrameState SpherePoser::frameState(const glm::mat4& entityWorld, const anim::Pose* pose) const {
  // W_P per node (with the pose's local matrices when posed), as the renderer places them.
  std::map<int, glm::mat4> nodeWorld;
  scene::forEachInstancedNode(asset_, ref_, entityWorld, [&](int n, const glm::mat4& w) { nodeWorld[n] = w; },
                              pose ? &pose->local : nullptr);
  FrameState f;
  f.pose = pose;
  f.skinFrame = pose ? glm::dmat4(anim::skinFrame(asset_, ref_, entityWorld, *pose)) : glm::dmat4(entityWorld);
  f.rigid.resize(primitives_.size());
  f.rigidScale.resize(primitives_.size());
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    f.rigid[i] = glm::dmat4(nodeWorld.at(primitives_[i].node)) * bakeFrameInverse_[i];
    f.rigidScale[i] = std::cbrt(std::abs(glm::determinant(glm::dmat3(f.rigid[i]))));
  }
  return f;
}

glm::dmat4 SpherePoser::skinnedTransform(const FrameState& f, std::uint32_t prim, std::uint32_t v) const {
  if (!f.pose) return f.rigid[prim];  // unposed: drawn at its node's transform (as ref::extractScene)
  const InstancedPrimitive& ip = primitives_[prim];
  const asset::Node& node = asset_.nodes[std::size_t(ip.node)];
  const auto& p = asset_.meshes[std::size_t(node.mesh)].primitives[ip.primitive];
  return f.skinFrame * glm::dmat4(anim::skinMatrix(p, f.pose->joints[std::size_t(node.skin)], v)) *
         bakeFrameInverse_[prim];
}

std::vector<glm::dmat4> SpherePoser::vertexTransforms(const glm::mat4& entityWorld, const anim::Pose* pose) const {
  const FrameState f = frameState(entityWorld, pose);
  std::vector<glm::dmat4> out;
  for (std::uint32_t prim = 0; prim < primitives_.size(); ++prim) {
    for (std::uint32_t v = 0; v < primitives_[prim].vertexCount; ++v)
      out.push_back(skinned_[prim] ? skinnedTransform(f, prim, v) : f.rigid[prim]);
  }
  return out;
}

void SpherePoser::pose(const glm::mat4& entityWorld, const anim::Pose* pose, std::vector<PosedSphere>& out) const {
  const FrameState f = frameState(entityWorld, pose);
  auto average = [&](const Covered& c, glm::dmat4& sum, double& scale) {
    sum = glm::dmat4(0.0);
    scale = 0.0;
    std::size_t n = 0;
    for (const auto& [prim, count] : c.rigid) {
      sum += double(count) * f.rigid[prim];
      scale += double(count) * f.rigidScale[prim];
      n += count;
    }
    for (const auto& [prim, v] : c.skinned) {
      const glm::dmat4 t = skinnedTransform(f, prim, v);
      sum += t;
      scale += std::cbrt(std::abs(glm::determinant(glm::dmat3(t))));
      ++n;
    }
    if (n == 0) return false;
    sum /= double(n);
    scale /= double(n);
    return true;
  };
  glm::dmat4 whole(1.0);
  double wholeScale = 1.0;
  bool haveWhole = false;
  out.resize(centres_.size());
  for (std::size_t s = 0; s < centres_.size(); ++s) {
    glm::dmat4 a;
    double scale;
    if (!average(covered_[s], a, scale)) {
      if (!haveWhole && !average(all_, whole, wholeScale)) whole = glm::dmat4(1.0), wholeScale = 1.0;
      haveWhole = true;
      a = whole, scale = wholeScale;
    }
    out[s].centre = glm::vec3(a * glm::dvec4(glm::dvec3(centres_[s]), 1.0));
    out[s].radius = float(double(radii_[s]) * scale);
    out[s].rotation = glm::mat3(closestRotation(glm::dmat3(a)));
  }
}

std::vector<PosedSphere> parentSpheres(std::span<const PosedSphere> posed, std::span<const std::uint32_t> objects) {
  if (posed.size() != objects.size()) throw InternalError("sl::parentSpheres: one object id per SL");
  std::uint32_t count = 0;
  for (std::uint32_t o : objects) count = std::max(count, o + 1);
  std::vector<std::vector<Sphere>> children(count);
  for (std::size_t i = 0; i < posed.size(); ++i)
    children[objects[i]].push_back({glm::dvec3(posed[i].centre), double(posed[i].radius)});
  std::vector<PosedSphere> out(count);
  for (std::uint32_t o = 0; o < count; ++o) {
    if (children[o].empty()) continue;
    const Sphere s = parentSphere(children[o]);
    out[o].centre = glm::vec3(s.centre);
    out[o].radius = float(s.radius);
  }
  return out;
}

}  // namespace bounce::gi::sl
