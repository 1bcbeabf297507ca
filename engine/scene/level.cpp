#include "engine/scene/level.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/gi/resolution.hpp"  // header only: the "sl" and "dnrt" "resolution" names, one table
#include "engine/scene/json_reader.hpp"
#include "engine/scene/motion.hpp"
#include "engine/scene/systems.hpp"
#include "engine/scene/transform_math.hpp"

namespace bounce::scene {

namespace {

constexpr std::size_t kMaxEntities = 1u << 20;
constexpr double kDegToRad = std::numbers::pi / 180.0;

struct ParseContext {
  std::filesystem::path dir;  // the level file's folder, absolute
};

// ---- one parser per entity key -------------------------------------------------------------

void parseTransform(const json::Node& node, EntityDesc& d, const ParseContext&) {
  const auto o = node.object({"translation", "rotation", "rotation_euler_deg", "scale"});
  if (auto t = o.optional("translation")) d.transform.translation = t->vec3();
  if (o.has("rotation") && o.has("rotation_euler_deg"))
    o.optional("rotation_euler_deg")->fail("both rotation and rotation_euler_deg given", "one of them");
  if (auto r = o.optional("rotation")) d.transform.rotation = parseQuaternion(*r);
  if (auto r = o.optional("rotation_euler_deg")) d.transform.rotation = quatFromEulerDeg(r->vec3());
  if (auto s = o.optional("scale")) d.transform.scale = parseScale(*s);
}

void parseMesh(const json::Node& node, EntityDesc& d, const ParseContext& ctx) {
  const auto o = node.object({"asset", "node", "subdivision"});
  MeshRef mesh;
  const auto asset = o.required("asset", "a .gltf or .glb path relative to the level file");
  const std::filesystem::path rel(asset.string());
  std::string ext = rel.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".gltf" && ext != ".glb") asset.fail("unsupported file type " + json::inQuotes(ext), "a .gltf or .glb file");
  mesh.asset = (ctx.dir / rel).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(mesh.asset, ec))
    asset.fail("file not found: " + json::printable(mesh.asset.string()), "an existing file, relative to the level file");
  if (auto n = o.optional("node")) {
    if (n->raw().is_string())
      mesh.node = n->string();
    else if (n->raw().is_number_integer() || n->raw().is_number_unsigned())
      mesh.node = std::uint32_t(n->integer(0, 0x7fffffff));
    else
      n->wrongType("a node name (string) or index (integer >= 0)");
  }
  if (auto s = o.optional("subdivision")) {
    const auto so = s->object({"scheme", "levels"});
    Subdivision sub;
    const auto scheme = so.required("scheme", "one of: catmull-clark, loop, bilinear");
    const std::string name = scheme.string();
    if (name == "catmull-clark")
      sub.scheme = SubdivisionScheme::CatmullClark;
    else if (name == "loop")
      sub.scheme = SubdivisionScheme::Loop;
    else if (name == "bilinear")
      sub.scheme = SubdivisionScheme::Bilinear;
    else
      scheme.fail("unknown scheme " + json::inQuotes(name), "one of: catmull-clark, loop, bilinear");
    sub.levels = int(so.required("levels", "an integer in [1, 4]").integer(1, 4));
    mesh.subdivision = sub;
  }
  d.mesh = std::move(mesh);
}

void parseMaterial(const json::Node& node, EntityDesc& d, const ParseContext&) {
  const auto o = node.object({"albedo", "emissive"});
  MaterialOverride m;
  if (auto a = o.optional("albedo")) m.albedo = a->vec3(json::Range::closed(0, 1));
  if (auto e = o.optional("emissive")) m.emissive = e->vec3(json::Range::atLeast(0));
  d.material = m;
}

void parseCamera(const json::Node& node, EntityDesc& d, const ParseContext&) {
  const auto o = node.object({"yfov_deg", "near", "far"});
  Camera c;
  if (auto f = o.optional("yfov_deg")) c.yfovRad = float(f->real(json::Range::open(0, 180)) * kDegToRad);
  double nearM = 0.05, farM = 100.0;  // defaults, metres
  if (auto n = o.optional("near")) {
    n->real(json::Range::greaterThan(0));  // also checks it fits a float
    nearM = n->real64(json::Range::greaterThan(0));
  }
  if (auto f = o.optional("far")) {
    f->real(json::Range::greaterThan(nearM));
    farM = f->real64(json::Range::greaterThan(nearM));
  } else if (farM <= nearM) {
    o.node().child("near").fail(json::formatNumber(nearM) + " is not below the default far 100",
                                "a near below far (give \"far\")");
  }
  c.near = float(nearM);
  c.far = float(farM);
  d.camera = c;
}

void parseLight(const json::Node& node, EntityDesc& d, const ParseContext&) {
  const auto o = node.object({"type", "color", "intensity", "range", "inner_cone_deg", "outer_cone_deg", "shadows",
                                 "radius"});
  Light l;
  const auto type = o.required("type", "one of: point, spot, directional");
  const std::string t = type.string();
  if (t == "point")
    l.type = LightType::Point;
  else if (t == "spot")
    l.type = LightType::Spot;
  else if (t == "directional")
    l.type = LightType::Directional;
  else
    type.fail("unknown light type " + json::inQuotes(t), "one of: point, spot, directional");
  if (auto c = o.optional("color")) l.color = c->vec3(json::Range::atLeast(0));
  if (auto i = o.optional("intensity")) l.intensity = i->real(json::Range::atLeast(0));
  if (auto r = o.optional("range")) l.range = r->real(json::Range::greaterThan(0));
  if (auto s = o.optional("shadows")) l.shadows = s->boolean();
  if (auto r = o.optional("radius")) {
    if (l.type == LightType::Directional) r->fail("a directional light has no position", "no radius");
    l.radius = r->real(json::Range::closed(0.0, 100.0));
  }
  for (const char* cone : {"inner_cone_deg", "outer_cone_deg"})
    if (l.type != LightType::Spot && o.has(cone)) o.node().child(cone).fail("only spot lights have cones", "no such key");
  double inner = 0.0, outer = 45.0;
  if (auto i = o.optional("inner_cone_deg")) inner = i->real64(json::Range::closedOpen(0, 90));
  if (auto oc = o.optional("outer_cone_deg")) {
    outer = oc->real64(json::Range::openClosed(inner, 90));
  } else if (inner >= outer) {
    o.node().child("inner_cone_deg").fail(json::formatNumber(inner) + " is not below the default outer cone 45",
                                          "inner < outer (give \"outer_cone_deg\")");
  }
  l.innerConeRad = float(inner * kDegToRad);
  l.outerConeRad = float(outer * kDegToRad);
  d.light = l;
}

// "dnrt": {"sh": 4|9, "grid": 16|32|64, "inner": 3, "outer": 6, "intrusion": false,
//          "anti_radiance": "paper"|"improved", "lights_in_anti_radiance": true, "rays": 256,
//          "mode": "box"|"fullscreen"|"clustered"|"fused"} — every key
//          optional (defaults above).
void parseDnrt(const json::Node& node, EntityDesc& d, const ParseContext&) {
  const auto o =
      node.object({"sh", "grid", "inner", "outer", "intrusion", "anti_radiance", "lights_in_anti_radiance", "rays", "mode"});
  Dnrt c;
  if (auto v = o.optional("sh")) {
    c.shCount = int(v->integer(0, 16));
    if (c.shCount != 4 && c.shCount != 9) v->fail("SH count " + std::to_string(c.shCount), "4 or 9");
  }
  if (auto v = o.optional("grid")) {
    c.grid = int(v->integer(0, 1024));
    if (c.grid != 16 && c.grid != 32 && c.grid != 64) v->fail("grid " + std::to_string(c.grid), "16, 32 or 64");
  }
  if (auto v = o.optional("inner")) c.innerExtent = v->real(json::Range::closed(1.0, 100.0));
  if (auto v = o.optional("outer")) c.outerExtent = v->real(json::Range::closed(1.0, 1000.0));
  if (!(c.outerExtent > c.innerExtent))
    (o.has("outer") ? o.node().child("outer") : o.node().child("inner"))
        .fail("outer extent " + json::formatNumber(c.outerExtent) + " is not above inner " +
                  json::formatNumber(c.innerExtent),
              "outer > inner (defaults 3 and 6)");
  if (auto v = o.optional("intrusion")) c.intrusion = v->boolean();
  if (auto v = o.optional("anti_radiance")) {
    const std::string m = v->string();
    if (m != "paper" && m != "improved") v->fail("unknown mode " + json::inQuotes(m), "paper or improved");
    c.improvedAntiRadiance = m == "improved";
  }
  if (auto v = o.optional("lights_in_anti_radiance")) c.lightsInAntiRadiance = v->boolean();
  if (auto v = o.optional("rays")) {
    const auto rays = v->integer(1, 65536);
    const auto side = std::int64_t(std::lround(std::sqrt(double(rays))));
    if (side * side != rays) v->fail(std::to_string(rays) + " is not a square", "a square number (e.g. 64, 256)");
    c.samplesPerAxis = int(side);
  }
  if (auto v = o.optional("mode")) {
    const std::string m = v->string();
    if (m != "box" && m != "fullscreen" && m != "clustered" && m != "fused")
      v->fail("unknown mode " + json::inQuotes(m), "box, fullscreen, clustered or fused");
    c.mode = m == "fullscreen"  ? DnrtMode::FullScreen
             : m == "clustered" ? DnrtMode::Clustered
             : m == "fused"     ? DnrtMode::Fused
                                : DnrtMode::Box;
  }
  d.dnrt = c;
}

// "sl": {"spheres": 1..64, "order": 3|4, "blocking": "per-sphere"|"per-object", "influence": 0|3..1000,
//        "resolution": "full"|"half"|"quarter", "local_lights": bool, "hierarchy": bool, "fused": bool,
//        "blocked_light": "receiver"|"sphere", "blocked_read": "sh"|"map"} — every key optional (defaults 16, 4,
//        per-sphere, 12, full, false, false, true, receiver, sh); "sphere" with "hierarchy": true is refused,
//        "map" needs "sphere". The sphere limit is gi::sl::kMaxSpheres
//        (one uint64 mask).
void parseSl(const json::Node& node, EntityDesc& d, const ParseContext&) {
  const auto o = node.object(
      {"spheres", "order", "blocking", "influence", "resolution", "local_lights", "hierarchy", "fused", "blocked_light",
       "blocked_read"});
  Sl c;
  if (auto v = o.optional("spheres")) c.spheres = int(v->integer(1, 64));
  if (auto v = o.optional("order")) {
    c.order = int(v->integer(0, 16));
    if (c.order != 3 && c.order != 4) v->fail("SH order " + std::to_string(c.order), "3 or 4");
  }
  if (auto v = o.optional("blocking")) {
    const std::string m = v->string();
    if (m != "per-sphere" && m != "per-object") v->fail("unknown blocking " + json::inQuotes(m), "per-sphere or per-object");
    c.perObject = m == "per-object";
  }
  if (auto v = o.optional("influence")) {
    const double f = v->real(json::Range::closed(0.0, 1000.0));
    if (f > 0.0 && f < 3.0) {
      char text[64];
      std::snprintf(text, sizeof text, "influence %g", f);
      v->fail(text, "0 (off) or 3..1000 sphere radii");
    }
    c.influence = float(f);
  }
  if (auto v = o.optional("resolution")) {
    const std::string m = v->string();
    const std::optional<std::uint32_t> step = gi::parseResolution(m);
    if (!step) v->fail("unknown resolution " + json::inQuotes(m), gi::kResolutionNames);
    c.step = int(*step);
  }
  if (auto v = o.optional("local_lights")) c.localLights = v->boolean();
  if (auto v = o.optional("hierarchy")) c.hierarchy = v->boolean();
  if (auto v = o.optional("fused")) c.fused = v->boolean();
  if (auto v = o.optional("blocked_light")) {
    const std::string m = v->string();
    if (m != "receiver" && m != "sphere") v->fail("unknown blocked_light " + json::inQuotes(m), "receiver or sphere");
    c.blockedAtSphere = m == "sphere";
    if (c.blockedAtSphere && c.hierarchy)
      v->fail("blocked_light \"sphere\" with \"hierarchy\": true", "\"receiver\" with the hierarchy (its parents read the receiver's SH)");
  }
  if (auto v = o.optional("blocked_read")) {
    const std::string m = v->string();
    if (m != "sh" && m != "map") v->fail("unknown blocked_read " + json::inQuotes(m), "sh or map");
    c.blockedMap = m == "map";
    if (c.blockedMap && !c.blockedAtSphere)
      v->fail("blocked_read \"map\" without blocked_light \"sphere\"", "\"sh\", or \"blocked_light\": \"sphere\" (the map is read at the SLs)");
  }
  d.sl = c;
}

// "rtf": {"proxies": 1..64, "bounces": 1..4, "spheres": 2..64, "face": 1..64, "rays": 1..256,
//         "vertex_rays": 1..256, "clusters": 1..4096, "components": 0..256, "byte_components": 0..components,
//         "inner": η, "outer": η, "sh": 4|9, "tail": [0, 1)} — every key optional (defaults in components.hpp
//         Rtf); 0 < inner < outer ≤ 100.
void parseRtf(const json::Node& node, EntityDesc& d, const ParseContext&) {
  const auto o = node.object({"proxies", "bounces", "spheres", "face", "rays", "vertex_rays", "clusters", "components",
                              "byte_components", "inner", "outer", "sh", "tail"});
  Rtf c;
  if (auto v = o.optional("proxies")) c.proxies = int(v->integer(1, 64));
  if (auto v = o.optional("bounces")) c.bounces = int(v->integer(1, 4));
  if (auto v = o.optional("spheres")) c.spheres = int(v->integer(2, 64));
  if (auto v = o.optional("face")) c.face = int(v->integer(1, 64));
  if (auto v = o.optional("rays")) c.rays = int(v->integer(1, 256));
  if (auto v = o.optional("vertex_rays")) c.vertexRays = int(v->integer(1, 256));
  if (auto v = o.optional("clusters")) c.clusters = int(v->integer(1, 4096));
  if (auto v = o.optional("components")) c.components = int(v->integer(0, 256));
  if (auto v = o.optional("byte_components")) {
    c.byteComponents = int(v->integer(0, 256));
    if (c.byteComponents > c.components)
      v->fail(std::to_string(c.byteComponents) + " is above components " + std::to_string(c.components),
              "an integer in [0, components]: the 8-bit tail is part of the components");
  }
  if (auto v = o.optional("inner")) c.inner = v->real(json::Range::openClosed(0.0, 100.0));
  if (auto v = o.optional("outer")) c.outer = v->real(json::Range::openClosed(0.0, 100.0));
  if (auto v = o.optional("sh")) {
    c.sh = int(v->integer(0, 16));
    if (c.sh != 4 && c.sh != 9) v->fail("SH count " + std::to_string(c.sh), "4 or 9");
  }
  if (auto v = o.optional("tail")) c.tail = v->real(json::Range::closedOpen(0.0, 1.0));
  if (!(c.outer > c.inner))
    (o.has("outer") ? o.node().child("outer") : o.node().child("inner"))
        .fail("outer radius " + json::formatNumber(c.outer) + " is not above inner " + json::formatNumber(c.inner),
              "outer > inner (defaults 0.5 and 4)");
  d.rtf = c;
}

// "vlm": {"tag": int ≥ 1, "color": [r,g,b], "intensity": float, "reflectance": [r,g,b]} — tag
// required; the mesh is attached in parseEntity (the "mesh" key is read first).
void parseVlm(const json::Node& node, EntityDesc& d, const ParseContext&) {
  const auto o = node.object({"tag", "color", "intensity", "reflectance"});
  Vlm v;
  v.tag = int(o.required("tag", "an integer id >= 1").integer(1, 1 << 24));
  if (auto c = o.optional("color")) v.color = c->vec3(json::Range::atLeast(0));
  if (auto i = o.optional("intensity")) v.intensity = i->real(json::Range::closed(0, 1e6));
  if (auto r = o.optional("reflectance")) v.reflectance = r->vec3(json::Range::closed(0, 1));
  d.vlm = v;
}

// "overrides": {"TAG": {"intensity": x, "color": [r,g,b], "hue_deg": h}}: keys are decimal tags
// (1 ≤ TAG ≤ 2^24, no sign, no leading zero), every inner key optional.
std::map<int, VlmOverride> parseVlmOverrides(const json::Node& node) {
  if (!node.raw().is_object()) node.wrongType("an object {\"TAG\": {\"intensity\": x, \"color\": [r, g, b], \"hue_deg\": h}}");
  std::map<int, VlmOverride> out;
  for (const auto& [key, _] : node.raw().items()) {
    const json::Node entry = node.child(key);
    const bool digits = !key.empty() && key.size() <= 8 && key[0] != '0' &&
                        key.find_first_not_of("0123456789") == std::string::npos;
    if (!digits || std::stoi(key) > (1 << 24))
      entry.fail("key " + json::inQuotes(key) + " is not a tag", "a decimal tag id in [1, 16777216]");
    const auto o = entry.object({"intensity", "color", "hue_deg"});
    VlmOverride v;
    if (auto i = o.optional("intensity")) v.intensity = i->real(json::Range::closed(0, 1e6));
    if (auto c = o.optional("color")) v.color = c->vec3(json::Range::atLeast(0));
    if (auto h = o.optional("hue_deg")) v.hueDeg = h->real(json::Range::closed(-360, 360));
    out[std::stoi(key)] = v;
  }
  return out;
}

void parseVlmTag(const json::Node& node, EntityDesc& d, const ParseContext&) {
  d.vlmTag = VlmTag{int(node.integer(1, 1 << 24))};
}

// A `vlm` entity's mesh is virtual-light geometry: it goes into the Vlm component, not MeshRef,
// so the renderer and the reference never see it as real geometry.
void emplaceMesh(const EntityDesc& d, ecs::Registry& r, ecs::Entity e) {
  if (d.mesh && !d.vlm) r.emplace<MeshRef>(e, *d.mesh);
}

void parseMotionKey(const json::Node& node, EntityDesc& d, const ParseContext&) { d.motion = parseMotion(node); }

// "animation": false, or {"clip": name | index, "speed": x, "mode": "loop" | "ping-pong" | "once",
// "phase_s": s} — every key optional. The clip name is checked against the asset when the asset is
// cooked (engine/anim/animator.cpp), since loading a level never opens its assets.
void parseAnimation(const json::Node& node, EntityDesc& d, const ParseContext&) {
  AnimationClip a;
  a.file = node.file();
  a.pointer = node.pointer();
  if (node.raw().is_boolean()) {
    if (node.boolean()) node.fail("true", "false (hold the rest pose) or an object {\"clip\": …}");
    a.enabled = false;
    d.animation = a;
    return;
  }
  const auto o = node.object({"clip", "speed", "mode", "phase_s"});
  if (auto c = o.optional("clip")) {
    if (c->raw().is_string())
      a.clip = c->string();
    else if (c->raw().is_number_integer() || c->raw().is_number_unsigned())
      a.clip = std::uint32_t(c->integer(0, 0x7fffffff));
    else
      c->wrongType("a clip name (string) or index (integer >= 0)");
  }
  if (auto v = o.optional("speed")) a.speed = v->real(json::Range::closed(-100, 100));
  if (auto v = o.optional("mode")) {
    const std::string m = v->string();
    if (m == "loop") a.mode = PlayMode::Loop;
    else if (m == "ping-pong") a.mode = PlayMode::PingPong;
    else if (m == "once") a.mode = PlayMode::Once;
    else v->fail("unknown mode " + json::inQuotes(m), "one of: loop, ping-pong, once");
  }
  if (auto v = o.optional("phase_s")) a.phaseS = v->real(json::Range::closed(-1e6, 1e6));
  d.animation = a;
}

// ---- the table ------------------------------------------------------------------------------
// A component key: how to read it into EntityDesc and how to put it on an entity. Adding a
// technique component (dnrt, vlm, …) is: a field in EntityDesc, a parse function, one row here.
struct ComponentKey {
  std::string_view key;
  void (*parse)(const json::Node&, EntityDesc&, const ParseContext&);
  void (*emplace)(const EntityDesc&, ecs::Registry&, ecs::Entity);
};

template <auto Field>
void emplaceIfSet(const EntityDesc& d, ecs::Registry& r, ecs::Entity e) {
  if (const auto& v = d.*Field) r.emplace<std::decay_t<decltype(*v)>>(e, *v);
}

const ComponentKey kComponentKeys[] = {
    {"transform", parseTransform, nullptr},  // every entity gets a Transform: see instantiate()
    {"mesh", parseMesh, emplaceMesh},
    {"material", parseMaterial, emplaceIfSet<&EntityDesc::material>},
    {"camera", parseCamera, emplaceIfSet<&EntityDesc::camera>},
    {"light", parseLight, emplaceIfSet<&EntityDesc::light>},
    {"motion", parseMotionKey, emplaceIfSet<&EntityDesc::motion>},
    {"animation", parseAnimation, emplaceIfSet<&EntityDesc::animation>},
    {"dnrt", parseDnrt, emplaceIfSet<&EntityDesc::dnrt>},
    {"sl", parseSl, emplaceIfSet<&EntityDesc::sl>},
    {"rtf", parseRtf, emplaceIfSet<&EntityDesc::rtf>},
    {"vlm", parseVlm, emplaceIfSet<&EntityDesc::vlm>},
    {"vlm_tag", parseVlmTag, emplaceIfSet<&EntityDesc::vlmTag>},
};

std::vector<std::string_view> entityKeys() {
  std::vector<std::string_view> keys{"id", "parent", "dynamic"};
  for (const auto& c : kComponentKeys) keys.push_back(c.key);
  return keys;
}

EntityDesc parseEntity(const json::Node& node, const ParseContext& ctx) {
  static const std::vector<std::string_view> kKeys = entityKeys();
  const auto o = node.object(kKeys);
  EntityDesc d;
  d.pointer = node.pointer();
  d.id = o.required("id", "a unique string id").string();
  if (auto p = o.optional("parent")) d.parent = p->string();
  for (const auto& c : kComponentKeys)
    if (auto v = o.optional(c.key)) c.parse(*v, d, ctx);
  if (auto dyn = o.optional("dynamic")) {
    d.dynamic = dyn->boolean();
    if (!d.dynamic && d.motion) dyn->fail("false, but the entity has a motion", "true, or no \"dynamic\" key");
  }
  if (d.motion) {
    d.dynamic = true;
    d.motion->base = d.transform;
  }
  if (d.animation && !d.mesh) o.node().child("animation").fail("an animation on an entity without a mesh", "a \"mesh\" key");
  if (d.dnrt && !d.mesh) o.node().child("dnrt").fail("a DNRT field on an entity without a mesh", "a \"mesh\" key");
  if (d.dnrt && !d.dynamic)
    o.node().child("dnrt").fail("a DNRT field on a static entity", "\"dynamic\": true or a motion");
  if (d.sl && !d.mesh) o.node().child("sl").fail("spherical lights on an entity without a mesh", "a \"mesh\" key");
  if (d.sl && !d.dynamic)
    o.node().child("sl").fail("spherical lights on a static entity", "\"dynamic\": true or a motion");
  if (d.rtf && !d.mesh) o.node().child("rtf").fail("a radiance transfer field on an entity without a mesh", "a \"mesh\" key");
  if (d.rtf && !d.dynamic)
    o.node().child("rtf").fail("a radiance transfer field on a static entity", "\"dynamic\": true or a motion");
  if (d.vlm) {
    if (!d.mesh) o.node().child("vlm").fail("a VLM on an entity without a mesh", "a \"mesh\" key");
    if (d.dnrt) o.node().child("dnrt").fail("a DNRT field on a VLM entity (not drawn)", "no \"dnrt\" key");
    if (d.sl) o.node().child("sl").fail("spherical lights on a VLM entity (not drawn)", "no \"sl\" key");
    if (d.rtf) o.node().child("rtf").fail("a radiance transfer field on a VLM entity (not drawn)", "no \"rtf\" key");
    if (d.vlmTag) o.node().child("vlm_tag").fail("a vlm_tag on a VLM entity (the tag is in \"vlm\")", "no \"vlm_tag\" key");
    d.vlm->mesh = *d.mesh;
    if (d.material) d.vlm->albedoOverride = d.material->albedo;
  }
  return d;
}

// Duplicate ids, unknown parents, parent cycles (reported at the cycle member first in file order).
void checkHierarchy(const std::vector<EntityDesc>& es, const json::Node& entities) {
  std::unordered_map<std::string, std::size_t> byId;
  for (std::size_t i = 0; i < es.size(); ++i) {
    auto [it, fresh] = byId.emplace(es[i].id, i);
    if (!fresh)
      entities.element(i).child("id").fail("duplicate id " + json::inQuotes(es[i].id),
                                           "a unique id; first used at " + es[it->second].pointer + "/id");
  }
  std::vector<std::size_t> parentOf(es.size(), SIZE_MAX);
  for (std::size_t i = 0; i < es.size(); ++i) {
    if (!es[i].parent) continue;
    auto it = byId.find(*es[i].parent);
    if (it == byId.end())
      entities.element(i).child("parent").fail("unknown id " + json::inQuotes(*es[i].parent),
                                               "the id of another entity in this level");
    parentOf[i] = it->second;
  }
  // Walk each chain once: 0 = unvisited, 1 = on the current path, 2 = known acyclic.
  std::vector<std::uint8_t> state(es.size(), 0);
  for (std::size_t start = 0; start < es.size(); ++start) {
    std::vector<std::size_t> path;
    std::size_t cur = start;
    while (cur != SIZE_MAX && state[cur] == 0) {
      state[cur] = 1;
      path.push_back(cur);
      cur = parentOf[cur];
    }
    if (cur != SIZE_MAX && state[cur] == 1) {
      std::vector<std::size_t> cycle(std::find(path.begin(), path.end(), cur), path.end());
      std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
      constexpr std::size_t kShown = 8;  // keep the message one readable line
      std::string chain;
      for (std::size_t k = 0; k < std::min(cycle.size(), kShown); ++k) chain += json::inQuotes(es[cycle[k]].id) + " -> ";
      chain += cycle.size() > kShown ? "... -> " + json::inQuotes(es[cycle[0]].id) : json::inQuotes(es[cycle[0]].id);
      entities.element(cycle[0]).child("parent").fail("parent cycle " + chain, "a hierarchy without cycles");
    }
    for (std::size_t p : path) state[p] = 2;
  }
}

Level levelFromJson(const nlohmann::json& doc, const std::filesystem::path& pathIn) {
  const std::string file = pathIn.string();
  const json::Node root(doc, "", file);
  if (doc.is_object() && doc.contains("bounce_capture") && !doc.contains("bounce_level"))
    throwInputError(file, "/bounce_capture", "this is a capture script, not a level",
                    "a level (\"bounce_level\": 1); run a capture script with 'bounce capture SCRIPT --out DIR'");
  const auto o = root.object({"bounce_level", "name", "effects", "background", "probes", "dnrt", "rtf", "vlm", "entities"});

  const auto version = o.required("bounce_level", "the format version 1");
  if (const auto v = version.integer(0, 1 << 30); v != 1)
    version.fail("unsupported version " + std::to_string(v), "1");

  Level level;
  level.source = std::filesystem::absolute(pathIn).lexically_normal();
  const ParseContext ctx{level.source.parent_path()};
  level.name = pathIn.stem().string();
  if (auto n = o.optional("name")) level.name = n->string();

  const auto effects = o.required("effects", "an array of effect names (one of: " + knownEffectNames() + ")");
  level.effects = parseEffects(effects);
  if (auto b = o.optional("background")) level.background = b->vec3(json::Range::atLeast(0));
  if (auto p = o.optional("probes")) {
    const auto po = p->object({"spacing", "order", "rays", "relight", "sl_bounce"});
    if (auto v = po.optional("relight")) level.probes.relight = v->boolean();
    if (auto v = po.optional("sl_bounce")) {
      level.probes.slBounce = v->boolean();
      if (level.probes.slBounce && !level.probes.relight) v->fail("sl_bounce without relight", "\"relight\": true with it");
    }
    if (auto v = po.optional("spacing")) level.probes.spacing = float(v->real(json::Range::closed(1e-3, 1e3)));
    if (auto v = po.optional("order")) {
      level.probes.order = int(v->integer(0, 16));
      if (level.probes.order != 2 && level.probes.order != 3)
        v->fail("SH order " + std::to_string(level.probes.order), "2 or 3");
    }
    if (auto v = po.optional("rays")) {
      const auto rays = v->integer(64, 65536);
      const auto root = std::int64_t(std::lround(std::sqrt(double(rays))));
      if (root * root != rays || root % 8 != 0)
        v->fail(std::to_string(rays) + " rays", "a square whose root is a multiple of 8 (64, 256, 576, 1024, ...)");
      level.probes.rays = std::uint32_t(rays);
    }
  }

  // "dnrt": {"resolution": "full"|"half"|"quarter"} — the DNRT draw's resolution for every object, and
  // "rtf": {"resolution": …} the RTF shading draws' (the same names and steps as SL pass 2's,
  // gi/resolution.hpp; default full).
  const auto resolutionOf = [&o](const char* key, std::uint32_t& step) {
    if (auto p = o.optional(key)) {
      const auto obj = p->object({"resolution"});
      if (auto v = obj.optional("resolution")) {
        const std::string m = v->string();
        const std::optional<std::uint32_t> parsed = gi::parseResolution(m);
        if (!parsed) v->fail("unknown resolution " + json::inQuotes(m), gi::kResolutionNames);
        step = *parsed;
      }
    }
  };
  resolutionOf("dnrt", level.dnrt.step);
  resolutionOf("rtf", level.rtf.step);

  if (auto p = o.optional("vlm")) {
    const auto vo = p->object({"grid", "k", "range", "overrides", "conservative_threshold"});
    if (auto v = vo.optional("grid")) level.vlm.grid = int(v->integer(1, 256));
    if (auto v = vo.optional("k")) level.vlm.k = int(v->integer(1, 256));
    if (auto v = vo.optional("range")) level.vlm.range = float(v->real(json::Range::closed(1.0, 100.0)));
    if (auto v = vo.optional("overrides")) level.vlm.overrides = parseVlmOverrides(*v);
    // Conservative overflow mode: a light is dropped from a cell only below this irradiance bound.
    if (auto v = vo.optional("conservative_threshold"))
      level.vlm.conservativeThreshold = float(v->real(json::Range::greaterThan(0.0)));
  }

  const auto entities = o.required("entities", "an array of entities");
  for (const auto& e : entities.array(0, kMaxEntities, "at most " + std::to_string(kMaxEntities) + " entities"))
    level.entities.push_back(parseEntity(e, ctx));
  checkHierarchy(level.entities, entities);
  return level;
}

}  // namespace

Level loadLevel(const std::filesystem::path& path) { return levelFromJson(json::parseFile(path), path); }

Level parseLevel(std::string_view text, const std::filesystem::path& path) {
  return levelFromJson(json::parse(text, path.string()), path);
}

void overrideEffects(Level& level, std::string_view list) { level.effects = parseEffectList(list, level.source.string()); }

std::vector<ecs::Entity> instantiate(const Level& level, ecs::Registry& registry) {
  const auto& es = level.entities;
  // Check the invariants loadLevel guarantees before touching the registry.
  std::unordered_map<std::string, std::size_t> byId;
  for (std::size_t i = 0; i < es.size(); ++i)
    if (!byId.emplace(es[i].id, i).second) throw InternalError("scene: instantiate: duplicate id \"" + es[i].id + "\"");
  std::vector<std::size_t> parentOf(es.size(), SIZE_MAX);
  for (std::size_t i = 0; i < es.size(); ++i) {
    if (!es[i].parent) continue;
    auto it = byId.find(*es[i].parent);
    if (it == byId.end()) throw InternalError("scene: instantiate: unknown parent \"" + *es[i].parent + "\"");
    parentOf[i] = it->second;
  }
  // Depth of each entity (memoised walk up the chain: O(n) in total even for one long chain).
  constexpr std::size_t kUnknown = SIZE_MAX;
  std::vector<std::size_t> depth(es.size(), kUnknown);
  for (std::size_t i = 0; i < es.size(); ++i) {
    std::vector<std::size_t> chain;
    std::size_t cur = i;
    while (cur != SIZE_MAX && depth[cur] == kUnknown) {
      chain.push_back(cur);
      if (chain.size() > es.size()) throw InternalError("scene: instantiate: parent cycle at \"" + es[i].id + "\"");
      cur = parentOf[cur];
    }
    std::size_t d = cur == SIZE_MAX ? 0 : depth[cur] + 1;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) depth[*it] = d++;
  }
  std::vector<ecs::Entity> out;
  out.reserve(es.size());
  for (std::size_t i = 0; i < es.size(); ++i) out.push_back(registry.create());
  bool haveActive = registry.view<ActiveCamera>().front() != ecs::Entity::null();
  for (std::size_t i = 0; i < es.size(); ++i) {
    const EntityDesc& d = es[i];
    const ecs::Entity e = out[i];
    registry.emplace<Name>(e, d.id);
    registry.emplace<Transform>(e, d.transform);
    registry.emplace<WorldTransform>(e);
    if (parentOf[i] != SIZE_MAX) registry.emplace<Parent>(e, out[parentOf[i]]);
    if (d.dynamic || d.motion) registry.emplace<Dynamic>(e);
    for (const auto& c : kComponentKeys)
      if (c.emplace) c.emplace(d, registry, e);
    if (d.camera && !haveActive) {
      registry.emplace<ActiveCamera>(e);
      haveActive = true;
    }
  }
  // World transforms, parents before children (stable by file order within a depth).
  std::vector<std::size_t> order(es.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
  for (std::size_t i : order) {
    const glm::mat4 local = toMatrix(es[i].transform);
    registry.get<WorldTransform>(out[i]).matrix =
        parentOf[i] == SIZE_MAX ? local : registry.get<WorldTransform>(out[parentOf[i]]).matrix * local;
  }
  return out;
}

}  // namespace bounce::scene
