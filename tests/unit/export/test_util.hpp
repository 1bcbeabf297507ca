#pragma once
// Helpers for the export tests: the level's instances computed independently of the exporter
// (straight from the cooked source assets and the scene systems), and a walk over the scene of a
// re-imported .glb.
#include <cstddef>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/anim/animator.hpp"
#include "engine/asset/cook.hpp"
#include "engine/core/file.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::scene_export::test {

namespace fs = std::filesystem;

inline fs::path outDir() { return fs::path(BOUNCE_TEST_OUT) / "export"; }
inline fs::path cookCache() { return outDir() / "cooked"; }
inline fs::path level(const std::string& name) { return fs::path(BOUNCE_SOURCE_DIR) / "content/levels" / name; }
inline fs::path contentAsset(const std::string& rel) { return fs::path(BOUNCE_SOURCE_DIR) / "content/src" / rel; }

struct Box {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};
  void grow(const glm::vec3& p) { min = glm::min(min, p), max = glm::max(max, p); }
  void grow(const Box& b) { grow(b.min), grow(b.max); }
  bool empty() const { return min.x > max.x; }
  float diagonal() const { return glm::length(max - min); }
};

inline glm::mat4 localOf(const asset::Node& n) {
  if (n.hasMatrix) return n.matrix;
  return glm::translate(glm::mat4(1.0f), n.translation) * glm::mat4_cast(n.rotation) *
         glm::scale(glm::mat4(1.0f), n.scale);
}

// Triangles and world-space vertex bounds of mesh `mesh` of `a` placed at `world`.
inline std::size_t addMesh(const asset::CookedAsset& a, int mesh, const glm::mat4& world, Box& box) {
  std::size_t triangles = 0;
  for (const auto& p : a.meshes[std::size_t(mesh)].primitives) {
    triangles += p.indices.size() / 3;
    for (const auto& v : p.positions) box.grow(glm::vec3(world * glm::vec4(v, 1.0f)));
  }
  return triangles;
}

// What the level's mesh instances are at time t, computed without the exporter.
struct Expected {
  std::size_t triangles = 0;
  std::size_t instances = 0;  // asset nodes with a mesh
  Box bounds;
  std::map<std::string, Box> entityBounds;  // by entity id
};

inline Expected expectedInstances(const scene::Level& lvl, double t) {
  ecs::Registry registry;
  const auto entities = scene::instantiate(lvl, registry);
  scene::motionSystem(registry, t);
  anim::attachAnimators(registry, cookCache());  // node-animated props play their clips (issue 12)
  anim::animationSystem(registry, t);
  scene::transformSystem(registry);
  Expected out;
  for (std::size_t i = 0; i < entities.size(); ++i) {
    const auto* ref = registry.tryGet<scene::MeshRef>(entities[i]);
    if (!ref) continue;
    const asset::CookedAsset a = asset::loadOrCook(ref->asset, cookCache());
    const glm::mat4 world = registry.get<scene::WorldTransform>(entities[i]).matrix;
    Box& entityBox = out.entityBounds[lvl.entities[i].id];
    const auto* pose = registry.tryGet<anim::Pose>(entities[i]);
    // Recursive walk of the default scene (the test levels name no node).
    auto walk = [&](auto&& self, int n, const glm::mat4& parent) -> void {
      const glm::mat4 m = parent * (pose ? pose->local[std::size_t(n)] : localOf(a.nodes[std::size_t(n)]));
      if (a.nodes[std::size_t(n)].mesh >= 0) {
        out.triangles += addMesh(a, a.nodes[std::size_t(n)].mesh, m, entityBox);
        ++out.instances;
      }
      for (int c : a.nodes[std::size_t(n)].children) self(self, c, m);
    };
    for (int r : a.rootNodes) walk(walk, r, world);
    out.bounds.grow(entityBox);
  }
  return out;
}

// One node of a re-imported file, with its world matrix and the root (entity) it hangs under.
struct Placed {
  int node = -1;
  std::string name;
  std::string root;
  glm::mat4 world{1.0f};
};

inline std::vector<Placed> placedNodes(const asset::CookedAsset& a) {
  std::vector<Placed> out;
  auto walk = [&](auto&& self, int n, const glm::mat4& parent, const std::string& root) -> void {
    const glm::mat4 m = parent * localOf(a.nodes[std::size_t(n)]);
    out.push_back({n, a.nodes[std::size_t(n)].name, root, m});
    for (int c : a.nodes[std::size_t(n)].children) self(self, c, m, root);
  };
  for (int r : a.rootNodes) walk(walk, r, glm::mat4(1.0f), a.nodes[std::size_t(r)].name);
  return out;
}

// Triangles and bounds of every mesh node of a re-imported file (optionally under one root).
struct Imported {
  std::size_t triangles = 0;
  std::size_t instances = 0;
  Box bounds;
};

inline Imported importedInstances(const asset::CookedAsset& a, const std::string& root = {}) {
  Imported out;
  for (const auto& p : placedNodes(a)) {
    if (!root.empty() && p.root != root) continue;
    if (a.nodes[std::size_t(p.node)].mesh < 0) continue;
    out.triangles += addMesh(a, a.nodes[std::size_t(p.node)].mesh, p.world, out.bounds);
    ++out.instances;
  }
  return out;
}

}  // namespace bounce::scene_export::test
