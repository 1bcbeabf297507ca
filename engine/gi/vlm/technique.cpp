#include "engine/gi/vlm/technique.hpp"

#include <cstdio>

#include "engine/gi/vlm/node.hpp"
#include "engine/gi/vlm/vlm_mesh.hpp"

namespace bounce::gi::vlm {
namespace {

class VlmTechnique final : public Technique {
 public:
  scene::Effect effect() const override { return scene::Effect::Vlm; }

  bool takesPart(const LevelContext& lc, std::string* why) const override {
    if (!collectVlms(lc.registry, lc.cookCache).empty()) return true;
    if (why) *why = "no entity has a vlm component or a mesh with extras.bounce_vlm";
    return false;
  }

  std::unique_ptr<TechniqueRuntime> create(SessionContext& sc) const override {
    return std::make_unique<Runtime>(sc.ctx, sc.renderer.pipelines(), sc.registry, settingsFrom(sc.level.vlm),
                                     sc.cookCache, sc.renderer.frames().framesInFlight());
  }

  // Virtual Light Meshes (issue 5 §7): the thesis's range parameter (Fig. 5.6: too small a range
  // leaves blocky cut-offs) × candidates per cell K (Table 5.3), on top of direct light. A VLM
  // simulates exactly one diffuse bounce (§3.6), so it is compared with the one-bounce reference.
  // Range and K reach the grid through the level's "vlm" settings.
  void accuracyRows(std::vector<AccuracyRow>& rows) const override {
    for (const double range : {1.5, 2.5, 3.5, 4.5})
      for (const int k : {10, 20, 30, 60}) {
        AccuracyRow r;
        r.technique = "vlm";
        char setting[96];
        std::snprintf(setting, sizeof setting, "range=%g;k=%d;ref=1bounce", range, k);
        r.setting = setting;
        r.effects = {"direct", "shadows", "vlm"};
        r.referenceBounces = 1;
        r.passes = {"shadow", "lighting", "vlm.lights", "vlm"};
        r.configure = [range, k](scene::Level& level) {
          level.vlm.range = float(range);
          level.vlm.k = k;
        };
        rows.push_back(std::move(r));
      }
  }

  std::vector<std::string> passes() const override { return {"vlm.lights", "vlm"}; }
};

}  // namespace

const Technique& technique() {
  static const VlmTechnique t;
  return t;
}

}  // namespace bounce::gi::vlm
