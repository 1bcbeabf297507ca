#pragma once
// DNRT as a technique of the table (engine/gi/technique.hpp): entities with a `dnrt` component and
// a mesh take part; one bake job per such entity (its field); the runtime of runtime.hpp with c_j
// from the incident-light service: the probes (Services::probeVolume) when they run, else the
// level's background, plus the frame's lights with their visibility traced against the level's
// static geometry (incident::SceneVisibility; the object itself is not in it).
#include <memory>

#include "engine/gi/dnrt/runtime.hpp"
#include "engine/gi/technique.hpp"

namespace bounce::gi::dnrt {

const Technique& technique();

// What a session holds for DNRT: the runtime and what it reads from (the CPU copies of the assets
// its bakes start from, the probes as c_j source).
class SessionRuntime final : public TechniqueRuntime {
 public:
  explicit SessionRuntime(SessionContext& sc);
  render::Renderer::GraphNode node() override { return runtime_->node(); }
  Runtime& runtime() { return *runtime_; }

 private:
  ref::ReferenceAssets assets_;
  // Shared: the probes node's fused-mode hook holds a weak reference (either runtime may go first).
  std::shared_ptr<Runtime> runtime_;
};

}  // namespace bounce::gi::dnrt
