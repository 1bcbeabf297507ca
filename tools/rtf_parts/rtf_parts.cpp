// rtf_parts: what the dynamic objects' effect at a receiver is made of, by brute force against
// the reference path tracer, next to RTF's two terms from the CPU shading step (issue 14; README
// Results "RTF", "Where cornell-5's effect is missing").
//
// For every pixel of the level's camera at WxH whose first hit r is NOT a dynamic object (a receiver),
// N cosine-weighted directions ω about r's shading normal, each traced with the reference's light
// transport (ref::tracePathFrom, unlimited bounces) in the level WITH its dynamic objects (L_with)
// and WITHOUT them (L_without). The outgoing radiance the objects change at r splits exactly into
//   interreflected = ρ·E[L_with(ω)   · 1(ω hits an object first)]    the light the objects send to r
//   blocked        = ρ·E[L_without(ω)· 1(ω hits an object first)]    the room's light they hide from r
//   room           = ρ·E[(L_with − L_without)(ω) · 1(ω misses them)] everything else: the room's own
//                    bounces of what the objects add and take away (their shadows on the floor, …)
// (ρ/π ∫ L cos dω = ρ·E[L] for cosine-weighted directions), plus the change of r's direct light
// (shadows), which the indirect-only mask of `bounce accuracy` leaves out. RTF models the first two:
//   rtf-interreflected, rtf-blocked = gi::rtf::shade() of the level's rtf objects (bounces 2, 9 SH)
//   (with TAIL: scene::Rtf::tail for every object) with the proxies lit as the session lights them (probes + the lamp through static geometry),
//   the blocked light = the probes' light at r (what shade() takes).
// and blocked-probes = ρ·E[L_probes(r, ω)·1(ω hits an object)]: the blocked term with the probes'
// SH radiance in place of the traced one (the light RTF's blocked term is made of).
// field.pfm: R = min over objects of |r − o|/R_fade (R_fade = (outer + Δr)·η: < 1 inside a field).
// The blocked term's light, four ways (issue 14, fifth pass; each object's term on its own and summed,
// as the GPU pass adds them): ρ/π E_n(Σ_s w_s s_s (u − V_s) ⊙ L) with Eq. 10's lookup weights w_s and
//   blocked-receiver  L = the probes' light at r, s = 1   (shade()'s light, per object)
//   blocked-shape-o   L = the light at o scaled per channel by L_00(r)/L_00(o), s = 1   (o's shape, r's level)
//   blocked-at-o      L = the light at o, s = 1   (the GPU before the third pass)
//   blocked-gpu       L = the light at o, s_s = overlap.hpp sharedOcclusion's s (the GPU pass as shipped)
//   blocked-level     L = the light at o, s_s = update.hpp blockedScale (the GPU before the seventh pass)
//   blocked-eq3       L = the light at o, s_s = Σ_k w_k L_00(χ_k)/L_00(o), Eq. 3's weights from the sample to the proxies
//   blocked-surface   L = the light at o, s_s = L_00(o + η d_s)/L_00(o), on the bounding sphere along the sample's ray
//
// The second inter-object bounce (issue 14, eighth pass; tools/rtf_bounce2.py reads them):
//   ref-via-other     ρ·E[ρ_A L(ω')·1(ω' from A's hit hits ANOTHER object B first)] over ω hitting object A:
//                     the part of ref-interreflected that came to A from the other objects (the reference's
//                     bounces ≥ 2 between the objects; 4 cosine directions ω' at A per ω, unlimited bounces)
//   ref-via-self      the same for ω' hitting A itself (self-interreflection, in RTF's transfer T)
//   rtf-interreflected-b1/-b3/-b4   shade()'s interreflected light at 1, 3 and 4 bounces
//   rtf-interreflected-engine-b1/-engine   shade()'s interreflected light at 1 and 2 bounces from the engine's own
//                     bouncing step (gi::rtf::Update with the objects as the lamp's occluders and the room shadows,
//                     as technique.cpp sets it up): what the GPU rows render (session 24)
//   rtf-interreflected-engine-add-b1/-add   the same with each object's field shaded on its own and added, as
//                     the GPU pass added them before session 24 (no nearer object's OOF over another's light,
//                     no w; Algorithm 1 has it)
//   rtf-interreflected-exact1/-exact2   a what-if: Algorithm 1 with each proxy's probe light scaled to the
//                     room's traced l = 0 there (below), at 1 and 2 bounces
// and per object on stderr: the reference's interreflected light via it and its part from the others, against
// RTF's (2 − 1)/1 via its field alone; at each proxy the reference's l = 0 radiance from the other objects
// (the level without the object, 6·16² directions × 4 paths) against RTF's second bounce (and bounces 2–4)
// there, the weight Eq. 10 puts on another object's samples inside it (V ≡ 0), and the room's traced l = 0
// (the level without any object) against the probes' there and at χ moved towards o
// (RTF_PARTS_PROXIES_ONLY=1: stop after those lines).
// ref-interreflected-hidden (issue 14, session 17): ρ·E[L_obj(ω)·1(ω hits an object behind the room's
//   first hit)]: the light objects send towards r that the room's geometry hides in the reference; RTF's field
//   has no room visibility and adds it (traced from just before the object's surface, its own random stream).
// RTF_PARTS_NEARER=1 (issue 14, session 24): the engine's interreflected light at every pixel, each object's field
//   added on its own, with ξ whole, ξ·w (overlap.hpp) and ξ ⊗ V_near per sample (nearer-*.pfm), then stop.
// RTF_PARTS_COVERAGE=1 (issue 14, session 24): per object, the pixels the shading pass covers against those whose
//   surface lies inside the field's sphere, in front of it and behind it (stderr), then stop.
// RTF_PARTS_FACES=N (issue 14, session 17): per object and face class, the light the objects' vertices send
//   out, RTF's transfer × the proxies' bounce-0 light (its lamp part and probes part) against the reference's
//   (direct and indirect, N cosine paths a vertex), and the albedo per vertex against the area mean
//   (RTF_PARTS_FACES_ONLY=1: stop after those lines).
// RTF_PARTS_TAP="J k B" (issue 14, ninth pass): at proxy k of object J, object B's Eq. 10 lookup tap by tap
// (sphere, weight, B's ξ l = 0 from its field and from a fresh uncompressed bake, V_0, the reference's l = 0
// from B at the sample's world position), per sphere Σ|ξ_0| uncompressed against the field's, and at tap 2
// the vertices the sample's hits take their transfer from.
//
// usage: rtf_parts LEVEL WIDTH HEIGHT DIRS_PER_AXIS OUT_DIR [FRAME [TAIL]]   (TAIL: scene::Rtf::tail τ for every object)
//   writes OUT_DIR/{ref-interreflected,ref-blocked,ref-room,blocked-probes,rtf-interreflected,
//   rtf-blocked,field,ref-interreflected-hidden,…}.pfm (outgoing radiance, rows top to bottom as bounce accuracy's images).
// A diagnostic, not a test: run by hand, numbers read with tools/rtf_parts.py.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "engine/anim/animator.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/incident/session_light.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/gi/rtf/bake.hpp"
#include "engine/gi/rtf/evaluate.hpp"
#include "engine/gi/rtf/overlap.hpp"
#include "engine/gi/rtf/technique.hpp"
#include "engine/gi/rtf/update.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "engine/math/sh_convolve.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/ref/reference.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/ref/tracer.hpp"
#include "engine/render/gpu_types.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"
#include "game/accuracy_level.hpp"

using namespace bounce;

namespace {

struct Posed {
  ecs::Registry registry;
  ref::ReferenceAssets assets;
  ref::SceneDesc desc;
};

// The level at `time` as the reference poses it (ref::renderReference, step 2).
void pose(const scene::Level& level, double time, const std::filesystem::path& cooked, Posed& p) {
  scene::instantiate(level, p.registry);
  scene::motionSystem(p.registry, time);
  anim::attachAnimators(p.registry, cooked);
  anim::animationSystem(p.registry, time);
  scene::transformSystem(p.registry);
  p.assets.load(p.registry, cooked);
  p.desc = ref::extractScene(p.registry, level, p.assets);
}

glm::vec3 albedoAt(const ref::SceneDesc& scene, const ref::Hit& hit) {
  const ref::RefMaterial& mat = scene.materials[hit.material];
  glm::vec3 a = mat.albedo;
  if (mat.albedoTexture >= 0) a *= scene.textures[std::size_t(mat.albedoTexture)].sample(hit.uv);
  return glm::clamp(a, 0.0f, 1.0f);
}

glm::vec3 offset(glm::vec3 p, glm::vec3 ng, glm::vec3 dir) {  // tracer.cpp offsetOrigin
  const float scale = std::max({1.0f, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return p + (glm::dot(dir, ng) >= 0.0f ? 1e-4f : -1e-4f) * scale * ng;
}

render::LightGpu lightGpu(const ref::RefLight& l) {  // GpuScene's makeLight from the tracer's light
  render::LightGpu g{};
  g.positionType = glm::vec4(l.position, float(l.type == ref::RefLightType::Directional ? 0 : l.type == ref::RefLightType::Point ? 1 : 2));
  g.directionRange = glm::vec4(l.direction, l.range);
  g.radiance = glm::vec4(l.radiance, 0.0f);
  g.cone = glm::vec4(l.cosOuter, l.cosInner, 0.0f, 0.0f);
  g.shadow = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
  return g;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: rtf_parts LEVEL WIDTH HEIGHT DIRS_PER_AXIS OUT_DIR [FRAME [TAIL]]\n");
    return 2;
  }
  const std::filesystem::path levelPath = argv[1], out = argv[5];
  const std::uint32_t W = std::uint32_t(std::atoi(argv[2])), H = std::uint32_t(std::atoi(argv[3]));
  const int spa = std::atoi(argv[4]);
  const std::uint32_t frame = argc > 6 ? std::uint32_t(std::atoi(argv[6])) : 0u;
  const float tail = argc > 7 ? float(std::atof(argv[7])) : 0.0f;  // scene::Rtf::tail τ for every object
  const double time = double(frame) * ref::kLevelFrameDt;
  const std::filesystem::path cooked = cacheDir("cooked");
  std::filesystem::create_directories(out);

  const scene::Level level = scene::loadLevel(levelPath);
  const std::set<std::string> dynamic = game::dynamicEntityIds(level);
  scene::Level propsLevel = level;  // the dynamic objects alone (and the camera): which rays hit one
  propsLevel.entities.clear();
  for (const auto& e : level.entities)
    if (dynamic.count(e.id) || e.camera) propsLevel.entities.push_back(e);
  Posed with, without, props;
  pose(level, time, cooked, with);
  pose(game::withoutDynamicEntities(level), time, cooked, without);
  pose(propsLevel, time, cooked, props);
  const ref::SceneBvh bvhWith(with.desc), bvhWithout(without.desc), bvhProps(props.desc);

  // RTF: the fields (cached by the level's bake), the bouncing step as the session runs it.
  gi::probes::LoadResult probeVolume = gi::probes::loadOrBake(level, cooked, cacheDir("probes"), gi::probes::settingsFrom(level));
  gi::incident::SessionLight light(level, cooked, &probeVolume.volume);
  gi::incident::Service service;
  service.setIndirect(&light.indirect());
  service.setVisibility(&light.lightVisibility());
  std::vector<render::LightGpu> lights;
  for (const ref::RefLight& l : with.desc.lights) lights.push_back(lightGpu(l));
  std::vector<gi::rtf::Field> fields;
  std::vector<gi::rtf::Object> objects;
  struct Reach { glm::vec3 centre; float radius; };
  std::vector<Reach> reach;
  std::vector<ecs::Entity> rtfEntities;
  with.registry.view<scene::Rtf>().each([&](ecs::Entity e, scene::Rtf&) { rtfEntities.push_back(e); });
  std::vector<std::unique_ptr<ref::SceneBvh>> objectBvh;  // each object alone, its local frame (blocked-oof-at-r)
  for (ecs::Entity e : rtfEntities) {
    const gi::rtf::FieldSettings s = gi::rtf::settingsFrom(with.registry.get<scene::Rtf>(e));
    ref::SceneDesc od = gi::dnrt::objectScene(with.registry, e, with.assets);
    fields.push_back(gi::rtf::bakeCached(od, s, gi::rtf::cacheFolder()));
    objectBvh.push_back(std::make_unique<ref::SceneBvh>(std::move(od)));
  }
  // Each rtf object alone, posed in the world (which object a ray hits first; issue 14, "Eighth pass").
  std::vector<std::unique_ptr<Posed>> alone;
  std::vector<std::unique_ptr<ref::SceneBvh>> aloneBvh;
  for (ecs::Entity e : rtfEntities) {
    scene::Level one = level;
    one.entities.clear();
    for (const auto& ent : level.entities)
      if (ent.id == with.registry.get<scene::Name>(e).id || ent.camera) one.entities.push_back(ent);
    alone.push_back(std::make_unique<Posed>());
    pose(one, time, cooked, *alone.back());
    aloneBvh.push_back(std::make_unique<ref::SceneBvh>(alone.back()->desc));
  }
  // The rtf object whose surface is hit first along o + t·w at t ≈ tHit (−1: none; object `skip` ignored).
  auto objectHit = [&](glm::vec3 o, glm::vec3 w, float tHit, int skip = -1) {
    int best = -1;
    float bestT = 1e30f;
    for (std::size_t k = 0; k < aloneBvh.size(); ++k) {
      ref::Hit h;
      if (int(k) == skip) continue;
      if (aloneBvh[k]->intersect(o, w, 0.0f, 1e30f, h) && h.t < bestT) best = int(k), bestT = h.t;
    }
    return best >= 0 && bestT <= tHit * (1.0f + 1e-4f) + 1e-5f ? best : -1;
  };
  // The cube-map directions the bake projects the OOF over (bake.cpp), at face 16.
  struct Dir { glm::vec3 w; std::array<double, gi::rtf::kShCount> y; double solidAngle; };
  std::vector<Dir> oofDirs;
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const glm::dvec3 w = sh::cubeTexelDirection(face, x, y, 16);
        Dir d{glm::vec3(w), {}, sh::cubeTexelSolidAngle(x, y, 16)};
        sh::evalBasis<double>(gi::rtf::kShOrder, w, d.y);
        for (auto& c : d.y) c *= sh::cubeTexelSolidAngle(x, y, 16);
        oofDirs.push_back(d);
      }
  for (std::size_t i = 0; i < rtfEntities.size(); ++i) {
    const auto& s = fields[i].settings;
    objects.push_back({&fields[i], with.registry.get<scene::WorldTransform>(rtfEntities[i]).matrix, gi::rtf::tailReach(fields[i], tail)});
    std::fprintf(stderr, "rtf_parts: object %zu: outermost sphere %.2f eta, tail %.3f: reach %.2f eta\n", i, s.outerRadius, tail,
                 objects.back().reach);
    const gi::rtf::Placement pl = gi::rtf::place(fields[i], objects.back().world);
    const float dr = (s.outerRadius - s.innerRadius) / float(s.spheres - 1);
    reach.push_back({pl.centreWorld, (s.outerRadius + dr) * pl.radiusWorld});  // field.pfm: the shipped fade's end
  }
  // RTF_PARTS_COVERAGE=1 (session 24): what the shading pass covers, per object — rtf.vert's octagon around the
  // field's sphere (radius (outer + Δr)·η, or the tail's reach), or the whole screen with the eye within 1.05 of
  // it — against the pixels whose surface lies inside that sphere (where the field is not zero), in front of it
  // and behind it; then stop.
  if (const char* cov = std::getenv("RTF_PARTS_COVERAGE"); cov && std::string(cov) == "1") {
    const glm::vec3 eye = ref::cameraRay(with.desc.camera, W, H, W / 2, H / 2).origin;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const gi::rtf::FieldSettings& fs = fields[i].settings;
      const gi::rtf::Placement pl = gi::rtf::place(fields[i], objects[i].world);
      const float dr = (fs.outerRadius - fs.innerRadius) / float(fs.spheres - 1);
      const float R = pl.radiusWorld * std::max(fs.outerRadius + dr, objects[i].reach), d = glm::length(pl.centreWorld - eye);
      const bool full = d < 1.05f * R;
      const float cosCone = full ? -1.0f : std::cos(std::asin(R / d) / std::cos(3.14159265f / 8.0f));
      std::size_t covered = 0, inside = 0, before = 0, behind = 0, none = 0;
      for (std::uint32_t y = 0; y < H; ++y)
        for (std::uint32_t x = 0; x < W; ++x) {
          const ref::CameraRay cam = ref::cameraRay(with.desc.camera, W, H, x, y);
          if (!full && glm::dot(cam.direction, (pl.centreWorld - eye) / d) < cosCone) continue;
          ++covered;
          ref::Hit hit;
          if (!bvhWith.intersect(cam.origin, cam.direction, cam.tMin, cam.tMax, hit)) { ++none; continue; }
          const float along = glm::dot(hit.position - pl.centreWorld, cam.direction);
          if (glm::length(hit.position - pl.centreWorld) < R) ++inside;
          else if (along < 0.0f) ++before;
          else ++behind;
        }
      std::fprintf(stderr, "rtf_parts: coverage %s: R %.3f m at %.3f m (%s): %zu px covered of %u; surface inside the field's sphere %zu, "
                   "in front of it %zu, behind it %zu, background %zu\n", with.registry.get<scene::Name>(rtfEntities[i]).id.c_str(), R, d,
                   full ? "full screen" : "octagon", covered, W * H, inside, before, behind, none);
    }
    return 0;
  }
  const gi::rtf::LitSource lit(service, lights);
  const gi::rtf::BounceResult bounced = gi::rtf::bounce(objects, lit, 2);
  const gi::rtf::BounceResult bounced1 = gi::rtf::bounce(objects, lit, 1);
  const gi::rtf::BounceResult bounced3 = gi::rtf::bounce(objects, lit, 3), bounced4 = gi::rtf::bounce(objects, lit, 4);
  // The engine's bouncing step as the session runs it (technique.cpp: gi::rtf::Update with the posed
  // objects as the lamp's occluders and the room shadows on the proxies' probe light), 1 and 2 bounces:
  // rtf-interreflected-engine-b1 / -engine (session 24: the GPU's second bounce against shade()'s on the
  // same proxy light; `bounced` above is the shared source without them).
  const auto engineBounce = [&](int bounces) {
    std::vector<gi::rtf::Participant> participants;
    std::vector<ref::SceneDesc> meshes;
    for (std::size_t i = 0; i < rtfEntities.size(); ++i) {
      gi::rtf::Participant p;
      p.entity = rtfEntities[i], p.name = with.registry.get<scene::Name>(rtfEntities[i]).id;
      p.field = fields[i], p.bounces = bounces, p.reach = objects[i].reach;
      participants.push_back(std::move(p));
      meshes.push_back(gi::dnrt::objectScene(with.registry, rtfEntities[i], with.assets));
    }
    gi::rtf::Update update(with.registry, std::move(participants));
    update.setIndirect(&light.indirect());
    update.setLightVisibility(&light.lightVisibility());
    update.setOccluders(std::make_unique<gi::rtf::PosedOccluders>(std::move(meshes)), &light.lightVisibility().bvh());
    update.setRoomShadows(&light.surfaces());
    gi::rtf::FrameObjects f = update.frame(lights);
    if (f.participant.size() != objects.size()) {
      std::fprintf(stderr, "rtf_parts: the engine's bouncing step placed %zu of %zu objects\n", f.participant.size(), objects.size());
      std::exit(1);
    }
    gi::rtf::BounceResult r;
    for (std::size_t i = 0; i < objects.size(); ++i) r.xi.push_back(gi::rtf::xiCache(*objects[i].field, f.proxyLight[i]));
    r.proxyLight = std::move(f.proxyLight);
    r.bounceEnergy = std::move(f.bounceEnergy);
    return r;
  };
  const gi::rtf::BounceResult engine1 = engineBounce(1), engine2 = engineBounce(2);
  std::vector<gi::rtf::BounceResult> engineSingle1, engineSingle2;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    engineSingle1.push_back({{engine1.proxyLight[k]}, {engine1.xi[k]}, {}});
    engineSingle2.push_back({{engine2.proxyLight[k]}, {engine2.xi[k]}, {}});
  }
  // RTF_PARTS_NEARER=1 (issue 14, session 24; a what-if): the engine's interreflected light at 1 and 2 bounces
  // at EVERY pixel (an object's own pixels skip its own field), each object's field shaded on its own and
  // added as the GPU pass does, three ways: nearer-add (ξ whole), nearer-w (ξ·w, overlap.hpp as shipped: w_on on the
  // pixels that see an object, w_off elsewhere) and
  // nearer-dir (ξ ⊗ V_near per sample: the SH product of ξ with the visibility of the objects nearer to the
  // sample, looked up there and turned into the object's frame — Algorithm 1 at the sample, direction by
  // direction); written as nearer-{add,w,dir}-b{1,2}.pfm, then stop.
  if (const char* nv = std::getenv("RTF_PARTS_NEARER"); nv && std::string(nv) == "1") {
    const auto dirXi = [&](std::size_t a, const std::vector<glm::vec3>& xi) {
      const gi::rtf::Field& f = *objects[a].field;
      const gi::rtf::FieldSettings& fs = f.settings;
      const gi::rtf::Placement pa = gi::rtf::place(f, objects[a].world);
      std::vector<glm::vec3> out = xi;
      std::vector<gi::rtf::OtherField> others;
      for (std::size_t b = 0; b < objects.size(); ++b)
        if (b != a) others.emplace_back(objects, a, b);
      const int per = gi::rtf::samplesPerSphere(fs);
      for (int sphere = 0; sphere < fs.spheres; ++sphere)
        for (int ray = 0; ray < per; ++ray) {
          const std::size_t smp = std::size_t(sphere) * std::size_t(per) + std::size_t(ray);
          const glm::vec3 dir = pa.localToWorldDirections() * gi::rtf::sampleDirection(fs, std::size_t(ray));
          const glm::vec3 p = pa.centreWorld + pa.radiusWorld * gi::rtf::sphereRadius(fs, sphere) * dir;
          std::vector<float> V(gi::rtf::kShCount, 0.0f);
          V[0] = gi::rtf::kUnitVisibility;
          bool any = false;
          for (const gi::rtf::OtherField& o : others) {
            if (!o.nearerThanA(p)) continue;
            gi::rtf::ShScalar vbA = o.hiddenInA(p);  // (1 − V_B), A's frame → V_B
            for (int j = 0; j < gi::rtf::kShCount; ++j) vbA[std::size_t(j)] = (j == 0 ? gi::rtf::kUnitVisibility : 0.0f) - vbA[std::size_t(j)];
            V = sh::product<float>(std::span<const float>(V), std::span<const float>(vbA), gi::rtf::kShOrder);
            any = true;
          }
          if (!any) continue;
          for (int c = 0; c < 3; ++c) {
            std::vector<float> x(gi::rtf::kShCount);
            for (int i = 0; i < gi::rtf::kShCount; ++i) x[std::size_t(i)] = xi[smp * gi::rtf::kShCount + std::size_t(i)][c];
            const std::vector<float> y = sh::product<float>(std::span<const float>(x), std::span<const float>(V), gi::rtf::kShOrder);
            for (int i = 0; i < gi::rtf::kShCount; ++i) out[smp * gi::rtf::kShCount + std::size_t(i)][c] = y[std::size_t(i)];
          }
        }
      return out;
    };
    // Three forms × two bounce counts of per-object results, and ξ·w_on (forms[3]: the shipped form's
    // factor for the pixels on an object since session 26; nearer-w takes it there, w_off elsewhere).
    std::vector<gi::rtf::BounceResult> forms[4][2];
    for (int bn = 0; bn < 2; ++bn) {
      const gi::rtf::BounceResult& eb = bn == 0 ? engine1 : engine2;
      for (std::size_t k = 0; k < objects.size(); ++k) {
        const gi::rtf::OcclusionShares sh = gi::rtf::sharedOcclusion(objects, k);
        std::vector<glm::vec3> xw = eb.xi[k], xon = eb.xi[k];
        for (std::size_t r = 0; r < sh.scale.size(); ++r)
          for (int i = 0; i < gi::rtf::kShCount; ++i) {
            xw[r * gi::rtf::kShCount + std::size_t(i)] *= sh.scale[r].w;
            xon[r * gi::rtf::kShCount + std::size_t(i)] *= sh.onObjects[r];
          }
        forms[3][bn].push_back({{eb.proxyLight[k]}, {xon}, {}});
        forms[0][bn].push_back({{eb.proxyLight[k]}, {eb.xi[k]}, {}});
        forms[1][bn].push_back({{eb.proxyLight[k]}, {xw}, {}});
        forms[2][bn].push_back({{eb.proxyLight[k]}, {dirXi(k, eb.xi[k])}, {}});
      }
    }
    std::vector<gpu::FloatImage> img(6);
    for (auto& im : img) im.width = W, im.height = H, im.rgb.assign(std::size_t(W) * H * 3, 0.0f);
    parallelFor(0, std::size_t(W) * H, [&](std::size_t pixel) {
      const ref::CameraRay cam = ref::cameraRay(with.desc.camera, W, H, std::uint32_t(pixel % W), std::uint32_t(pixel / W));
      ref::Hit hit;
      if (!bvhWith.intersect(cam.origin, cam.direction, cam.tMin, cam.tMax, hit)) return;
      const int own = objectHit(cam.origin, cam.direction, hit.t);  // the object this pixel sees, −1: none
      const glm::vec3 rho = albedoAt(with.desc, hit);
      glm::vec3 n = hit.shadingNormal;
      if (glm::dot(n, cam.direction) > 0.0f) n = -n;
      for (int form = 0; form < 3; ++form)
        for (int bn = 0; bn < 2; ++bn) {
          glm::vec3 sum(0.0f);
          for (std::size_t k = 0; k < objects.size(); ++k) {
            if (int(k) == own) continue;
            const std::span<const gi::rtf::Object> one(&objects[k], 1);
            const int f = form == 1 && own >= 0 ? 3 : form;  // nearer-w: w_on on an object's pixels
            sum += gi::rtf::shade(one, forms[f][bn][k], light.indirect(), hit.position, n, rho, -1, 9).interreflected;
          }
          float* px = img[std::size_t(form * 2 + bn)].rgb.data() + pixel * 3;
          px[0] = sum.x, px[1] = sum.y, px[2] = sum.z;
        }
    }, 16);
    const char* fn[6] = {"nearer-add-b1", "nearer-add-b2", "nearer-w-b1", "nearer-w-b2", "nearer-dir-b1", "nearer-dir-b2"};
    for (int i = 0; i < 6; ++i) gpu::writePfm(out / (std::string(fn[i]) + ".pfm"), img[std::size_t(i)]);
    std::fprintf(stderr, "rtf_parts: wrote the nearer-* what-if to %s\n", out.c_str());
    return 0;
  }
  for (std::size_t b = 0; b < engine2.bounceEnergy.size(); ++b)
    std::fprintf(stderr, "rtf_parts: engine's bouncing step: bounce %zu energy %.6g; the shared source's %.6g\n", b,
                 engine2.bounceEnergy[b], b < bounced.bounceEnergy.size() ? bounced.bounceEnergy[b] : 0.0);
  // Each object's field alone with its own bounced light, 1 and 2 bounces (per-object interreflected sums).
  std::vector<gi::rtf::BounceResult> single1, single2;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    single1.push_back({{bounced1.proxyLight[k]}, {bounced1.xi[k]}, {}});
    single2.push_back({{bounced.proxyLight[k]}, {bounced.xi[k]}, {}});
  }
  // Per object A and pixel: reference interreflected via A, its part that came to A from another object
  // (bounce ≥ 2 between the objects), RTF's interreflected via A at 1 and 2 bounces (Σ RGB).
  std::vector<std::array<double, 4>> perObject(std::size_t(W) * H * objects.size(), std::array<double, 4>{});
  std::fprintf(stderr, "rtf_parts: %zu rtf objects, %zu lights, %ux%u, %d² directions per pixel\n", objects.size(),
               lights.size(), W, H, spa);
  // How far apart the objects stand: a sphere of radius η_B at distance d lit like A sends A about
  // ρ_B (η_B/d)² of A's own irradiance, so Σ_B (η_B/d)² bounds the second bounce's share (× albedo).
  for (std::size_t a = 0; a < objects.size(); ++a) {
    const gi::rtf::Placement pa = gi::rtf::place(fields[a], objects[a].world);
    double share = 0.0, nearest = 1e30;
    for (std::size_t b = 0; b < objects.size(); ++b) {
      if (b == a) continue;
      const gi::rtf::Placement pb = gi::rtf::place(fields[b], objects[b].world);
      const double d = glm::length(pa.centreWorld - pb.centreWorld);
      share += double(pb.radiusWorld) * pb.radiusWorld / (d * d);
      nearest = std::min(nearest, d / pa.radiusWorld);
    }
    std::fprintf(stderr, "rtf_parts: object %zu: nearest other object at %.2f eta, sum of (eta_B/d)^2 %.4f\n", a, nearest, share);
  }
  // Per object: the proxies' light of bounce 1 (2 bounces − 1 bounce) against bounce 0 (Σ |L_00| over proxies).
  {
    const gi::rtf::BounceResult one = gi::rtf::bounce(objects, lit, 1);
    for (std::size_t a = 0; a < objects.size(); ++a) {
      double e0 = 0.0, e1 = 0.0;
      for (std::size_t p = 0; p < one.proxyLight[a].size(); p += gi::rtf::kShCount) {
        const glm::vec3 l0 = one.proxyLight[a][p], l1 = bounced.proxyLight[a][p] - one.proxyLight[a][p];
        e0 += double(l0.x + l0.y + l0.z), e1 += double(l1.x + l1.y + l1.z);
      }
      std::fprintf(stderr, "rtf_parts: object %zu (%s): proxies' L_00 bounce 0 %.4g, bounce 1 %.4g (%.3g of bounce 0)\n", a,
                   with.registry.get<scene::Name>(rtfEntities[a]).id.c_str(), e0, e1, e1 / std::max(e0, 1e-30));
    }
  }
  // RTF_PARTS_FACES=N (issue 14, session 17: where the first order is too bright): at every vertex p of
  // every rtf object, the light the object sends out, RTF's against the reference's, before any field:
  //   RTF  B_p = Σ_k Σ_j t_{p,k}^j L_k^j  (bake.hpp vertexTransfer with self-interreflection, Eq. 8 then
  //        Eq. 3's proxy weights; L_k = Algorithm 1's bounce-0 light at the proxies, the session's source:
  //        the probes' SH plus the lamp projected into the same 9 coefficients, occluded by the others' OOFs),
  //        split into the lamp's part (source − probes only) and the probes' part;
  //   ref  ρ_p/π E_lamp max(n·l, 0) V (shadow ray through the level) + ρ_p E[L_with] over N cosine paths
  //        (unlimited bounces, the level with every object): the reference's radiance leaving p.
  // Summed per object and face class (n·up > 0.5 up, < −0.5 down, else side; RGB mean, per vertex);
  // vertices within 2 mm of the floor plane y = 0 are left out (a face on the floor sends nothing).
  // Also per object the albedo two ways: the mean of the vertices' ρ (what the transfer holds) and the
  // area mean of the surface's ρ (the texture over each triangle, what the path tracer sees).
  // An object's albedo two ways (RGB mean): the mean of its vertices' ρ (the texture at each vertex's uv: what
  // bake.cpp's transfer holds) and the area mean of its surface's ρ (the texture over each triangle, 64 points
  // each: what the path tracer sees).
  const auto albedoMeans = [](const ref::SceneDesc& d) {
    double perVertex = 0.0, vertices = 0.0, areaRho = 0.0, area = 0.0;
    for (std::size_t mi = 0; mi < d.meshes.size(); ++mi) {
      const ref::RefMesh& m = d.meshes[mi];
      const ref::RefMaterial* mat = m.material < d.materials.size() ? &d.materials[m.material] : nullptr;
      const bool hasUv = m.uvs.size() == m.positions.size();
      const auto rhoAt = [&](glm::vec2 uv) {
        glm::vec3 a = mat ? mat->albedo : glm::vec3(1.0f);
        if (hasUv && mat && mat->albedoTexture >= 0 && std::size_t(mat->albedoTexture) < d.textures.size())
          a *= d.textures[std::size_t(mat->albedoTexture)].sample(uv);
        a = glm::clamp(a, glm::vec3(0.0f), glm::vec3(1.0f));
        return double(a.x + a.y + a.z) / 3.0;
      };
      for (std::size_t i = 0; i < m.positions.size(); ++i) perVertex += rhoAt(hasUv ? m.uvs[i] : glm::vec2(0.0f)), vertices += 1.0;
      math::Pcg32 rng = math::Pcg32::fromIndex(4242 + mi);
      for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const std::uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
        const double A = 0.5 * double(glm::length(glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a])));
        double sum = 0.0;
        for (int q = 0; q < 64; ++q) {
          float u = rng.nextFloat(), v = rng.nextFloat();
          if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
          sum += rhoAt(hasUv ? (1.0f - u - v) * m.uvs[a] + u * m.uvs[b] + v * m.uvs[c] : glm::vec2(0.0f));
        }
        areaRho += A * sum / 64.0, area += A;
      }
    }
    return std::array<double, 2>{perVertex / std::max(vertices, 1.0), areaRho / std::max(area, 1e-30)};
  };
  if (const char* fenv = std::getenv("RTF_PARTS_FACES")) {
    const int paths = std::max(1, std::atoi(fenv));
    const gi::rtf::BounceResult probesOnly = gi::rtf::bounce(objects, light.indirect(), 1);
    for (std::size_t J = 0; J < objects.size(); ++J) {
      const gi::rtf::Field& f = *objects[J].field;
      const ref::SceneDesc od = gi::dnrt::objectScene(with.registry, rtfEntities[J], with.assets);
      const ref::SceneDesc& wd = alone[J]->desc;  // the same meshes posed in the world
      const std::vector<glm::vec3> tv = gi::rtf::vertexTransfer(od, f.proxies, f.radius, f.settings);
      const std::size_t stride = f.proxies.size() * gi::rtf::kShCount;
      std::vector<glm::vec3> P, Nw, rhoV;
      for (std::size_t mi = 0; mi < wd.meshes.size() && mi < od.meshes.size(); ++mi) {
        const ref::RefMesh& m = wd.meshes[mi];
        const ref::RefMaterial* mat = m.material < wd.materials.size() ? &wd.materials[m.material] : nullptr;
        const auto rhoAt = [&](glm::vec2 uv, bool hasUv) {
          glm::vec3 a = mat ? mat->albedo : glm::vec3(1.0f);
          if (hasUv && mat && mat->albedoTexture >= 0 && std::size_t(mat->albedoTexture) < wd.textures.size())
            a *= wd.textures[std::size_t(mat->albedoTexture)].sample(uv);
          return glm::clamp(a, glm::vec3(0.0f), glm::vec3(1.0f));
        };
        const bool hasUv = m.uvs.size() == m.positions.size();
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
          P.push_back(m.positions[i]);
          Nw.push_back(glm::normalize(i < m.normals.size() ? m.normals[i] : glm::vec3(0, 1, 0)));
          rhoV.push_back(rhoAt(hasUv ? m.uvs[i] : glm::vec2(0.0f), hasUv));
        }
      }
      if (tv.size() != P.size() * stride) {
        std::fprintf(stderr, "rtf_parts: faces: object %zu: %zu transfer rows against %zu world vertices, skipped\n", J, tv.size() / stride, P.size());
        continue;
      }
      // classes: 0 up, 1 side, 2 down; parts: rtf lamp, rtf probes, ref direct, ref indirect, count
      double acc[3][5] = {};
      std::vector<std::array<double, 4>> perV(P.size());
      parallelFor(0, P.size(), [&](std::size_t p) {
        double rl = 0.0, rp = 0.0;
        for (std::size_t k = 0; k < f.proxies.size(); ++k)
          for (int j = 0; j < gi::rtf::kShCount; ++j) {
            const std::size_t e = k * gi::rtf::kShCount + std::size_t(j);
            const glm::vec3 all = bounced1.proxyLight[J][e], pr = probesOnly.proxyLight[J][e], t = tv[p * stride + e];
            rl += double(glm::dot(t, all - pr)) / 3.0, rp += double(glm::dot(t, pr)) / 3.0;
          }
        const glm::vec3 n = Nw[p], o = P[p] + 1e-4f * std::max(1.0f, glm::length(P[p])) * n;
        double dir = 0.0;
        for (const ref::RefLight& l : with.desc.lights) {
          glm::vec3 toL;
          float dist = 0.0f;
          const glm::vec3 E = gi::incident::lightIrradiance(lightGpu(l), P[p], toL, dist);
          const float c = glm::dot(n, toL);
          if (c <= 0.0f || bvhWith.occluded(o, toL, 0.0f, dist * (1.0f - 1e-4f))) continue;
          dir += double(glm::dot(rhoV[p], E)) / 3.0 * double(c) / math::kPi;
        }
        math::Pcg32 rng = math::Pcg32::fromIndex(777000 + J * 100000 + p);
        std::uint64_t rays = 0;
        glm::dvec3 ind(0.0);
        const int spa = int(std::ceil(std::sqrt(double(paths))));
        const auto dirs = math::stratified2D(spa, rng);
        for (const glm::dvec2& u : dirs)
          ind += ref::tracePathFrom(bvhWith, o, glm::vec3(math::cosineHemisphere(u, glm::dvec3(n))), 0.0f, 1e30f, ref::kUnlimitedBounces, rng, rays);
        ind /= double(dirs.size());
        perV[p] = {rl, rp, dir, glm::dot(glm::dvec3(rhoV[p]), ind) / 3.0};
      }, 1);
      for (std::size_t p = 0; p < P.size(); ++p) {
        if (P[p].y < 0.002f) continue;
        const int cls = Nw[p].y > 0.5f ? 0 : Nw[p].y < -0.5f ? 2 : 1;
        for (int i = 0; i < 4; ++i) acc[cls][i] += perV[p][std::size_t(i)];
        acc[cls][4] += 1.0;
      }
      // The lamp's visibility (lights[0]): at the proxies as the bouncing step takes it (the session's light
      // visibility, static geometry, one ray), and at the vertices through the static level and through the
      // level with every object (the reference's shadow ray).
      double vProxy = 0.0, vStatic = 0.0, vFull = 0.0;
      for (const glm::vec3& c : f.proxies)
        vProxy += double(light.lightVisibility().visible(lights[0], glm::vec3(objects[J].world * glm::vec4(c, 1.0f)), 0.0f));
      for (std::size_t p = 0; p < P.size(); ++p) {
        const glm::vec3 o = P[p] + 1e-4f * std::max(1.0f, glm::length(P[p])) * Nw[p];
        const glm::vec3 d = with.desc.lights[0].position - o;
        const float len = glm::length(d);
        vStatic += bvhWithout.occluded(o, d / len, 0.0f, len * (1.0f - 1e-4f)) ? 0.0 : 1.0;
        vFull += bvhWith.occluded(o, d / len, 0.0f, len * (1.0f - 1e-4f)) ? 0.0 : 1.0;
      }
      std::fprintf(stderr, "rtf_parts: faces: object %zu: lamp visibility, mean over the proxies (static, bouncing step) %.3f; over the vertices static %.3f, with the objects %.3f\n", J,
                   vProxy / double(f.proxies.size()), vStatic / double(P.size()), vFull / double(P.size()));
      const std::array<double, 2> am = albedoMeans(wd);
      std::fprintf(stderr, "rtf_parts: faces: object %zu (%s): albedo per vertex %.4f, area mean %.4f (%.3f)\n", J,
                   with.registry.get<scene::Name>(rtfEntities[J]).id.c_str(), am[0], am[1], am[0] / std::max(am[1], 1e-30));
      const char* cname[3] = {"up", "side", "down"};
      const auto ratio = [](double a, double b) { return b > 1e-9 ? a / b : std::nan(""); };  // nan: the reference has none
      for (int c = 0; c < 3; ++c) {
        if (acc[c][4] == 0.0) continue;
        const double nn = acc[c][4], rt = (acc[c][0] + acc[c][1]) / nn, rf = (acc[c][2] + acc[c][3]) / nn;
        std::fprintf(stderr,
                     "rtf_parts: faces: object %zu %-4s %3.0f vertices: RTF %.4g (lamp %.4g, probes %.4g) ref %.4g (direct %.4g, indirect %.4g) RTF/ref %.3f, lamp/direct %.3f, probes/indirect %.3f\n",
                     J, cname[c], nn, rt, acc[c][0] / nn, acc[c][1] / nn, rf, acc[c][2] / nn, acc[c][3] / nn, ratio(rt, rf), ratio(acc[c][0], acc[c][2]),
                     ratio(acc[c][1], acc[c][3]));
      }
    }
    if (std::getenv("RTF_PARTS_FACES_ONLY") != nullptr) return 0;
  }
  // At each object J's proxies χ_k, the reference's radiance from the OTHER objects (the level without J,
  // 6·16² cube directions, 4 paths each, unlimited bounces; the part whose first hit is another object):
  // its l = 0 coefficient against RTF's second bounce (2 bounces − 1) at the same proxies (Σ over proxies, RGB mean).
  // The source with each proxy's room light (the probes' part) scaled to the traced one (a what-if:
  // Algorithm 1 with exact proxy light; rtf-interreflected-exact1/-exact2).
  struct ProxyScale { glm::vec3 at; double ratio; };
  std::vector<ProxyScale> proxyScale, proxyScaleShadowed;
  for (std::size_t J = 0; J < objects.size(); ++J) {
    scene::Level minusJ = level;
    minusJ.entities.clear();
    const std::string idJ = with.registry.get<scene::Name>(rtfEntities[J]).id;
    for (const auto& ent : level.entities)
      if (ent.id != idJ) minusJ.entities.push_back(ent);
    Posed pj;
    pose(minusJ, time, cooked, pj);
    const ref::SceneBvh bvhJ(pj.desc);
    const gi::rtf::Field& f = *objects[J].field;
    std::vector<double> refOther(f.proxies.size(), 0.0), rtfOther(f.proxies.size(), 0.0), rtfOther4(f.proxies.size(), 0.0), refRoom(f.proxies.size(), 0.0), probeRoom(f.proxies.size(), 0.0);
    std::vector<double> refRoomShadowed(f.proxies.size(), 0.0);  // the room's l = 0 traced in the level without J, other objects' first hits left out
    std::vector<std::array<double, 4>> probeToward(f.proxies.size());
    // RTF_PARTS_TAP="J k B": proxy k of object J, object B's Eq. 10 lookup there, tap by tap: the sphere, the
    // weight, B's bounce-1 ξ l = 0 (RTF's light from B at the sample, Algorithm 1 with 1 bounce), V's l = 0 and
    // the reference's l = 0 from B at the sample's world position (the level without J, as refOther).
    if (const char* tap = std::getenv("RTF_PARTS_TAP")) {
      unsigned tj = 0, tk = 0, tb = 0;
      if (std::sscanf(tap, "%u %u %u", &tj, &tk, &tb) == 3 && tj == J && tb < objects.size() && tk < f.proxies.size()) {
        const gi::rtf::Field& fb = *objects[tb].field;
        const gi::rtf::Placement pb = gi::rtf::place(fb, objects[tb].world);
        const glm::vec3 chi = glm::vec3(objects[J].world * glm::vec4(f.proxies[tk], 1.0f));
        const glm::vec3 qb = (glm::vec3(pb.worldToLocal * glm::vec4(chi, 1.0f)) - fb.centre) / fb.radius;
        const gi::rtf::Lookup lk = gi::rtf::lookup(fb.settings, qb, objects[tb].reach);
        const auto xi0 = [&](const std::vector<glm::vec3>& xi, std::size_t s) { const glm::vec3 v = xi[s * gi::rtf::kShCount]; return (v.x + v.y + v.z) / 3.0f; };
        const gi::rtf::ShRgb I = gi::rtf::interreflection(fb, bounced1.xi[tb], qb, objects[tb].reach);
        std::fprintf(stderr, "rtf_parts: tap J=%u k=%u B=%u |q|=%.3f q=(%.3f %.3f %.3f) interreflection l0 %.4g\n", tj, tk, tb, glm::length(qb), qb.x, qb.y, qb.z,
                     (I[0].x + I[0].y + I[0].z) / 3.0f);
        // The same field uncompressed (a fresh bake of B at its settings: CPCA's share of the error).
        const gi::rtf::BakeResult raw = gi::rtf::bake(gi::dnrt::objectScene(with.registry, rtfEntities[tb], with.assets), fb.settings);
        const std::size_t D = gi::rtf::itfDimension(fb.settings);
        {  // At tap 2's sample: the vertices its front hits take their transfer from (bake.cpp's nearest vertex).
          const ref::SceneDesc od = gi::dnrt::objectScene(with.registry, rtfEntities[tb], with.assets);
          const std::vector<glm::vec3> tv = gi::rtf::vertexTransfer(od, fb.proxies, fb.radius, fb.settings);
          std::vector<glm::vec3> P, Nn;
          for (const auto& m : od.meshes)
            for (std::size_t i = 0; i < m.positions.size(); ++i) P.push_back(m.positions[i]), Nn.push_back(i < m.normals.size() ? m.normals[i] : glm::vec3(0, 0, 1));
          const std::size_t stride = std::size_t(fb.settings.proxies) * gi::rtf::kShCount;
          const glm::vec3 sp = fb.centre + gi::rtf::samplePosition(fb.settings, lk.sample[2]) * fb.radius;
          int hitsN = 0, dark = 0;
          double tsum = 0.0, dsum = 0.0;
          for (std::size_t di = 0; di < oofDirs.size(); ++di) {
            ref::Hit h;
            if (!objectBvh[tb]->intersect(sp, oofDirs[di].w, 0.0f, 1e30f, h) || glm::dot(h.geometricNormal, oofDirs[di].w) > 0.0f) continue;
            std::size_t best = 0;
            float bd = 1e30f;
            for (std::size_t i = 0; i < P.size(); ++i) {
              const float d2 = glm::dot(P[i] - h.position, P[i] - h.position);
              if (glm::dot(Nn[i], h.geometricNormal) > 0.0f && d2 < bd) bd = d2, best = i;
            }
            double t0 = 0.0;
            for (int k = 0; k < fb.settings.proxies; ++k) { const glm::vec3 x = tv[best * stride + std::size_t(k) * gi::rtf::kShCount]; t0 += (x.x + x.y + x.z) / 3.0; }
            ++hitsN, tsum += t0, dsum += std::sqrt(bd) / fb.radius;
            if (t0 < 0.02) {
              ++dark;
              if (dark <= 6)
                std::fprintf(stderr, "rtf_parts:   dark hit at (%.3g %.3g %.3g) ng (%.2f %.2f %.2f) vertex %zu at %.3g eta, n (%.2f %.2f %.2f), T0 %.4g\n", h.position.x, h.position.y, h.position.z,
                             h.geometricNormal.x, h.geometricNormal.y, h.geometricNormal.z, best, std::sqrt(bd) / fb.radius, Nn[best].x, Nn[best].y, Nn[best].z, t0);
            }
          }
          std::fprintf(stderr, "rtf_parts:   tap 2: %d front hits, mean Σ_k T0 %.4g, mean vertex distance %.3g eta, %d with Σ_k T0 < 0.02; %zu vertices\n", hitsN, tsum / std::max(hitsN, 1),
                       dsum / std::max(hitsN, 1), dark, P.size());
        }
        {  // Per sphere: Σ |ξ0| over its samples, uncompressed against the field's (CPCA), B's bounce-1 light.
          const std::size_t per = std::size_t(gi::rtf::samplesPerSphere(fb.settings));
          std::string line;
          for (int sp = 0; sp < fb.settings.spheres; ++sp) {
            double r = 0.0, c = 0.0, diff = 0.0;
            for (std::size_t si = std::size_t(sp) * per; si < std::size_t(sp + 1) * per; ++si) {
              double x = 0.0;
              for (int k = 0; k < fb.settings.proxies; ++k)
                for (int j = 0; j < gi::rtf::kShCount; ++j)
                  for (int ch = 0; ch < 3; ++ch)
                    x += raw.itf[si * D + gi::rtf::itfIndex(k, 0, j, ch)] * bounced1.proxyLight[tb][std::size_t(k) * gi::rtf::kShCount + std::size_t(j)][ch] / 3.0;
              const glm::vec3 v = bounced1.xi[tb][si * gi::rtf::kShCount];
              const double y = (v.x + v.y + v.z) / 3.0;
              r += std::abs(x), c += std::abs(y), diff += std::abs(x - y);
            }
            char b[64];
            std::snprintf(b, sizeof b, " %d: %.3g/%.3g (|d| %.3g)", sp, r, c, diff);
            line += b;
          }
          std::fprintf(stderr, "rtf_parts:   B's xi0 per sphere, uncompressed/CPCA:%s (field frobenius %.4g, fresh bake's %.4g)\n", line.c_str(), fb.frobenius, raw.stats.frobenius);
        }
        for (int t = 0; t < 8; ++t) {
          const std::size_t si = lk.sample[std::size_t(t)];
          double rawXi = 0.0;
          for (int k = 0; k < fb.settings.proxies; ++k)
            for (int j = 0; j < gi::rtf::kShCount; ++j)
              for (int c = 0; c < 3; ++c)
                rawXi += raw.itf[si * D + gi::rtf::itfIndex(k, 0, j, c)] * bounced1.proxyLight[tb][std::size_t(k) * gi::rtf::kShCount + std::size_t(j)][c] / 3.0;
          std::string perK;
          for (int k = 0; k < fb.settings.proxies; ++k) {
            double m00 = 0.0;
            for (int c = 0; c < 3; ++c) m00 += raw.itf[si * D + gi::rtf::itfIndex(k, 0, 0, c)] / 3.0;
            char b[24];
            std::snprintf(b, sizeof b, " %.3g", m00);
            perK += b;
          }
          std::fprintf(stderr, "rtf_parts:   tap %d M00 per proxy:%s\n", t, perK.c_str());
          int front = 0, back = 0;
          for (const Dir& d : oofDirs) {
            ref::Hit h;
            if (!objectBvh[tb]->intersect(fb.centre + gi::rtf::samplePosition(fb.settings, si) * fb.radius, d.w, 0.0f, 1e30f, h)) continue;
            (glm::dot(h.geometricNormal, d.w) > 0.0f ? back : front) += 1;
          }
          std::fprintf(stderr, "rtf_parts:   tap %d uncompressed xi1 l0 %.4g, front/back hits %d/%d of %zu\n", t, rawXi, front, back, oofDirs.size());
          const glm::vec3 sl = gi::rtf::samplePosition(fb.settings, si);
          const glm::vec3 sw = glm::vec3(objects[tb].world * glm::vec4(fb.centre + sl * fb.radius, 1.0f));
          math::Pcg32 rng = math::Pcg32::fromIndex(7777 + t);
          std::uint64_t rays = 0;
          double acc = 0.0;
          for (const Dir& d : oofDirs)
            for (int path = 0; path < 4; ++path) {
              ref::Hit first;
              bool any = false;
              const glm::dvec3 L = ref::tracePathFrom(bvhJ, sw, d.w, 0.0f, 1e30f, ref::kUnlimitedBounces, rng, rays, &first, &any);
              if (any && objectHit(sw, d.w, first.t, int(J)) == int(tb)) acc += (L.x + L.y + L.z) / 3.0 * 0.28209479 * d.solidAngle / 4.0;
            }
          std::fprintf(stderr, "rtf_parts:   tap %d sample %zu |s|=%.2f w=%.3f xi1 l0 %.4g (bounce-2 xi %.4g) V0/u %.3f ref l0 from B %.4g\n", t, si, glm::length(sl),
                       lk.weight[std::size_t(t)], xi0(bounced1.xi[tb], si), xi0(bounced.xi[tb], si), fb.oof[si * gi::rtf::kShCount] / gi::rtf::kUnitVisibility, acc);
        }
        const auto& pl = bounced1.proxyLight[tb];
        std::string ls;
        for (std::size_t k = 0; k < fb.proxies.size(); ++k) { char b[32]; const glm::vec3 v = pl[k * gi::rtf::kShCount]; std::snprintf(b, sizeof b, " %.3g", (v.x + v.y + v.z) / 3.0f); ls += b; }
        std::fprintf(stderr, "rtf_parts:   B's proxies' l0 light (bounce 1):%s\n", ls.c_str());
      }
    }
    parallelFor(0, f.proxies.size(), [&](std::size_t k) {
      // 1 % of the way towards J's centre (J is not in bvhJ): a proxy on the floor (a box's bottom corner)
      // would otherwise start its rays on the floor's plane.
      const glm::vec3 o = glm::vec3(objects[J].world * glm::vec4(f.centre, 1.0f));
      const glm::vec3 chi = glm::mix(glm::vec3(objects[J].world * glm::vec4(f.proxies[k], 1.0f)), o, 0.01f);
      math::Pcg32 rng = math::Pcg32::fromIndex(J * 1000 + k);
      std::uint64_t rays = 0;
      double acc = 0.0, room = 0.0, shadowed = 0.0;
      for (const Dir& d : oofDirs)
        for (int path = 0; path < 4; ++path) {
          ref::Hit first;
          bool any = false;
          const glm::dvec3 L = ref::tracePathFrom(bvhJ, chi, d.w, 0.0f, 1e30f, ref::kUnlimitedBounces, rng, rays, &first, &any);
          if (any && objectHit(chi, d.w, first.t, int(J)) >= 0) acc += (L.x + L.y + L.z) / 3.0 * 0.28209479 * d.solidAngle / 4.0;
          else shadowed += (L.x + L.y + L.z) / 3.0 * 0.28209479 * d.solidAngle / 4.0;
          const glm::dvec3 L0 = ref::tracePathFrom(bvhWithout, chi, d.w, 0.0f, 1e30f, ref::kUnlimitedBounces, rng, rays);
          room += (L0.x + L0.y + L0.z) / 3.0 * 0.28209479 * d.solidAngle / 4.0;
        }
      refOther[k] = acc;
      refRoomShadowed[k] = shadowed;
      // The room's light at χ without any object (the traced l = 0) against the probes' there: the source
      // light Algorithm 1's bounce 0 starts from.
      const glm::vec3 pr = light.indirect().radianceSH(chi)[0];
      refRoom[k] = room, probeRoom[k] = double(pr.x + pr.y + pr.z) / 3.0;
      for (int t = 0; t < 4; ++t) {  // the probes' l = 0 at χ moved towards o by 0, ¼, ½, 1 of the way
        const glm::vec3 pt = light.indirect().radianceSH(glm::mix(chi, o, 0.25f * float(t == 3 ? 4 : t)))[0];
        probeToward[k][std::size_t(t)] = double(pt.x + pt.y + pt.z) / 3.0;
      }
      const glm::vec3 l1 = bounced.proxyLight[J][k * gi::rtf::kShCount] - bounced1.proxyLight[J][k * gi::rtf::kShCount];
      rtfOther[k] = double(l1.x + l1.y + l1.z) / 3.0;
      const glm::vec3 l4 = bounced4.proxyLight[J][k * gi::rtf::kShCount] - bounced1.proxyLight[J][k * gi::rtf::kShCount];
      rtfOther4[k] = double(l4.x + l4.y + l4.z) / 3.0;
    }, 1);
    double a = 0.0, b = 0.0, b4 = 0.0;
    for (double v : rtfOther4) b4 += v;
    std::string per;
    for (std::size_t k = 0; k < f.proxies.size(); ++k) {
      a += refOther[k], b += rtfOther[k];
      char buf[96];
      const glm::vec3 chi = glm::vec3(objects[J].world * glm::vec4(f.proxies[k], 1.0f));
      float nearest = 1e30f;  // the nearest other object's |q| (η) at the proxy
      float insideMesh = 0.0f;  // the largest share of directions that leave through another object's back faces
      float inside = 0.0f;    // the largest weight Eq. 10 puts on another object's samples with V ≡ 0 (inside it)
      for (std::size_t B = 0; B < objects.size(); ++B)
        if (B != J) {
          const gi::rtf::Field& fb = *objects[B].field;
          const gi::rtf::Placement pb = gi::rtf::place(fb, objects[B].world);
          nearest = std::min(nearest, glm::length(chi - pb.centreWorld) / pb.radiusWorld);
          const glm::vec3 qb = (glm::vec3(pb.worldToLocal * glm::vec4(chi, 1.0f)) - fb.centre) / fb.radius;
          const gi::rtf::Lookup lk = gi::rtf::lookup(fb.settings, qb, objects[B].reach);
          float w0 = 0.0f;
          for (int t = 0; t < 8; ++t)
            if (std::abs(fb.oof[lk.sample[std::size_t(t)] * gi::rtf::kShCount]) < 1e-3f) w0 += lk.weight[std::size_t(t)];
          inside = std::max(inside, w0);
          // Is χ inside B's mesh? the share of directions whose first hit on B is a back face.
          int back = 0, total = 0;
          for (std::size_t di = 0; di < oofDirs.size(); di += 7) {
            ref::Hit h;
            if (!aloneBvh[B]->intersect(chi, oofDirs[di].w, 0.0f, 1e30f, h)) continue;
            ++total;
            back += glm::dot(h.geometricNormal, oofDirs[di].w) > 0.0f;
          }
          insideMesh = std::max(insideMesh, total > 0 ? float(back) / float(oofDirs.size() / 7) : 0.0f);
        }
      std::snprintf(buf, sizeof buf, " %.3g/%.3g/%.3g@%.2f(w0 %.2f back %.2f)", refOther[k], rtfOther[k], rtfOther4[k], nearest, inside, insideMesh);
      per += buf;
    }
    std::string rooms;
    for (std::size_t k = 0; k < f.proxies.size(); ++k)
      proxyScale.push_back({glm::vec3(objects[J].world * glm::vec4(f.proxies[k], 1.0f)), probeRoom[k] > 1e-6 ? refRoom[k] / probeRoom[k] : 1.0}),
      proxyScaleShadowed.push_back({proxyScale.back().at, probeRoom[k] > 1e-6 ? refRoomShadowed[k] / probeRoom[k] : 1.0});
    for (std::size_t k = 0; k < f.proxies.size(); ++k) {
      char buf[48];
      std::snprintf(buf, sizeof buf, " %.3g/%.3g", refRoom[k], probeRoom[k]);
      rooms += buf;
    }
    std::fprintf(stderr, "rtf_parts: object %zu: the room's L_00 at the proxies, traced without the objects / the probes':%s\n", J, rooms.c_str());
    {
      double t0 = 0.0, t1 = 0.0, pr = 0.0;
      for (std::size_t k = 0; k < f.proxies.size(); ++k) t0 += refRoom[k], t1 += refRoomShadowed[k], pr += probeRoom[k];
      std::fprintf(stderr, "rtf_parts: object %zu: the room's L_00 summed over the proxies: probes %.4g, traced without any object %.4g, traced with the other objects (their shadows; directions onto them left out) %.4g\n",
                   J, pr, t0, t1);
    }
    {
      double e[4] = {}, tr = 0.0;
      for (std::size_t k = 0; k < f.proxies.size(); ++k) {
        tr += refRoom[k];
        for (int t = 0; t < 4; ++t) e[t] += std::abs(probeToward[k][std::size_t(t)] - refRoom[k]);
      }
      std::fprintf(stderr, "rtf_parts: object %zu: mean |probes - traced| / traced at chi moved towards o by 0, 1/4, 1/2, 1: %.3f %.3f %.3f %.3f\n", J,
                   e[0] / tr, e[1] / tr, e[2] / tr, e[3] / tr);
    }
    std::fprintf(stderr, "rtf_parts: object %zu (%s): proxies' L_00 from the other objects: reference %.4g, RTF second bounce %.4g (%.3g), bounces 2-4 %.4g (%.3g); per proxy ref/RTF 2/RTF 4:%s\n",
                 J, idJ.c_str(), a, b, b / std::max(a, 1e-30), b4, b4 / std::max(a, 1e-30), per.c_str());
  }
  if (std::getenv("RTF_PARTS_PROXIES_ONLY") != nullptr) return 0;  // the proxy lines above only
  struct ExactProxySource final : gi::incident::IndirectSource {
    const gi::incident::IndirectSource& lit;
    const gi::incident::IndirectSource& probes;
    const std::vector<ProxyScale>& scale;
    ExactProxySource(const gi::incident::IndirectSource& l, const gi::incident::IndirectSource& p, const std::vector<ProxyScale>& s)
        : lit(l), probes(p), scale(s) {}
    gi::incident::RadianceSH radianceSH(glm::vec3 p) const override {
      gi::incident::RadianceSH L = lit.radianceSH(p);
      for (const ProxyScale& ps : scale)
        if (glm::length(ps.at - p) < 1e-5f * std::max(1.0f, glm::length(p))) {
          const gi::incident::RadianceSH pr = probes.radianceSH(p);
          for (std::size_t i = 0; i < L.size(); ++i) L[i] += float(ps.ratio - 1.0) * pr[i];
          break;
        }
      return L;
    }
  };
  const ExactProxySource exactSource(lit, light.indirect(), proxyScale);
  // Session 17 what-ifs on the objects' first order (rtf-interreflected-albedo / -lampvis / -both, 2 bounces):
  //   albedo:  each object's ξ scaled by its area-mean ρ over its per-vertex mean ρ (albedoMeans; the transfer is
  //            linear in the first reflection's ρ, the self bounces' ρ² is left as is);
  //   lampvis: the bouncing step's source with the lamp's visibility at each proxy of J traced through the level
  //            without J (the other objects included: the textured box under the lamp shadows the truck, which the
  //            OOFs cannot: a point light, and 6.4 η away, beyond its field) instead of the static level alone.
  std::vector<float> albedoScale;
  for (std::size_t J = 0; J < objects.size(); ++J) {
    const std::array<double, 2> am = albedoMeans(alone[J]->desc);
    albedoScale.push_back(float(am[1] / std::max(am[0], 1e-30)));
    std::fprintf(stderr, "rtf_parts: object %zu: albedo per vertex %.4f, area mean %.4f: what-if scale %.3f\n", J, am[0], am[1], albedoScale.back());
  }
  std::vector<std::unique_ptr<Posed>> minusPosed;
  std::vector<std::unique_ptr<ref::SceneBvh>> minusBvh;
  for (std::size_t J = 0; J < objects.size(); ++J) {
    scene::Level minusJ = level;
    minusJ.entities.clear();
    for (const auto& ent : level.entities)
      if (ent.id != with.registry.get<scene::Name>(rtfEntities[J]).id) minusJ.entities.push_back(ent);
    minusPosed.push_back(std::make_unique<Posed>());
    pose(minusJ, time, cooked, *minusPosed.back());
    minusBvh.push_back(std::make_unique<ref::SceneBvh>(minusPosed.back()->desc));
  }
  struct LampVisSource final : gi::incident::IndirectSource {
    const gi::incident::IndirectSource& probes;
    std::vector<std::pair<glm::vec3, const ref::SceneBvh*>> at;  // each proxy's world position and its level without J
    std::span<const render::LightGpu> lights;
    gi::incident::RadianceSH radianceSH(glm::vec3 p) const override {
      gi::incident::RadianceSH L = probes.radianceSH(p);
      const ref::SceneBvh* bvh = nullptr;
      for (const auto& a : at)
        if (glm::length(a.first - p) < 1e-5f * std::max(1.0f, glm::length(p))) bvh = a.second;
      for (const render::LightGpu& l : lights) {
        const glm::vec3 d = glm::vec3(l.positionType) - p;
        const float len = glm::length(d);
        const bool seen = !bvh || !(len > 0.0f) || !bvh->occluded(p, d / len, 0.0f, len * (1.0f - 1e-4f));
        if (seen) gi::incident::addLight(l, p, 0.0f, 1.0f, L);
      }
      return L;
    }
    LampVisSource(const gi::incident::IndirectSource& pr, std::span<const render::LightGpu> ls) : probes(pr), lights(ls) {}
  };
  LampVisSource lampVis(light.indirect(), lights);
  for (std::size_t J = 0; J < objects.size(); ++J)
    for (const glm::vec3& c : objects[J].field->proxies) lampVis.at.push_back({glm::vec3(objects[J].world * glm::vec4(c, 1.0f)), minusBvh[J].get()});
  const gi::rtf::BounceResult bouncedLamp = gi::rtf::bounce(objects, lampVis, 2);
  gi::rtf::BounceResult bouncedAlbedo = bounced, bouncedBoth = bouncedLamp;
  //   shadowed: each proxy's probe part scaled to the room's l = 0 traced at it in the level without J (the other
  //            objects' shadows in it; exact1's trace had no object at all), lamp as shipped; shadowed-lampvis: with
  //            the lampvis source.
  const ExactProxySource shadowedSource(lit, light.indirect(), proxyScaleShadowed), shadowedLampSource(lampVis, light.indirect(), proxyScaleShadowed);
  const gi::rtf::BounceResult bouncedShadowed = gi::rtf::bounce(objects, shadowedSource, 2), bouncedShadowedLamp = gi::rtf::bounce(objects, shadowedLampSource, 2);
  const gi::rtf::BounceResult bouncedShadowedLamp1 = gi::rtf::bounce(objects, shadowedLampSource, 1);  // the same at 1 bounce (-b1)
  //   lampray-b1: what the engine's form of lampvis would give (1 bounce): Algorithm 1's OOF product on the
  //            probes' part only, the lamp added after it with the ray's visibility through the level without J
  //            (so the lamp is not occluded twice, by the ray and by the OOFs); shadowed-lampray-b1: with the
  //            probes' part scaled as `shadowed`.
  struct NoLight final : gi::incident::IndirectSource {
    gi::incident::RadianceSH radianceSH(glm::vec3) const override { return {}; }
  };
  const NoLight noLight;
  LampVisSource lampOnly(noLight, lights);
  lampOnly.at = lampVis.at;
  const ExactProxySource shadowedProbes(light.indirect(), light.indirect(), proxyScaleShadowed);
  const auto withLampRay = [&](const gi::incident::IndirectSource& probesPart) {
    gi::rtf::BounceResult r = gi::rtf::bounce(objects, probesPart, 1);
    r.xi.clear();
    for (std::size_t J = 0; J < objects.size(); ++J) {
      const gi::rtf::Placement pl = gi::rtf::place(*objects[J].field, objects[J].world);
      for (std::size_t k = 0; k < objects[J].field->proxies.size(); ++k) {
        const glm::vec3 chi = glm::vec3(objects[J].world * glm::vec4(objects[J].field->proxies[k], 1.0f));
        const gi::rtf::ShRgb l = gi::rtf::toLocal(gi::rtf::sourceRadiance(lampOnly, chi), pl);
        for (int j = 0; j < gi::rtf::kShCount; ++j) r.proxyLight[J][k * gi::rtf::kShCount + std::size_t(j)] += l[std::size_t(j)];
      }
      r.xi.push_back(gi::rtf::xiCache(*objects[J].field, r.proxyLight[J]));
    }
    return r;
  };
  const gi::rtf::BounceResult lampRay1 = withLampRay(light.indirect()), shadowedLampRay1 = withLampRay(shadowedProbes);
  for (std::size_t J = 0; J < objects.size(); ++J) {
    for (glm::vec3& x : bouncedAlbedo.xi[J]) x *= albedoScale[J];
    for (glm::vec3& x : bouncedBoth.xi[J]) x *= albedoScale[J];
  }
  const gi::rtf::BounceResult exact1 = gi::rtf::bounce(objects, exactSource, 1), exact2 = gi::rtf::bounce(objects, exactSource, 2);
  // Algorithm 1's energy per bounce (evaluate.hpp BounceResult::bounceEnergy): what a second
  // inter-object bounce can add at all, against the first.
  for (std::size_t b = 0; b < bounced.bounceEnergy.size(); ++b)
    std::fprintf(stderr, "rtf_parts: bounce %zu energy %.6g (%.3g of bounce 0)\n", b, bounced.bounceEnergy[b],
                 bounced.bounceEnergy[b] / std::max(bounced.bounceEnergy[0], 1e-30));

  // The GPU's per-sample level of the blocked light (update.hpp blockedScale, static geometry = the level without its props).
  // The GPU's per-sample factor as shipped (overlap.hpp sharedOcclusion's s: the objects' shared occlusion, light at o),
  // and the former per-sample light level (update.hpp blockedScale, static geometry = the level without its props).
  std::vector<std::vector<glm::vec4>> scales, levels;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    scales.push_back(gi::rtf::sharedOcclusion(objects, k).scale);
    levels.push_back(gi::rtf::blockedScale(*objects[k].field, objects[k].world, light.indirect(), &bvhWithout));
  }
  // Two per-sample levels from the light AT THE OBJECT (issue 14, seventh pass), L_00 per channel over L_00(o):
  //   eq3:     Σ_k w_k(p_s) L_00(χ_k), w_k = Eq. 3's normalised inverse distances from the sample p_s to the proxies
  //   surface: L_00 at o + η·d_s, the bounding sphere's point on the sample's ray from o
  std::vector<std::vector<glm::vec4>> scalesEq3, scalesSurf;
  for (const gi::rtf::Object& ob : objects) {
    const gi::rtf::Field& f = *ob.field;
    const gi::rtf::Placement pl = gi::rtf::place(f, ob.world);
    const glm::vec3 at = glm::max(light.indirect().radianceSH(pl.centreWorld)[0], glm::vec3(1e-6f));
    std::vector<glm::vec3> chi, lchi;
    for (const glm::vec3& c : f.proxies) {
      chi.push_back(glm::vec3(ob.world * glm::vec4(c, 1.0f)));
      lchi.push_back(light.indirect().radianceSH(chi.back())[0]);
    }
    const gi::rtf::FieldSettings& s = f.settings;
    const int per = gi::rtf::samplesPerSphere(s);
    std::vector<glm::vec4> e3(gi::rtf::sampleCount(s)), sf(gi::rtf::sampleCount(s));
    for (int rest = 0; rest < per; ++rest) {
      const glm::vec3 dir = pl.localToWorldDirections() * gi::rtf::sampleDirection(s, std::size_t(rest));
      const glm::vec3 surf = light.indirect().radianceSH(pl.centreWorld + pl.radiusWorld * dir)[0] / at;
      for (int sphere = 0; sphere < s.spheres; ++sphere) {
        const glm::vec3 p = pl.centreWorld + pl.radiusWorld * gi::rtf::sphereRadius(s, sphere) * dir;
        glm::vec3 l(0.0f);
        float wsum = 0.0f;
        for (std::size_t k = 0; k < chi.size(); ++k) {
          const float w = 1.0f / std::max(glm::length(p - chi[k]), 1e-4f);
          l += w * lchi[k], wsum += w;
        }
        e3[std::size_t(sphere * per + rest)] = glm::vec4(glm::max(l / wsum / at, glm::vec3(0.0f)), 1.0f);
        sf[std::size_t(sphere * per + rest)] = glm::vec4(glm::max(surf, glm::vec3(0.0f)), 1.0f);
      }
    }
    scalesEq3.push_back(std::move(e3));
    scalesSurf.push_back(std::move(sf));
  }
  enum { kInter, kBlocked, kRoom, kBlockedProbes, kRtfInter, kRtfBlocked, kField, kAtR, kShapeO, kAtO, kGpu, kOofAtR, kOofNoFade, kOofShExactCos, kVisExactCos, kEq3, kSurf, kLevel, kViaOther, kViaSelf, kRtfInter1, kRtfInter3, kRtfInter4, kExact1, kExact2, kHidden, kAlbedo, kLampVis, kBoth, kShadowed, kShadowedLamp, kShadowedLamp1, kLampRay1, kShadowedLampRay1, kEngine1, kEngine2, kEngineAdd1, kEngineAdd2, kParts };
  const char* names[kParts] = {"ref-interreflected", "ref-blocked", "ref-room", "blocked-probes", "rtf-interreflected",
                               "rtf-blocked", "field", "blocked-receiver", "blocked-shape-o", "blocked-at-o", "blocked-gpu",
                               "blocked-oof-at-r", "blocked-oof-at-r-nofade", "blocked-oofsh-exactcos", "blocked-vis-exactcos", "blocked-eq3", "blocked-surface", "blocked-level",
                               "ref-via-other", "ref-via-self", "rtf-interreflected-b1",
                               "rtf-interreflected-b3", "rtf-interreflected-b4",
                               "rtf-interreflected-exact1", "rtf-interreflected-exact2", "ref-interreflected-hidden", "rtf-interreflected-albedo", "rtf-interreflected-lampvis", "rtf-interreflected-both", "rtf-interreflected-shadowed", "rtf-interreflected-shadowed-lampvis", "rtf-interreflected-shadowed-lampvis-b1", "rtf-interreflected-lampray-b1", "rtf-interreflected-shadowed-lampray-b1", "rtf-interreflected-engine-b1", "rtf-interreflected-engine", "rtf-interreflected-engine-add-b1", "rtf-interreflected-engine-add"};
  std::vector<gpu::FloatImage> images(kParts);
  for (auto& im : images) im.width = W, im.height = H, im.rgb.assign(std::size_t(W) * H * 3, 0.0f);
  parallelFor(0, std::size_t(W) * H, [&](std::size_t pixel) {
    const std::uint32_t x = std::uint32_t(pixel % W), y = std::uint32_t(pixel / W);
    const ref::CameraRay cam = ref::cameraRay(with.desc.camera, W, H, x, y);
    ref::Hit hit, propHit;
    if (!bvhWith.intersect(cam.origin, cam.direction, cam.tMin, cam.tMax, hit)) return;
    if (bvhProps.intersect(cam.origin, cam.direction, cam.tMin, cam.tMax, propHit) && propHit.t <= hit.t * (1.0f + 1e-5f))
      return;  // the pixel sees an object: not a receiver
    const glm::vec3 rho = albedoAt(with.desc, hit);
    glm::vec3 n = hit.shadingNormal, ng = hit.geometricNormal;
    if (glm::dot(n, cam.direction) > 0.0f) n = -n;
    if (glm::dot(ng, cam.direction) > 0.0f) ng = -ng;
    const auto probeSh = light.indirect().radianceSH(hit.position);
    math::Pcg32 rng = math::Pcg32::fromIndex(pixel);
    glm::dvec3 sum[7] = {};
    math::Pcg32 rngHidden = math::Pcg32::fromIndex((std::uint64_t(1) << 40) + pixel);  // its own stream: the other parts stay as before
    std::array<glm::dvec3, 8> objInter{}, objOther{};
    std::uint64_t rays = 0;
    const auto dirs = math::stratified2D(spa, rng);
    for (const glm::dvec2& u : dirs) {
      const glm::vec3 w = glm::vec3(math::cosineHemisphere(u, glm::dvec3(n)));
      if (glm::dot(w, ng) <= 0.0f) continue;  // below the surface: no light (the tracer's rule)
      const glm::vec3 o = offset(hit.position, ng, w);
      ref::Hit first, ph;
      bool any = false;
      const glm::dvec3 lw = ref::tracePathFrom(bvhWith, o, w, 0.0f, 1e30f, ref::kUnlimitedBounces, rng, rays, &first, &any);
      const glm::dvec3 lo = ref::tracePathFrom(bvhWithout, o, w, 0.0f, 1e30f, ref::kUnlimitedBounces, rng, rays);
      const bool onProp = any && bvhProps.intersect(o, w, 0.0f, 1e30f, ph) && ph.t <= first.t * (1.0f + 1e-5f) + 1e-6f;
      if (onProp) {
        sum[0] += lw, sum[1] += lo;
        // The light that reached the object A (first hit) from another object B (bounce ≥ 2 between the
        // objects) or from A itself: kSub cosine directions about A's normal at the hit, each traced on
        // (unlimited bounces) when its first hit is an object; ρ_A·E[L·1(B)] is that part of A's
        // outgoing light (the rest: A's emission, its direct light and the room's light at A).
        const int a = objectHit(o, w, first.t);
        if (a >= 0) {
          objInter[std::size_t(a)] += lw;
          const glm::vec3 rhoA = albedoAt(with.desc, first);
          glm::vec3 na = first.shadingNormal, nga = first.geometricNormal;
          if (glm::dot(na, w) > 0.0f) na = -na;
          if (glm::dot(nga, w) > 0.0f) nga = -nga;
          constexpr int kSub = 4;
          for (int sub = 0; sub < kSub; ++sub) {
            const glm::vec3 w2 = glm::vec3(math::cosineHemisphere(rng.next2D(), glm::dvec3(na)));
            if (glm::dot(w2, nga) <= 0.0f) continue;
            const glm::vec3 o2 = offset(first.position, nga, w2);
            ref::Hit h2;
            if (!bvhWith.intersect(o2, w2, 0.0f, 1e30f, h2)) continue;
            const int b = objectHit(o2, w2, h2.t);
            if (b < 0) continue;
            const glm::dvec3 l2 = glm::dvec3(rhoA) * ref::tracePathFrom(bvhWith, o2, w2, 0.0f, 1e30f, ref::kUnlimitedBounces, rng, rays) / double(kSub);
            sum[b == a ? 5 : 4] += l2;
            if (b != a) objOther[std::size_t(a)] += l2;
          }
        }
        const auto yb = sh::evalBasis<double>(3, glm::dvec3(w));
        glm::dvec3 lp(0.0);
        for (int i = 0; i < 9; ++i) lp += glm::dvec3(probeSh[std::size_t(i)]) * yb[std::size_t(i)];
        sum[3] += lp;
      } else {
        sum[2] += lw - lo;
        // ref-interreflected-hidden (session 17): an object on this ray that the room hides from r. RTF's
        // field has no room visibility, so it sends r the light the object sends along −ω all the same:
        // traced from just before the object's surface (its outgoing radiance towards r).
        ref::Hit hp;
        if (bvhProps.intersect(o, w, 0.0f, 1e30f, hp))
          sum[6] += ref::tracePathFrom(bvhWith, o + w * (hp.t * (1.0f - 1e-4f)), w, 0.0f, 1e30f, ref::kUnlimitedBounces, rngHidden, rays);
      }
    }
    const double inv = 1.0 / double(dirs.size());
    auto put = [&](int part, glm::vec3 v) {
      float* px = images[std::size_t(part)].rgb.data() + pixel * 3;
      px[0] = v.x, px[1] = v.y, px[2] = v.z;
    };
    put(kInter, rho * glm::vec3(sum[0] * inv));
    put(kBlocked, rho * glm::vec3(sum[1] * inv));
    put(kRoom, rho * glm::vec3(sum[2] * inv));
    put(kBlockedProbes, rho * glm::vec3(sum[3] * inv));
    put(kViaOther, rho * glm::vec3(sum[4] * inv));
    put(kViaSelf, rho * glm::vec3(sum[5] * inv));
    put(kHidden, rho * glm::vec3(sum[6] * inv));
    put(kRtfInter1, gi::rtf::shade(objects, bounced1, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kRtfInter3, gi::rtf::shade(objects, bounced3, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kRtfInter4, gi::rtf::shade(objects, bounced4, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kExact1, gi::rtf::shade(objects, exact1, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kExact2, gi::rtf::shade(objects, exact2, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kAlbedo, gi::rtf::shade(objects, bouncedAlbedo, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kLampVis, gi::rtf::shade(objects, bouncedLamp, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kBoth, gi::rtf::shade(objects, bouncedBoth, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kShadowed, gi::rtf::shade(objects, bouncedShadowed, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kShadowedLamp, gi::rtf::shade(objects, bouncedShadowedLamp, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kShadowedLamp1, gi::rtf::shade(objects, bouncedShadowedLamp1, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kLampRay1, gi::rtf::shade(objects, lampRay1, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kShadowedLampRay1, gi::rtf::shade(objects, shadowedLampRay1, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kEngine1, gi::rtf::shade(objects, engine1, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    put(kEngine2, gi::rtf::shade(objects, engine2, light.indirect(), hit.position, n, rho, -1, 9).interreflected);
    {  // the GPU pass's form: each object's field on its own, added (no nearer object's OOF over it)
      glm::vec3 add1(0.0f), add2(0.0f);
      for (std::size_t k = 0; k < objects.size(); ++k) {
        const std::span<const gi::rtf::Object> one(&objects[k], 1);
        add1 += gi::rtf::shade(one, engineSingle1[k], light.indirect(), hit.position, n, rho, -1, 9).interreflected;
        add2 += gi::rtf::shade(one, engineSingle2[k], light.indirect(), hit.position, n, rho, -1, 9).interreflected;
      }
      put(kEngineAdd1, add1), put(kEngineAdd2, add2);
    }
    for (std::size_t k = 0; k < objects.size(); ++k) {
      const std::span<const gi::rtf::Object> one(&objects[k], 1);
      auto& po = perObject[pixel * objects.size() + k];
      const auto s3 = [](glm::dvec3 v) { return v.x + v.y + v.z; };
      po[0] = s3(glm::dvec3(rho) * objInter[k] * inv), po[1] = s3(glm::dvec3(rho) * objOther[k] * inv);
      po[2] = s3(glm::dvec3(gi::rtf::shade(one, single1[k], light.indirect(), hit.position, n, rho, -1, 9).interreflected));
      po[3] = s3(glm::dvec3(gi::rtf::shade(one, single2[k], light.indirect(), hit.position, n, rho, -1, 9).interreflected));
    }
    const gi::rtf::Shading sh = gi::rtf::shade(objects, bounced, light.indirect(), hit.position, n, rho, -1, 9);
    put(kRtfInter, sh.interreflected);
    put(kRtfBlocked, sh.blocked);
    float nearest = 1e30f;
    for (const Reach& r : reach) nearest = std::min(nearest, glm::length(hit.position - r.centre) / r.radius);
    put(kField, glm::vec3(nearest));
    // The blocked term four ways (header), each object's term on its own, in its frame.
    const gi::rtf::ShRgb atR = gi::rtf::sourceRadiance(light.indirect(), hit.position);
    glm::vec3 variant[7] = {}, exactV(0.0f), exactNoFade(0.0f), shExactCos(0.0f), visExactCos(0.0f);
    for (std::size_t k = 0; k < objects.size(); ++k) {
      const gi::rtf::Field& f = *objects[k].field;
      const gi::rtf::Placement pl = gi::rtf::place(f, objects[k].world);
      const glm::vec3 q = (glm::vec3(pl.worldToLocal * glm::vec4(hit.position, 1.0f)) - f.centre) / f.radius;
      const gi::rtf::Lookup lk = gi::rtf::lookup(f.settings, q, objects[k].reach);
      const glm::mat3 toLocal = glm::transpose(pl.localToWorldDirections());
      const gi::rtf::ShRgb atO = gi::rtf::sourceRadiance(light.indirect(), pl.centreWorld);
      const glm::vec3 level = glm::vec3(atR[0]) / glm::max(glm::vec3(atO[0]), glm::vec3(1e-12f));
      gi::rtf::ShRgb lights[3] = {gi::rtf::toLocal(atR, pl), gi::rtf::toLocal(atO, pl), {}};
      lights[2] = lights[1];
      gi::rtf::ShRgb shapeO = lights[1];
      for (auto& c : shapeO) c *= level;
      const gi::rtf::ShRgb* useL[7] = {&lights[0], &shapeO, &lights[1], &lights[1], &lights[1], &lights[1], &lights[1]};
      const glm::vec3 nl = toLocal * n;
      for (int v = 0; v < 7; ++v) {
        std::vector<glm::vec3> notV(gi::rtf::kShCount, glm::vec3(0.0f));
        float total = 0.0f;
        for (int t = 0; t < 8; ++t) {
          const float w = lk.weight[std::size_t(t)];
          if (w == 0.0f) continue;
          total += w;
          const std::size_t smp = lk.sample[std::size_t(t)];
          const glm::vec3 sc = v == 3 ? glm::vec3(scales[k][smp]) : v == 4 ? glm::vec3(scalesEq3[k][smp]) : v == 5 ? glm::vec3(scalesSurf[k][smp]) : v == 6 ? glm::vec3(levels[k][smp]) : glm::vec3(1.0f);
          for (int j = 0; j < gi::rtf::kShCount; ++j)
            notV[std::size_t(j)] += w * sc * ((j == 0 ? 3.5449077f : 0.0f) - f.oof[smp * gi::rtf::kShCount + std::size_t(j)]);
        }
        if (total == 0.0f) continue;
        const auto b = sh::product<glm::vec3>(std::span<const glm::vec3>(notV), std::span<const glm::vec3>(*useL[v]), gi::rtf::kShOrder);
        const auto e = sh::convolveCosine<glm::vec3>(std::span<const glm::vec3>(b));
        variant[v] += rho / float(math::kPi) * sh::evalSum<glm::vec3, float>(std::span<const glm::vec3>(e).first(9), glm::normalize(nl));
      }
      // blocked-oof-at-r: the OOF projected AT r (no lookup), as the bake projects it, with the light at r:
      // what is left of blocked-receiver's error against blocked-probes is the SH truncation alone.
      float fade = 0.0f;  // the lookup's fade beyond the outermost sphere, as blocked-receiver's
      for (float w : lk.weight) fade += w;
      if (glm::length(q) < 3.0f * f.settings.outerRadius) {
        const glm::vec3 ql = glm::vec3(pl.worldToLocal * glm::vec4(hit.position, 1.0f));
        const glm::vec3 nn = glm::normalize(nl);
        std::vector<glm::vec3> notV(gi::rtf::kShCount, glm::vec3(0.0f));
        std::vector<char> hitDir(oofDirs.size(), 0);
        for (std::size_t di = 0; di < oofDirs.size(); ++di) {
          const Dir& d = oofDirs[di];
          ref::Hit oh;
          if (!objectBvh[k]->intersect(ql, d.w, 1e-5f * f.radius, 1e30f, oh)) continue;
          hitDir[di] = 1;
          for (int j = 0; j < gi::rtf::kShCount; ++j) notV[std::size_t(j)] += glm::vec3(float(d.y[std::size_t(j)]));
        }
        const auto b = sh::product<glm::vec3>(std::span<const glm::vec3>(notV), std::span<const glm::vec3>(lights[0]), gi::rtf::kShOrder);
        const auto e = sh::convolveCosine<glm::vec3>(std::span<const glm::vec3>(b));
        const glm::vec3 A = rho / float(math::kPi) * sh::evalSum<glm::vec3, float>(std::span<const glm::vec3>(e).first(9), nn);
        exactNoFade += A;
        exactV += fade * A;
        // The same integral with the exact clamped cosine (numerical over the cube directions): with the
        // order-4 (1 − V) (B), and with the exact visibility (C).
        glm::dvec3 B(0.0), C(0.0);
        for (std::size_t di = 0; di < oofDirs.size(); ++di) {
          const Dir& d = oofDirs[di];
          const double c = std::max(0.0, double(glm::dot(nn, d.w)));
          if (c <= 0.0) continue;
          const auto yb = sh::evalBasis<double>(gi::rtf::kShOrder, glm::dvec3(d.w));
          const double dw = d.solidAngle;
          glm::dvec3 L(0.0);
          double ov = 0.0;
          for (int j = 0; j < gi::rtf::kShCount; ++j) L += glm::dvec3(lights[0][std::size_t(j)]) * yb[std::size_t(j)], ov += double(notV[std::size_t(j)].x) * yb[std::size_t(j)];
          B += ov * L * c * dw;
          if (hitDir[di]) C += L * c * dw;
        }
        shExactCos += rho / float(math::kPi) * glm::vec3(B);
        visExactCos += rho / float(math::kPi) * glm::vec3(C);
      }
    }
    for (int v = 0; v < 4; ++v) put(kAtR + v, variant[v]);
    put(kEq3, variant[4]);
    put(kSurf, variant[5]);
    put(kLevel, variant[6]);
    put(kOofAtR, exactV);
    put(kOofNoFade, exactNoFade);
    put(kOofShExactCos, shExactCos);
    put(kVisExactCos, visExactCos);
  }, 16);
  // Per object A, over the receivers: the reference's interreflected light via A and its part that came to A
  // from the other objects, against RTF's (2 bounces − 1) over 1 bounce via A's field (Σ RGB, summed over pixels).
  for (std::size_t k = 0; k < objects.size(); ++k) {
    std::array<double, 4> t{};
    for (std::size_t px = 0; px < std::size_t(W) * H; ++px)
      for (int j = 0; j < 4; ++j) t[std::size_t(j)] += perObject[px * objects.size() + k][std::size_t(j)];
    std::fprintf(stderr,
                 "rtf_parts: object %zu (%s): reference interreflected %.4g, from other objects %.4g (%.3g); RTF 1 bounce %.4g, "
                 "2 bounces %.4g (second bounce %.3g of the first)\n",
                 k, with.registry.get<scene::Name>(rtfEntities[k]).id.c_str(), t[0], t[1], t[1] / std::max(t[0] - t[1], 1e-30), t[2], t[3],
                 (t[3] - t[2]) / std::max(t[2], 1e-30));
  }
  for (int i = 0; i < kParts; ++i) gpu::writePfm(out / (std::string(names[i]) + ".pfm"), images[std::size_t(i)]);
  std::fprintf(stderr, "rtf_parts: wrote %s\n", out.c_str());
  return 0;
}
