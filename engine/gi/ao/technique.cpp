#include "engine/gi/ao/technique.hpp"

namespace bounce::gi::ao {
namespace {

class AoTechnique final : public Technique {
 public:
  explicit AoTechnique(Kind kind) : kind_(kind) {}
  scene::Effect effect() const override { return kind_ == Kind::Ssao ? scene::Effect::Ssao : scene::Effect::Hbao; }
  // Screen space: whatever the frame draws is occluded and occludes.
  bool takesPart(const LevelContext&, std::string*) const override { return true; }
  std::unique_ptr<TechniqueRuntime> create(SessionContext& sc) const override {
    return std::make_unique<Node>(sc.ctx, sc.renderer.pipelines(), kind_);
  }
  // The DNRT paper's baselines (§6.4): screen-space AO darkening the probes' indirect light around
  // every object, dynamic ones included. Same probes as the DNRT rows (level defaults).
  void accuracyRows(std::vector<AccuracyRow>& rows) const override {
    const char* kind = kindName(kind_);
    AccuracyRow r;
    r.technique = kind;
    r.setting = "radius=0.1m;ref=all";
    r.effects = {"direct", "shadows", "probes", kind};
    r.passes = {"shadow", "lighting", kind, "probes"};
    r.optionalPasses = {"probes.tiles"};  // per frame only when the probes are relit
    rows.push_back(std::move(r));
  }
  std::vector<std::string> passes() const override { return {kindName(kind_)}; }

 private:
  Kind kind_;
};

}  // namespace

const Technique& technique(Kind kind) {
  static const AoTechnique ssao(Kind::Ssao), hbao(Kind::Hbao);
  return kind == Kind::Ssao ? ssao : hbao;
}

}  // namespace bounce::gi::ao
