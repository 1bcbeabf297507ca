#include "engine/gi/rtf/update.hpp"
// The bouncing step per frame and the shading records (update.hpp). The math is evaluate.cpp's; this
// file only gathers the frame's objects and folds what the fragment shader would otherwise recompute
// per pixel (the product matrix of the indirect light, the q mapping) into the records.

#include <algorithm>
#include <utility>
#include <bit>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/gi/rtf/overlap.hpp"
#include "engine/gi/rtf/room_shadows.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "engine/scene/components.hpp"

namespace bounce::gi::rtf {

std::vector<std::size_t> nearestOthers(std::span<const glm::vec3> centres, std::size_t o, std::size_t count) {
  std::vector<std::pair<float, std::size_t>> others;
  for (std::size_t b = 0; b < centres.size(); ++b)
    if (b != o) others.emplace_back(glm::length(centres[b] - centres[o]), b);
  std::sort(others.begin(), others.end());  // by distance, then index
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < std::min(count, others.size()); ++k) out.push_back(others[k].second);
  return out;
}

RtfObjectGpu packObject(const Field& f, const glm::mat4& world, const ShRgb& indirect, std::uint32_t entity, int shCount,
                        float reach) {
  if (shCount != 4 && shCount != 9) throw InternalError("rtf::packObject: SH count " + std::to_string(shCount) + " (4 or 9)");
  const Placement p = place(f, world);
  RtfObjectGpu o{};
  for (glm::uvec4& ids : o.onObject) ids = glm::uvec4(kRtfNoEntity);  // no other object: Update::frame fills them
  // q = (worldToLocal·p − centre)/η: rows of the affine map.
  for (int r = 0; r < 3; ++r) {
    glm::vec4 row(p.worldToLocal[0][r], p.worldToLocal[1][r], p.worldToLocal[2][r], p.worldToLocal[3][r]);
    row.w -= f.centre[r];
    o.toQ[r] = row / f.radius;
  }
  // World → local directions: Mᵀ, a reflection for a mirrored object (gi::Placement), so the normal
  // rtf.frag rotates into the object frame is the local one.
  const glm::mat3 toLocal = glm::transpose(p.localToWorldDirections());
  for (int r = 0; r < 3; ++r) o.toLocal[r] = glm::vec4(toLocal[0][r], toLocal[1][r], toLocal[2][r], 0.0f);
  const FieldSettings& s = f.settings;
  const float dr = (s.outerRadius - s.innerRadius) / float(s.spheres - 1);
  // tailFade(): otherwise the field ends at r_N + Δr ((r_N/|q|)² with a ramp over its last quarter spacing).
  const bool tail = reach > s.outerRadius + dr;
  o.centreWorld = glm::vec4(p.centreWorld, (tail ? reach : s.outerRadius + dr) * p.radiusWorld);
  o.grid = glm::vec4(float(s.spheres), float(s.faceSize), s.innerRadius, s.outerRadius);
  o.ids = glm::uvec4(entity + 1u, std::uint32_t(shCount), std::bit_cast<std::uint32_t>(tail ? reach : 0.0f), 0u);
  // T per channel in the object frame (Eq. 10's occlusion, shade() in evaluate.cpp).
  const ShRgb L = rtf::toLocal(indirect, p);
  for (int c = 0; c < 3; ++c) {
    std::vector<float> Lc(kShCount);
    for (int k = 0; k < kShCount; ++k) Lc[std::size_t(k)] = L[std::size_t(k)][c];
    const std::vector<float> T = sh::productMatrix<float>(std::span<const float>(Lc), kShOrder);  // T[i·16 + j]
    for (int i = 0; i < 9; ++i) {
      const float a = float(sh::cosineLobeBand(i == 0 ? 0 : i < 4 ? 1 : 2) / math::kPi);
      for (int j = 0; j < kShCount; ++j) o.blocked[j * 9 + i][c] = a * T[std::size_t(i * kShCount + j)];
    }
  }
  return o;
}

std::vector<glm::vec4> blockedScale(const Field& f, const glm::mat4& world, const incident::IndirectSource& indirect,
                                    const ref::SceneBvh* staticScene) {
  const Placement pl = place(f, world);
  const glm::vec3 at = indirect.radianceSH(pl.centreWorld)[0];
  const FieldSettings& s = f.settings;
  const int per = samplesPerSphere(s);
  std::vector<glm::vec4> out(sampleCount(s), glm::vec4(1.0f));
  for (int rest = 0; rest < per; ++rest) {  // each ray from o, outward
    const glm::vec3 dir = pl.localToWorldDirections() * sampleDirection(s, std::size_t(rest));
    float hidden = std::numeric_limits<float>::infinity();  // distance along the ray to static geometry
    if (staticScene) {
      ref::Hit hit;
      if (staticScene->intersect(pl.centreWorld, dir, 0.0f, pl.radiusWorld * s.outerRadius * 1.001f, hit))
        hidden = glm::length(hit.position - pl.centreWorld);
    }
    glm::vec4 last(1.0f);
    for (int sphere = 0; sphere < s.spheres; ++sphere) {
      const std::size_t r = std::size_t(sphere * per + rest);
      const float dist = pl.radiusWorld * sphereRadius(s, sphere);
      if (dist < hidden) {
        const glm::vec3 l = indirect.radianceSH(pl.centreWorld + dist * dir)[0];
        for (int c = 0; c < 3; ++c) last[c] = at[c] > 1e-6f ? std::max(0.0f, l[c] / at[c]) : 1.0f;
      }
      out[r] = last;
    }
  }
  return out;
}

Update::Update(ecs::Registry& registry, std::vector<Participant> participants)
    : registry_(registry), participants_(std::move(participants)) {}

int Update::bounces() const {
  int b = 1;
  for (const Participant& p : participants_) b = std::max(b, p.bounces);
  return b;
}

FrameObjects Update::frame(std::span<const render::LightGpu> lights) {
  const auto start = std::chrono::steady_clock::now();
  FrameObjects out;
  out.bounces = bounces();
  std::vector<Object> objects;
  for (std::size_t i = 0; i < participants_.size(); ++i) {
    const Participant& p = participants_[i];
    if (!registry_.valid(p.entity)) continue;
    const auto* placed = registry_.tryGet<scene::WorldTransform>(p.entity);
    // A world scale place() refuses (through 0 mid-motion, gi::tryPlace): the object has no size this
    // frame, so it neither bounces, blocks nor shades (as if absent); no pass breaks.
    if (!placed || !tryPlace(p.field, placed->matrix)) continue;
    out.participant.push_back(i);
    objects.push_back({&p.field, placed->matrix, p.reach});
  }
  if (!objects.empty()) {
    // Bounce 0's source light per object: the service's; with occluders, a service per object whose
    // lights' visibility leaves that object's own mesh out (occluders.hpp).
    std::vector<PosedOccluders::Pose> poses;
    std::vector<PosedVisibility> visibility;
    std::vector<incident::Service> services;
    std::vector<LitSource> lit;
    std::vector<const incident::IndirectSource*> sources;
    const LitSource shared(service_, lights);
    // The lit source plus the room's lost lamp light at the point (room_shadows.hpp).
    struct Shadowed final : incident::IndirectSource {
      const incident::IndirectSource* lit;
      const ref::SceneBvh* level;
      const PosedOccluders* occluders;
      std::span<const PosedOccluders::Pose> poses;
      std::span<const render::LightGpu> lights;
      incident::RadianceSH radianceSH(glm::vec3 p) const override {
        return withRoomShadow(lit->radianceSH(p), roomShadow(*level, *occluders, poses, lights, p));
      }
    };
    std::vector<Shadowed> shadowed;
    if (occluders_) {
      for (std::size_t o = 0; o < objects.size(); ++o)
        if (auto p = occluders_->pose(out.participant[o], objects[o].world)) poses.push_back(*p);
      visibility.reserve(objects.size()), services.reserve(objects.size()), lit.reserve(objects.size());
      shadowed.reserve(objects.size());
      for (std::size_t o = 0; o < objects.size(); ++o) {
        visibility.emplace_back(level_, *occluders_, poses, out.participant[o]);
        services.push_back(service_);
        services.back().setVisibility(&visibility.back());
        lit.emplace_back(services.back(), lights);
        sources.push_back(&lit.back());
        if (surfaces_) {
          shadowed.push_back({});
          shadowed.back().lit = &lit.back(), shadowed.back().level = surfaces_, shadowed.back().occluders = occluders_.get();
          shadowed.back().poses = poses, shadowed.back().lights = lights;
          sources.back() = &shadowed.back();
        }
      }
    } else {
      sources.assign(objects.size(), &shared);
    }
    BounceResult b = bounce(objects, sources, out.bounces);
    out.proxyLight = std::move(b.proxyLight);
    out.bounceEnergy = std::move(b.bounceEnergy);
    const incident::ConstantEnvironment none(glm::vec3(0.0f));
    const incident::IndirectSource& indirect = service_.indirect() ? *service_.indirect() : none;
    for (std::size_t o = 0; o < objects.size(); ++o) {
      const Placement pl = place(*objects[o].field, objects[o].world);
      out.records.push_back(packObject(*objects[o].field, objects[o].world, sourceRadiance(indirect, pl.centreWorld),
                                       participants_[out.participant[o]].entity.index(), participants_[out.participant[o]].sh,
                                       objects[o].reach));
      // The objects' shared occlusion (overlap.hpp); the light is o's (packObject), unscaled where one object acts.
      out.shares.push_back(sharedOcclusion(objects, o));
    }
    // Which receivers are on another rtf object (rtf.frag picks the field's on-object X there): the entity
    // index + 1 of the kRtfOnObjectIds other objects nearest to each one (centre distance, ties by index).
    std::vector<glm::vec3> centres;
    for (const Object& ob : objects) centres.push_back(place(*ob.field, ob.world).centreWorld);
    for (std::size_t o = 0; o < objects.size(); ++o) {
      RtfObjectGpu& r = out.records[o];
      const std::vector<std::size_t> near = nearestOthers(centres, o, kRtfOnObjectIds);
      for (std::size_t k = 0; k < near.size(); ++k)
        r.onObject[k / 4][int(k % 4)] = participants_[out.participant[near[k]]].entity.index() + 1u;
    }
  }
  bounceMs_.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  return out;
}

}  // namespace bounce::gi::rtf
