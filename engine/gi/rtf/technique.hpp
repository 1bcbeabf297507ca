#pragma once
// RTF as a technique of the table (engine/gi/technique.hpp; issue 14): entities with an `rtf`
// component and a mesh take part; one bake job per such entity (its field, cache kind "rtf",
// keyed by ref::hashGeometry of the object + the settings, bake.hpp cacheKey); the session runtime
// loads (or bakes) every field, uploads it for the ξ pass (xi_pass.hpp) and adds the node of
// node.hpp, whose setup runs the bouncing step (update.hpp) for the frame's lights.
#include <memory>
#include <string>
#include <vector>

#include "engine/gi/rtf/field.hpp"
#include "engine/gi/rtf/node.hpp"
#include "engine/gi/rtf/update.hpp"
#include "engine/gi/technique.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/components.hpp"

namespace bounce::gi::rtf {

const Technique& technique();

// The bake settings of a level component (the parser has checked the ranges). selfBounces stays
// at the library default (2), the rest follows the component.
FieldSettings settingsFrom(const scene::Rtf& c);
// <cache>/rtf: where the runtime and `bounce bake` keep the fields.
std::filesystem::path cacheFolder();

// What a session holds for RTF.
class SessionRuntime final : public TechniqueRuntime {
 public:
  // `cacheDir`: where fields are loaded from / baked into (tests pass their own).
  SessionRuntime(SessionContext& sc, const std::filesystem::path& cacheDir);
  render::Renderer::GraphNode node() override;
  std::vector<std::string> profileLines() const override;
  using TechniqueRuntime::update;  // the per-frame hook, beside the accessor below
  const Update& update() const { return *update_; }
  // Baked this run (the others came from the cache).
  std::size_t bakedCount() const { return baked_; }

 private:
  std::unique_ptr<Update> update_;
  std::vector<std::unique_ptr<XiPass>> xi_;  // per participant
  std::unique_ptr<Node> node_;
  std::uint32_t step_ = 1;  // G-buffer pixels per shaded sample per axis: the level's "rtf": {"resolution"}
  std::size_t baked_ = 0;
};

}  // namespace bounce::gi::rtf
