#pragma once
// SL as a technique of the table (engine/gi/technique.hpp): dynamic entities with an `sl` component
// and a mesh take part; one bake job per such entity (its sphere set, cache kind "sl"); the session
// runtime loads the sets through the cache and poses the SLs every frame (update.hpp, §7.1).
//
// The runtime's node (node.hpp) adds pass 1 ("sl.intensity", compute) and pass 2 ("sl", deferred)
// each frame. The indirect light of pass 1's samples is the probes' (Services::probeVolume, sampled
// at each SL's posed centre) when the probes run, else the level's background as a constant
// environment (as DNRT's c_j).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/sl/bake.hpp"
#include "engine/gi/sl/node.hpp"
#include "engine/gi/sl/update.hpp"
#include "engine/gi/technique.hpp"
#include "engine/ref/reference_scene.hpp"

namespace bounce::gi::sl {

const Technique& technique();

// The bake settings a level component asks for (sphere count and order; the rest the defaults).
BakeSettings settingsFrom(const scene::Sl& component);

// What one entity's bake reads: its mesh in its local frame (dnrt::objectScene: the same expansion,
// materials and textures the reference tracer sees) and its skin in the same vertex order.
struct ObjectInput {
  ref::SceneDesc object;
  Skin skin;
};
ObjectInput objectInput(ecs::Registry& registry, ecs::Entity entity, const ref::ReferenceAssets& assets);

// Content key: every mesh, material, texture and skin byte, the settings and the baker/format version.
std::string cacheKey(const ObjectInput& input, const BakeSettings& settings);
// `cacheDir`/sl-<key>.slset
std::filesystem::path cachePath(const std::string& key, const std::filesystem::path& cacheDir);
std::filesystem::path cacheFolder();  // cacheDir("sl")


// One entity taking part, as the session holds it.
struct Participant {
  ecs::Entity entity{};
  std::string name;
  scene::Sl component;
  SphereSet set;
  std::unique_ptr<SpherePoser> poser;
  std::vector<PosedSphere> spheres;  // this frame's (update)
};

class SessionRuntime final : public TechniqueRuntime {
 public:
  // Loads (baking on a miss) every participant's sphere set and poses it at the registry's state.
  SessionRuntime(ecs::Registry& registry, const std::filesystem::path& cookCache, const std::filesystem::path& cacheDir);
  void update(const FrameUpdate& frame) override;
  // The GPU side (node.hpp): without it (CPU tests) node() adds nothing. Pass order = the highest
  // of the components' orders; blocking and influence = the first participant's (one pass shades
  // every SL).
  void enableGpu(SessionContext& sc);
  render::Renderer::GraphNode node() override;
  const std::vector<Participant>& participants() const { return participants_; }
  // "sl update: S spheres on E entities, CPU median X ms over F frames (§7.1 poses)": what
  // `bounce profile` prints after its table (the sl_update_ms).
  std::vector<std::string> profileLines() const override;
  // The median CPU ms of update() so far (NaN before the first after construction): sl_update_ms.
  double medianUpdateMs() const;
  // Whether pass 2 reads the blocked light from the direction maps ("blocked_read": "map" as run).
  bool readsDirectionMaps() const { return blockedMap_; }

 private:
  ref::ReferenceAssets assets_;  // the cooked assets the posers read (skins, node hierarchy)
  std::vector<Participant> participants_;
  std::vector<double> updateMs_;  // CPU time of each update() (the first, at construction, excluded)
  std::unique_ptr<Node> node_;
  const incident::IndirectSource* indirect_ = nullptr;  // the session light's: probes or the background
  std::vector<PosedSphere> posed_;                      // concatenated over participants (update)
  std::vector<std::uint32_t> objects_;
  std::vector<incident::RadianceSH> indirectSh_;
  std::vector<incident::DirectionMap> indirectMaps_;  // "blocked_read": "map" only
  // "blocked_read": "map" as run: the level's, unless the maps' uniform block exceeds the device's
  // maxUniformBufferRange (enableGpu warns and reads the SH).
  bool blockedMap_ = false;
};

}  // namespace bounce::gi::sl
