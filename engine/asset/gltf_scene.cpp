// glTF 2.0 scene import: node hierarchy, cameras, KHR_lights_punctual, skins, animations and the
// default scene. The hierarchy must be a forest (glTF 2.0 §3.5.2: "no node may be a direct
// descendant of more than one node", no cycles); both are checked and reported with the child
// reference that breaks the rule.
#include "engine/asset/accessors.hpp"
#include "engine/asset/gltf_import.hpp"
#include "engine/core/error.hpp"
#include "engine/core/log.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace bounce::asset::detail {

namespace {

void checkIndex(const ImportContext& ctx, const std::string& where, int index, std::size_t size, const char* what) {
  if (index < 0 || std::size_t(index) >= size)
    ctx.fail(where, std::string(what) + " index " + std::to_string(index) + " out of range",
             "0 ≤ index < " + std::to_string(size));
}

float finite(const ImportContext& ctx, const std::string& where, double v) {
  if (!std::isfinite(v) || std::fabs(v) > 3.0e38) ctx.fail(where, "number is not finite", "a finite number");
  return float(v);
}

Subdivision parseSubdivision(const ImportContext& ctx, const tinygltf::Value& v, const std::string& where) {
  if (!v.IsObject()) ctx.fail(where, "not an object", "{\"scheme\": …, \"levels\": N}");
  Subdivision s;
  const tinygltf::Value& scheme = v.Get("scheme");
  const std::string name = scheme.IsString() ? scheme.Get<std::string>() : std::string();
  if (name == "catmull-clark") s.scheme = SubdivisionScheme::CatmullClark;
  else if (name == "loop") s.scheme = SubdivisionScheme::Loop;
  else if (name == "bilinear") s.scheme = SubdivisionScheme::Bilinear;
  else ctx.fail(where + "/scheme", "unknown scheme \"" + name + "\"", "catmull-clark, loop or bilinear");
  const tinygltf::Value& levels = v.Get("levels");
  if (!levels.IsInt() || levels.GetNumberAsInt() < 0 || levels.GetNumberAsInt() > 4)
    ctx.fail(where + "/levels", "missing or out of range", "an integer from 0 to 4");
  s.levels = std::uint32_t(levels.GetNumberAsInt());
  return s;
}

// extras.bounce_vlm: {"tag": N, "color": [r,g,b], "intensity": x, "reflectance": [r,g,b]}, tag required
// (1 ≤ N ≤ 2^24, as the level's "vlm" component), colour ≥ 0, intensity in [0, 1e6], reflectance in
// [0, 1]; unknown keys are errors (a typo would silently change the light otherwise).
NodeVlm parseVlmExtras(const ImportContext& ctx, const tinygltf::Value& v, const std::string& where, bool hasMesh) {
  const std::string form = "{\"tag\": N, \"color\": [r, g, b], \"intensity\": x, \"reflectance\": [r, g, b]}";
  if (!v.IsObject()) ctx.fail(where, "not an object", form);
  if (!hasMesh) ctx.fail(where, "a VLM on a node without a mesh", "bounce_vlm on a node with a mesh");
  for (const std::string& key : v.Keys())
    if (key != "tag" && key != "color" && key != "intensity" && key != "reflectance")
      ctx.fail(where + "/" + key, "unknown key \"" + key + "\"", "one of: tag, color, intensity, reflectance");
  auto number = [&](const tinygltf::Value& x, const std::string& at, double lo, double hi, const std::string& expected) {
    const double d = x.IsNumber() ? x.GetNumberAsDouble() : std::nan("");
    if (!(d >= lo && d <= hi)) ctx.fail(at, x.IsNumber() ? "out of range" : "not a number", expected);
    return d;
  };
  auto vec3 = [&](const char* key, double lo, double hi, const std::string& expected) {
    const tinygltf::Value& a = v.Get(key);
    const std::string at = where + "/" + key;
    if (!a.IsArray() || a.ArrayLen() != 3) ctx.fail(at, "not an array of 3 numbers", expected);
    glm::vec3 out;
    for (int k = 0; k < 3; ++k) out[k] = float(number(a.Get(k), ptr(at, std::size_t(k)), lo, hi, expected));
    return out;
  };
  NodeVlm n;
  n.present = true;
  if (!v.Has("tag")) ctx.fail(where, "missing required key \"tag\"", "an integer id >= 1");
  const tinygltf::Value& tag = v.Get("tag");
  const double t = number(tag, where + "/tag", 1, double(1 << 24), "an integer id in [1, 16777216]");
  if (t != std::floor(t)) ctx.fail(where + "/tag", "not an integer", "an integer id in [1, 16777216]");
  n.tag = std::uint32_t(t);
  if ((n.hasColor = v.Has("color"))) n.color = vec3("color", 0.0, 3e38, "3 numbers >= 0");
  if ((n.hasIntensity = v.Has("intensity")))
    n.intensity = float(number(v.Get("intensity"), where + "/intensity", 0.0, 1e6, "a number in [0, 1e6]"));
  if ((n.hasReflectance = v.Has("reflectance"))) n.reflectance = vec3("reflectance", 0.0, 1.0, "3 numbers in [0, 1]");
  return n;
}

void importNodes(const ImportContext& ctx, CookedAsset& out) {
  const auto& m = ctx.model;
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    const tinygltf::Node& src = m.nodes[i];
    const std::string where = ptr("/nodes", i);
    Node n;
    n.name = src.name;
    if (!src.matrix.empty()) {
      if (src.matrix.size() != 16) ctx.fail(where + "/matrix", "has " + std::to_string(src.matrix.size()) + " values", "16");
      n.hasMatrix = true;
      for (int k = 0; k < 16; ++k) glm::value_ptr(n.matrix)[k] = finite(ctx, where + "/matrix", src.matrix[std::size_t(k)]);
    }
    auto vec = [&](const std::vector<double>& v, std::size_t size, const char* key, float* dst) {
      if (v.empty()) return;
      if (v.size() != size) ctx.fail(where + "/" + key, "has " + std::to_string(v.size()) + " values", std::to_string(size));
      for (std::size_t k = 0; k < size; ++k) dst[k] = finite(ctx, where + "/" + key, v[k]);
    };
    vec(src.translation, 3, "translation", glm::value_ptr(n.translation));
    vec(src.scale, 3, "scale", glm::value_ptr(n.scale));
    if (!src.rotation.empty()) {
      float q[4];
      vec(src.rotation, 4, "rotation", q);
      n.rotation = glm::quat(q[3], q[0], q[1], q[2]);  // glTF stores x, y, z, w
    }
    for (std::size_t c = 0; c < src.children.size(); ++c) {
      checkIndex(ctx, ptr(where + "/children", c), src.children[c], m.nodes.size(), "node");
      n.children.push_back(src.children[c]);
    }
    if (src.mesh != -1) checkIndex(ctx, where + "/mesh", src.mesh, m.meshes.size(), "mesh");
    if (src.camera != -1) checkIndex(ctx, where + "/camera", src.camera, m.cameras.size(), "camera");
    if (src.skin != -1) checkIndex(ctx, where + "/skin", src.skin, m.skins.size(), "skin");
    n.mesh = src.mesh;
    n.camera = src.camera;
    n.skin = src.skin;
    if (auto it = src.extensions.find("KHR_lights_punctual"); it != src.extensions.end()) {
      const tinygltf::Value& light = it->second.Get("light");
      const std::string lw = where + "/extensions/KHR_lights_punctual/light";
      if (!light.IsInt()) ctx.fail(lw, "missing or not an integer", "a light index");
      checkIndex(ctx, lw, light.GetNumberAsInt(), m.lights.size(), "light");
      n.light = light.GetNumberAsInt();
    }
    if (src.extras.IsObject() && src.extras.Has("subdivision"))
      n.subdivision = parseSubdivision(ctx, src.extras.Get("subdivision"), where + "/extras/subdivision");
    if (src.extras.IsObject() && src.extras.Has("bounce_vlm"))
      n.vlm = parseVlmExtras(ctx, src.extras.Get("bounce_vlm"), where + "/extras/bounce_vlm", src.mesh != -1);
    out.nodes.push_back(std::move(n));
  }

  // Forest check: at most one parent each, then no cycle (a cycle of single-parent nodes has no
  // root, so walking up from any of its nodes never ends).
  std::vector<int> parent(m.nodes.size(), -1);
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    for (std::size_t c = 0; c < m.nodes[i].children.size(); ++c) {
      const int child = m.nodes[i].children[c];
      const std::string where = ptr(ptr("/nodes", i) + "/children", c);
      if (std::size_t(child) == i) ctx.fail(where, "node " + std::to_string(i) + " is its own child (cycle)", "an acyclic node graph");
      if (parent[std::size_t(child)] != -1)
        ctx.fail(where, "node " + std::to_string(child) + " already has parent " + std::to_string(parent[std::size_t(child)]),
                 "each node to have at most one parent");
      parent[std::size_t(child)] = int(i);
    }
  std::vector<char> state(m.nodes.size(), 0);  // 0 unknown, 1 on the current walk, 2 reaches a root
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    std::vector<std::size_t> walk;
    std::size_t at = i;
    while (state[at] == 0) {
      state[at] = 1;
      walk.push_back(at);
      if (parent[at] == -1) break;
      at = std::size_t(parent[at]);
    }
    if (state[at] == 1 && parent[at] != -1)
      ctx.fail(ptr("/nodes", std::size_t(parent[at])) + "/children",
               "node " + std::to_string(at) + " is its own ancestor (cycle)", "an acyclic node graph");
    for (std::size_t w : walk) state[w] = 2;
  }

  // Roots of the default scene (or of the first scene; with no scene, every parentless node).
  if (m.scenes.empty()) {
    for (std::size_t i = 0; i < m.nodes.size(); ++i)
      if (parent[i] == -1) out.rootNodes.push_back(int(i));
    return;
  }
  const int scene = m.defaultScene == -1 ? 0 : m.defaultScene;
  checkIndex(ctx, "/scene", scene, m.scenes.size(), "scene");
  const auto& roots = m.scenes[std::size_t(scene)].nodes;
  for (std::size_t r = 0; r < roots.size(); ++r) {
    const std::string where = ptr(ptr("/scenes", std::size_t(scene)) + "/nodes", r);
    checkIndex(ctx, where, roots[r], m.nodes.size(), "node");
    if (parent[std::size_t(roots[r])] != -1)
      ctx.fail(where, "node " + std::to_string(roots[r]) + " has a parent", "scene roots to be root nodes");
    out.rootNodes.push_back(roots[r]);
  }
}

void importCameras(const ImportContext& ctx, CookedAsset& out) {
  for (std::size_t i = 0; i < ctx.model.cameras.size(); ++i) {
    const tinygltf::Camera& src = ctx.model.cameras[i];
    const std::string where = ptr("/cameras", i);
    Camera c;
    c.name = src.name;
    if (src.type == "perspective") {
      c.type = CameraType::Perspective;
      c.yfov = finite(ctx, where + "/perspective/yfov", src.perspective.yfov);
      c.aspectRatio = finite(ctx, where + "/perspective/aspectRatio", src.perspective.aspectRatio);
      c.znear = finite(ctx, where + "/perspective/znear", src.perspective.znear);
      c.zfar = finite(ctx, where + "/perspective/zfar", src.perspective.zfar);
    } else if (src.type == "orthographic") {
      c.type = CameraType::Orthographic;
      c.xmag = finite(ctx, where + "/orthographic/xmag", src.orthographic.xmag);
      c.ymag = finite(ctx, where + "/orthographic/ymag", src.orthographic.ymag);
      c.znear = finite(ctx, where + "/orthographic/znear", src.orthographic.znear);
      c.zfar = finite(ctx, where + "/orthographic/zfar", src.orthographic.zfar);
    } else {
      ctx.fail(where + "/type", "unknown camera type \"" + src.type + "\"", "perspective or orthographic");
    }
    out.cameras.push_back(c);
  }
}

void importLights(const ImportContext& ctx, CookedAsset& out) {
  for (std::size_t i = 0; i < ctx.model.lights.size(); ++i) {
    const tinygltf::Light& src = ctx.model.lights[i];
    const std::string where = ptr("/extensions/KHR_lights_punctual/lights", i);
    Light l;
    l.name = src.name;
    if (src.type == "directional") l.type = LightType::Directional;
    else if (src.type == "point") l.type = LightType::Point;
    else if (src.type == "spot") l.type = LightType::Spot;
    else ctx.fail(where + "/type", "unknown light type \"" + src.type + "\"", "directional, point or spot");
    if (!src.color.empty()) {
      if (src.color.size() != 3) ctx.fail(where + "/color", "has " + std::to_string(src.color.size()) + " values", "3");
      for (int k = 0; k < 3; ++k) l.color[k] = finite(ctx, where + "/color", src.color[std::size_t(k)]);
    }
    l.intensity = finite(ctx, where + "/intensity", src.intensity);
    l.range = finite(ctx, where + "/range", src.range);
    l.innerConeAngle = finite(ctx, where + "/spot/innerConeAngle", src.spot.innerConeAngle);
    l.outerConeAngle = finite(ctx, where + "/spot/outerConeAngle", src.spot.outerConeAngle);
    if (l.intensity < 0.0f || l.range < 0.0f) ctx.fail(where, "negative intensity or range", "values ≥ 0");
    if (l.type == LightType::Spot && !(0.0f <= l.innerConeAngle && l.innerConeAngle < l.outerConeAngle &&
                                       l.outerConeAngle <= 1.5707964f))
      ctx.fail(where + "/spot", "cone angles inner " + std::to_string(l.innerConeAngle) + ", outer " +
                                    std::to_string(l.outerConeAngle),
               "0 ≤ innerConeAngle < outerConeAngle ≤ π/2");
    out.lights.push_back(l);
  }
}

void importSkins(const ImportContext& ctx, CookedAsset& out) {
  for (std::size_t i = 0; i < ctx.model.skins.size(); ++i) {
    const tinygltf::Skin& src = ctx.model.skins[i];
    const std::string where = ptr("/skins", i);
    Skin s;
    s.name = src.name;
    for (std::size_t j = 0; j < src.joints.size(); ++j) {
      checkIndex(ctx, ptr(where + "/joints", j), src.joints[j], ctx.model.nodes.size(), "node");
      s.joints.push_back(src.joints[j]);
    }
    if (src.skeleton != -1) checkIndex(ctx, where + "/skeleton", src.skeleton, ctx.model.nodes.size(), "node");
    s.skeleton = src.skeleton;
    s.inverseBindMatrices.assign(s.joints.size(), glm::mat4(1.0f));
    if (src.inverseBindMatrices != -1) {
      AccessorInfo info;
      const auto f = readFloats(ctx, src.inverseBindMatrices, where + "/inverseBindMatrices", {TINYGLTF_TYPE_MAT4}, &info);
      if (info.count < s.joints.size())
        ctx.fail(where + "/inverseBindMatrices", std::to_string(info.count) + " matrices for " +
                                                     std::to_string(s.joints.size()) + " joints",
                 "one matrix per joint");
      for (std::size_t j = 0; j < s.joints.size(); ++j)
        for (int k = 0; k < 16; ++k) glm::value_ptr(s.inverseBindMatrices[j])[k] = f[j * 16 + std::size_t(k)];
    }
    out.skins.push_back(std::move(s));
  }
}

void importAnimations(const ImportContext& ctx, CookedAsset& out) {
  std::size_t skippedChannels = 0;
  for (std::size_t a = 0; a < ctx.model.animations.size(); ++a) {
    const tinygltf::Animation& src = ctx.model.animations[a];
    const std::string where = ptr("/animations", a);
    Animation anim;
    anim.name = src.name;
    for (std::size_t s = 0; s < src.samplers.size(); ++s) {
      const auto& ss = src.samplers[s];
      const std::string sw = ptr(where + "/samplers", s);
      AnimationSampler smp;
      if (ss.interpolation == "LINEAR" || ss.interpolation.empty()) smp.interpolation = Interpolation::Linear;
      else if (ss.interpolation == "STEP") smp.interpolation = Interpolation::Step;
      else if (ss.interpolation == "CUBICSPLINE") smp.interpolation = Interpolation::CubicSpline;
      else ctx.fail(sw + "/interpolation", "unknown interpolation \"" + ss.interpolation + "\"", "LINEAR, STEP or CUBICSPLINE");
      AccessorInfo in, outInfo;
      smp.input = readFloats(ctx, ss.input, sw + "/input", {TINYGLTF_TYPE_SCALAR}, &in);
      smp.output = readFloats(ctx, ss.output, sw + "/output", {}, &outInfo);
      const std::size_t keys = in.count * (smp.interpolation == Interpolation::CubicSpline ? 3 : 1);
      if (smp.output.size() % keys != 0)
        ctx.fail(sw + "/output", std::to_string(smp.output.size()) + " values do not divide into " + std::to_string(keys) + " keys",
                 "a whole number of values per key");
      smp.components = std::uint32_t(smp.output.size() / keys);
      for (std::size_t k = 1; k < smp.input.size(); ++k)
        if (!(smp.input[k] > smp.input[k - 1]))
          ctx.fail(sw + "/input", "key times not strictly increasing at key " + std::to_string(k), "increasing times");
      anim.samplers.push_back(std::move(smp));
    }
    for (std::size_t c = 0; c < src.channels.size(); ++c) {
      const auto& cs = src.channels[c];
      const std::string cw = ptr(where + "/channels", c);
      AnimationChannel ch;
      checkIndex(ctx, cw + "/sampler", cs.sampler, anim.samplers.size(), "sampler");
      ch.sampler = cs.sampler;
      if (cs.target_node == -1) {
        ++skippedChannels;  // targets given by an extension only
        continue;
      }
      checkIndex(ctx, cw + "/target/node", cs.target_node, ctx.model.nodes.size(), "node");
      ch.node = cs.target_node;
      if (cs.target_path == "translation") ch.path = AnimationPath::Translation;
      else if (cs.target_path == "rotation") ch.path = AnimationPath::Rotation;
      else if (cs.target_path == "scale") ch.path = AnimationPath::Scale;
      else if (cs.target_path == "weights") ch.path = AnimationPath::Weights;
      else ctx.fail(cw + "/target/path", "unknown path \"" + cs.target_path + "\"", "translation, rotation, scale or weights");
      const std::uint32_t want = ch.path == AnimationPath::Rotation ? 4 : ch.path == AnimationPath::Weights ? 0 : 3;
      if (want != 0 && anim.samplers[std::size_t(ch.sampler)].components != want)
        ctx.fail(cw, "sampler has " + std::to_string(anim.samplers[std::size_t(ch.sampler)].components) +
                         " values per key for path " + cs.target_path,
                 std::to_string(want));
      anim.channels.push_back(ch);
    }
    out.animations.push_back(std::move(anim));
  }
  if (skippedChannels) log::warn(ctx.file + ": skipped " + std::to_string(skippedChannels) + " animation channels without a target node");
}

}  // namespace

void importScene(const ImportContext& ctx, CookedAsset& out) {
  importNodes(ctx, out);
  importCameras(ctx, out);
  importLights(ctx, out);
  importSkins(ctx, out);
  importAnimations(ctx, out);
}

}  // namespace bounce::asset::detail
