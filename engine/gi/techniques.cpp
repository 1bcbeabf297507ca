// THE list of GI techniques: Session, `bounce bake`, `bounce accuracy`, `bounce profile` and the
// play keys iterate it and name none of them. Order = node order (technique.hpp). Adding a
// technique: its folder engine/gi/<name>/ with a technique() like these, and one line here.
#include "engine/gi/ao/technique.hpp"
#include "engine/gi/dnrt/technique.hpp"
#include "engine/gi/probes/technique.hpp"
#include "engine/gi/rtf/technique.hpp"
#include "engine/gi/sl/technique.hpp"
#include "engine/gi/technique.hpp"
#include "engine/gi/vlm/technique.hpp"

namespace bounce::gi {

const std::vector<const Technique*>& techniques() {
  static const std::vector<const Technique*> table = {
      &ao::technique(ao::Kind::Ssao),  // first: a later node may read "ao.term"
      &ao::technique(ao::Kind::Hbao),
      &probes::technique(),  // the static indirect light; Services::probeVolume for the ones below
      &dnrt::technique(),    // what the dynamic objects add and take away (c_j from the probes)
      &vlm::technique(),
      &sl::technique(),  // spherical lights (issue 13): bake, poses and the GPU passes
      &rtf::technique(),  // radiance transfer fields (issue 14): multi-bounce between the dynamic objects
  };
  return table;
}

const Technique* findTechnique(scene::Effect effect) {
  for (const Technique* t : techniques())
    if (t->effect() == effect) return t;
  return nullptr;
}

}  // namespace bounce::gi
