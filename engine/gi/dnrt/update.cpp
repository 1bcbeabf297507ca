#include "engine/gi/dnrt/runtime.hpp"
// DNRT's per-frame CPU work (the "update" of the one technique shape): which objects the frame
// draws, their placement (§5.2.1: centre o, radius, rotation into the object's frame) and their c_j
// from the incident-light service, packed for the node. The bake and upload are in runtime.cpp, the
// GPU passes in node.cpp.

#include <algorithm>

#include "engine/gi/dnrt/evaluate.hpp"

namespace bounce::gi::dnrt {

incident::RadianceSH Runtime::incidentSH(glm::vec3 centre, float radius, std::span<const render::LightGpu> lights,
                                         const incident::BandWindow& window,
                                         incident::RadianceSH* lightsPart) const {
  return incident_.radianceSH(centre, radius, lights, window, lightsPart);
}

std::vector<NodeObject> Runtime::objectsFor(const render::RenderWorld& world) const {
  std::vector<NodeObject> out;
  for (const Object& o : objects_) {
    if (!registry_.valid(o.entity)) continue;
    const bool drawn = std::any_of(world.draws.begin(), world.draws.end(),
                                   [&](const render::DrawItem& d) { return d.entity == o.entity.index(); });
    const auto* placed = registry_.tryGet<scene::WorldTransform>(o.entity);
    if (!drawn || !placed) continue;
    // A world scale place() refuses (through 0 mid-motion, gi::tryPlace): the object has no size this
    // frame, so its field adds and takes away nothing; no pass breaks.
    const std::optional<Placement> maybe = tryPlace(o.field, placed->matrix);
    if (!maybe) continue;
    const Placement& pl = *maybe;
    const auto* component = registry_.tryGet<scene::Dnrt>(o.entity);
    // App. B.2's improved anti-radiance divides band 2 by Â_2 (×4) and so amplifies the ringing of
    // a lamp's truncated lobe: its fields get the lights' SH Hanning-windowed (incident.hpp). Not
    // when the lights are out of the anti-radiance (occlusionTextures): the lights then reach only
    // t_j, which no band factor scales (measured: cornell-1's improved rows, indirect-only
    // 0.487–0.577 windowed, 0.471–0.566 not; README "DNRT with the relit probes, session 10").
    const bool windowed = o.field.settings.antiRadiance == AntiRadiance::Improved && !o.occlusionTextures;
    incident::RadianceSH lights{};  // the lights' part of L alone (the occlusion term's c_j, below)
    const incident::RadianceSH L = incidentSH(pl.centreWorld, pl.radiusWorld, world.lights,
                                              windowed ? incident::kHanningWindow : incident::kNoWindow,
                                              o.occlusionTextures ? &lights : nullptr);
    out.push_back({o.textures.get(), packObject(o.field, placed->matrix, L, o.entity.index()), o.name,
                   component && component->intrusion, component ? component->mode : Mode::Box});
    if (o.occlusionTextures) {
      // The lights' part of c_j (the service's lightsSH, unwindowed as L's is here: the very numbers L
      // summed, not L − indirect), negated: with the field's −k_j it adds back Σ_j c_j^lights k_j, so
      // the anti-radiance is the indirect light's only.
      incident::RadianceSH minusLights = lights;
      for (glm::vec3& c : minusLights) c = -c;
      out.back().occlusion = o.occlusionTextures.get();
      out.back().occlusionData = packObject(*o.occlusion, placed->matrix, minusLights, o.entity.index());
    }
  }
  return out;
}

}  // namespace bounce::gi::dnrt
