#pragma once
// The shadow rays of incident::SceneVisibility (incident.hpp), with what blocks them left to the
// caller: RTF's bouncing step traces them through the static level AND the other posed objects
// (engine/gi/rtf/occluders.hpp), and its room shadows through the posed objects alone.
#include <memory>
#include <type_traits>

#include <glm/glm.hpp>

#include "engine/render/gpu_types.hpp"

namespace bounce::gi::incident {

// `occluded(o, d, tMax)`: is anything on the ray from origin o along unit direction d before the
// light at distance tMax (∞ for a directional light)?
// A non-owning reference to the caller's test (the callable outlives the traceVisibility call it is
// passed to): no std::function, whose capture of more than 16 bytes allocates on every call — RTF's
// room shadows make two calls per hit per light per direction per proxy each frame (session-18 review).
class RayTest {
 public:
  template <class F>
    requires(std::is_invocable_r_v<bool, F&, glm::vec3, glm::vec3, float> &&
             !std::is_same_v<std::remove_cvref_t<F>, RayTest>)
  RayTest(F&& f)  // NOLINT: implicit, as std::function's
      : object_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
        call_([](void* o, glm::vec3 a, glm::vec3 d, float t) {
          return bool((*static_cast<std::remove_reference_t<F>*>(o))(a, d, t));
        }) {}
  bool operator()(glm::vec3 o, glm::vec3 d, float tMax) const { return call_(object_, o, d, tMax); }

 private:
  void* object_;
  bool (*call_)(void*, glm::vec3, glm::vec3, float);
};
// The fraction in [0, 1] of SceneVisibility::visible's rays from the receiver (the sphere of `radius`
// around p; 0: the point p, one ray) to `light` that `occluded` does not block.
float traceVisibility(const render::LightGpu& light, glm::vec3 p, float radius, const RayTest& occluded);

}  // namespace bounce::gi::incident
