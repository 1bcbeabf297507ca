#include "engine/anim/animator.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/anim/sampling.hpp"
#include "engine/core/error.hpp"
#include "engine/scene/asset_instances.hpp"

namespace bounce::anim {

namespace {

double positiveMod(double x, double m) {
  const double r = std::fmod(x, m);
  return r < 0.0 ? r + m : r;
}

std::string clipList(const asset::CookedAsset& a) {
  std::string out;
  for (std::size_t i = 0; i < a.animations.size(); ++i)
    out += (i ? ", " : "") + (a.animations[i].name.empty() ? "#" + std::to_string(i) : a.animations[i].name);
  return out.empty() ? "none: the asset has no animations" : out;
}

}  // namespace

std::string Animator::clipName() const {
  if (clip < 0) return "rest pose";
  const std::string& n = asset->animations[std::size_t(clip)].name;
  return n.empty() ? "clip " + std::to_string(clip) : n;
}

float clipTime(scene::PlayMode mode, float duration, double u) {
  if (!(duration > 0.0f)) return 0.0f;
  const double d = duration;
  switch (mode) {
    case scene::PlayMode::Once: return float(std::clamp(u, 0.0, d));
    case scene::PlayMode::PingPong: {
      const double w = positiveMod(u, 2.0 * d);
      return float(w <= d ? w : 2.0 * d - w);
    }
    case scene::PlayMode::Loop: break;
  }
  return float(positiveMod(u, d));
}

void attachAnimators(ecs::Registry& registry, const std::filesystem::path& cookCache) {
  std::map<std::string, std::shared_ptr<const asset::CookedAsset>> cooked;
  std::vector<std::pair<ecs::Entity, Animator>> found;  // emplaced after the view (no storage change while iterating)
  registry.view<scene::MeshRef>().each([&](ecs::Entity e, scene::MeshRef& ref) {
    auto& a = cooked[scene::assetKey(ref)];
    if (!a) a = std::make_shared<const asset::CookedAsset>(scene::cookForRef(ref, cookCache));
    if (a->animations.empty() && a->skins.empty()) return;
    Animator an;
    an.asset = a;
    an.clip = a->animations.empty() ? -1 : 0;
    if (const auto* c = registry.tryGet<scene::AnimationClip>(e)) {
      an.speed = c->speed;
      an.mode = c->mode;
      an.phaseS = c->phaseS;
      if (!c->enabled) {
        an.clip = -1;
      } else if (c->clip) {
        const std::string where = c->pointer + "/clip";
        if (const auto* index = std::get_if<std::uint32_t>(&*c->clip)) {
          if (*index >= a->animations.size())
            throwInputError(c->file, where, "clip " + std::to_string(*index) + " does not exist in " + ref.asset.filename().string(),
                            "an index below " + std::to_string(a->animations.size()) + " (clips: " + clipList(*a) + ")");
          an.clip = int(*index);
        } else {
          const std::string& name = std::get<std::string>(*c->clip);
          auto it = std::find_if(a->animations.begin(), a->animations.end(), [&](const auto& x) { return x.name == name; });
          if (it == a->animations.end())
            throwInputError(c->file, where, "no clip named \"" + name + "\" in " + ref.asset.filename().string(),
                            "one of: " + clipList(*a));
          an.clip = int(it - a->animations.begin());
        }
      }
    }
    found.emplace_back(e, std::move(an));
  });
  for (auto& [e, an] : found) registry.emplaceOrReplace<Animator>(e, std::move(an));
}

void animationSystem(ecs::Registry& registry, double t) {
  std::vector<std::pair<ecs::Entity, Pose>> poses;
  registry.view<Animator>().each([&](ecs::Entity e, Animator& an) {
    const float duration = an.clip >= 0 ? clipDuration(an.asset->animations[std::size_t(an.clip)]) : 0.0f;
    an.clipTime = clipTime(an.mode, duration, double(an.phaseS) + double(an.speed) * t);
    Pose* existing = registry.tryGet<Pose>(e);
    if (existing) {
      evaluatePose(*an.asset, an.clip, an.clipTime, *existing);
    } else {
      Pose p;
      evaluatePose(*an.asset, an.clip, an.clipTime, p);
      poses.emplace_back(e, std::move(p));
    }
  });
  for (auto& [e, p] : poses) registry.emplaceOrReplace<Pose>(e, std::move(p));
}

void cycleClip(Animator& an) {
  const int n = int(an.clipCount());
  if (n == 0) return;
  an.clip = an.clip + 1 >= n ? -1 : an.clip + 1;
}

}  // namespace bounce::anim
