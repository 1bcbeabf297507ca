// Level loading: a valid level's exact contents, and one test per class of bad input, each
// asserting the exact one-line error and that the registry stays empty.
#include <gtest/gtest.h>

#include <numbers>

#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"
#include "engine/scene/transform_math.hpp"
#include "test_util.hpp"

using namespace bounce;
using namespace bounce::scene;
using namespace bounce::scene::test;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::string boxAsset() { return (dataDir() / "assets/box.gltf").string(); }

// A level around `entities` (a JSON array body) with the given effects.
std::string levelJson(const std::string& entities, const std::string& effects = R"(["direct"])") {
  return R"({"bounce_level": 1, "effects": )" + effects + R"(, "entities": [)" + entities + "]}";
}

// Loads `text` (written to <name>.json) into a fresh registry; returns the error line with the
// file name replaced by "FILE", and checks the registry stayed empty.
std::string loadError(const std::string& name, const std::string& text) {
  const auto path = writeTemp(name + ".json", text);
  ecs::Registry registry;
  std::string msg = inputErrorOf([&] { instantiate(loadLevel(path), registry); });
  EXPECT_EQ(registry.alive(), 0u) << name;
  const std::string prefix = path.string() + ": ";
  if (msg.rfind(prefix, 0) == 0) msg = "FILE: " + msg.substr(prefix.size());
  return msg;
}

}  // namespace

TEST(Level, ValidLevelParsesToExactData) {
  const Level level = loadLevel(dataDir() / "valid.json");
  EXPECT_EQ(level.name, "Test level");
  EXPECT_EQ(level.effects.names(), (std::vector<std::string>{"direct", "shadows"}));
  EXPECT_EQ(level.background, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(level.source, (dataDir() / "valid.json").lexically_normal());
  ASSERT_EQ(level.entities.size(), 6u);
  const auto box = (dataDir() / "assets/box.gltf").lexically_normal();

  const EntityDesc& room = level.entities[0];
  EXPECT_EQ(room.id, "room");
  EXPECT_EQ(room.pointer, "/entities/0");
  EXPECT_FALSE(room.parent);
  EXPECT_FALSE(room.dynamic);
  EXPECT_EQ(room.transform, Transform{});
  ASSERT_TRUE(room.mesh);
  EXPECT_EQ(*room.mesh, (MeshRef{box, std::string("Room"), Subdivision{SubdivisionScheme::Loop, 2}}));
  EXPECT_EQ(*room.material, (MaterialOverride{glm::vec3(0.5f, 0.25f, 1.0f), glm::vec3(2.0f, 0.0f, 0.0f)}));

  const EntityDesc& camera = level.entities[1];
  EXPECT_EQ(camera.transform.translation, glm::vec3(0, 1, 5));
  EXPECT_EQ(*camera.camera, (Camera{float(90 * kDeg), 0.5f, 50.0f}));

  const EntityDesc& spot = level.entities[2];
  EXPECT_EQ(spot.transform.rotation, quatFromEulerDeg({-90, 0, 0}));
  EXPECT_EQ(*spot.light, (Light{LightType::Spot, glm::vec3(1, 0.5f, 0.25f), 4.0f, std::optional<float>(10.0f),
                                float(30 * kDeg), float(60 * kDeg), false}));

  const EntityDesc& prop = level.entities[3];
  EXPECT_EQ(prop.parent, "room");
  EXPECT_TRUE(prop.dynamic);  // implied by motion
  // [0, 0, 0, 2] is normalised to the identity.
  EXPECT_EQ(prop.transform, (Transform{glm::vec3(1, 2, 3), glm::quat(1, 0, 0, 0), glm::vec3(2)}));
  EXPECT_EQ(*prop.mesh, (MeshRef{box, std::uint32_t(3), std::nullopt}));
  ASSERT_TRUE(prop.motion);
  EXPECT_FALSE(prop.motion->keyframes);
  EXPECT_FALSE(prop.motion->bob);
  EXPECT_EQ(*prop.motion->orbit, (Orbit{std::nullopt, glm::vec3(0, 1, 0), 0.5f, 4.0f, 0.0f}));
  EXPECT_EQ(*prop.motion->spin, (Spin{glm::vec3(0, 1, 0), 2.0f, 0.25f}));  // axis normalised
  EXPECT_EQ(prop.motion->base, prop.transform);

  EXPECT_EQ(level.entities[4].parent, "prop");
  EXPECT_TRUE(level.entities[4].dynamic);
  Light sun;
  sun.type = LightType::Directional;
  EXPECT_EQ(*level.entities[5].light, sun);  // every other field at its default
}

TEST(Level, InstantiateCreatesExactComponents) {
  const Level level = loadLevel(dataDir() / "valid.json");
  ecs::Registry r;
  const auto es = instantiate(level, r);
  ASSERT_EQ(es.size(), 6u);
  EXPECT_EQ(r.alive(), 6u);
  for (std::size_t i = 0; i < es.size(); ++i) {
    EXPECT_EQ(r.get<Name>(es[i]).id, level.entities[i].id);
    EXPECT_EQ(r.get<Transform>(es[i]), level.entities[i].transform);
  }
  EXPECT_EQ(r.get<Parent>(es[3]).entity, es[0]);
  EXPECT_EQ(r.get<Parent>(es[4]).entity, es[3]);
  EXPECT_FALSE(r.has<Parent>(es[0]));
  EXPECT_EQ(r.view<Dynamic>().entities(), (std::vector<ecs::Entity>{es[3], es[4]}));
  EXPECT_EQ(r.view<MeshRef>().entities(), (std::vector<ecs::Entity>{es[0], es[3]}));
  EXPECT_EQ(r.get<MaterialOverride>(es[0]), *level.entities[0].material);
  EXPECT_EQ(r.get<Camera>(es[1]), *level.entities[1].camera);
  EXPECT_EQ(r.get<Light>(es[2]), *level.entities[2].light);
  EXPECT_EQ(r.get<Motion>(es[3]), *level.entities[3].motion);
  EXPECT_EQ(activeCamera(r), es[1]);
  EXPECT_TRUE(r.has<ActiveCamera>(es[1]));
  // child world = room (identity) · prop (T(1,2,3) S2) · child (T(1,0,0)): translation (3, 2, 3).
  EXPECT_EQ(r.get<WorldTransform>(es[4]).matrix[3], glm::vec4(3, 2, 3, 1));
  EXPECT_EQ(r.get<WorldTransform>(es[4]).matrix[0], glm::vec4(2, 0, 0, 0));
}

TEST(Level, EffectsOverrideReplacesAndValidates) {
  Level level = loadLevel(dataDir() / "valid.json");
  overrideEffects(level, "ssao, direct,dnrt");
  EXPECT_EQ(level.effects.names(), (std::vector<std::string>{"direct", "dnrt", "ssao"}));
  overrideEffects(level, "");
  EXPECT_TRUE(level.effects.empty());
  const std::string file = level.source.string();
  EXPECT_EQ(inputErrorOf([&] { overrideEffects(level, "direct,bloom"); }),
            file + ": --effects: unknown effect \"bloom\" (expected one of: direct, shadows, probes, dnrt, vlm, sl, rtf, "
                   "ssao, hbao)");
  EXPECT_EQ(inputErrorOf([&] { overrideEffects(level, "vlm,vlm"); }),
            file + ": --effects: duplicate effect \"vlm\" (expected each effect at most once)");
  EXPECT_TRUE(level.effects.empty());  // a failed override changes nothing
}

TEST(LevelErrors, UnknownKey) {
  EXPECT_EQ(loadError("unknown-key", levelJson(R"({"id": "a", "colour": [1, 1, 1]})")),
            "FILE: /entities/0/colour: unknown key \"colour\" (expected one of: id, parent, dynamic, transform, mesh, "
            "material, camera, light, motion, animation, dnrt, sl, rtf, vlm, vlm_tag)");
  EXPECT_EQ(loadError("unknown-key-nested", levelJson(R"({"id": "a", "light": {"type": "point", "power": 1}})")),
            "FILE: /entities/0/light/power: unknown key \"power\" (expected one of: type, color, intensity, range, "
            "inner_cone_deg, outer_cone_deg, shadows, radius)");
}

TEST(LevelErrors, WrongType) {
  EXPECT_EQ(loadError("wrong-type", levelJson(R"({"id": "a", "light": {"type": "point", "intensity": "bright"}})")),
            "FILE: /entities/0/light/intensity: wrong type: string (expected a number >= 0)");
  EXPECT_EQ(loadError("wrong-type-root", "[1, 2]"), "FILE: wrong type: array (expected an object)");
  EXPECT_EQ(loadError("wrong-type-bool", levelJson(R"({"id": "a", "dynamic": 1})")),
            "FILE: /entities/0/dynamic: wrong type: integer (expected true or false)");
}

TEST(LevelErrors, MissingRequiredKey) {
  EXPECT_EQ(loadError("missing-id", levelJson(R"({"transform": {}})")),
            "FILE: /entities/0: missing required key \"id\" (expected a unique string id)");
  EXPECT_EQ(loadError("missing-entities", R"({"bounce_level": 1, "effects": []})"),
            "FILE: missing required key \"entities\" (expected an array of entities)");
  EXPECT_EQ(loadError("missing-light-type", levelJson(R"({"id": "a", "light": {}})")),
            "FILE: /entities/0/light: missing required key \"type\" (expected one of: point, spot, directional)");
}

TEST(LevelErrors, NonFiniteNumber) {
  // JSON has no NaN/Inf literals; an overflowing literal is the way to write one.
  EXPECT_EQ(loadError("inf", levelJson(R"({"id": "a", "transform": {"translation": [0, 1e999, 0]}})")),
            "FILE: /entities/0/transform/translation/1: number overflow parsing '1e999' (expected a finite number)");
  EXPECT_EQ(loadError("neg-inf", levelJson(R"({"id": "a", "light": {"type": "point", "intensity": -1e999}})")),
            "FILE: /entities/0/light/intensity: number overflow parsing '-1e999' (expected a finite number)");
  // Finite as a double but not as a float.
  EXPECT_EQ(loadError("float-overflow", levelJson(R"({"id": "a", "transform": {"scale": [1e39, 1, 1]}})")),
            "FILE: /entities/0/transform/scale/0: 1e+39 does not fit a 32-bit float (expected a number of magnitude "
            "<= 3.4e38)");
}

TEST(LevelErrors, OutOfRange) {
  EXPECT_EQ(loadError("fov", levelJson(R"({"id": "a", "camera": {"yfov_deg": 180}})")),
            "FILE: /entities/0/camera/yfov_deg: 180 is out of range (expected a number in (0, 180))");
  EXPECT_EQ(loadError("far", levelJson(R"({"id": "a", "camera": {"near": 2, "far": 1.5}})")),
            "FILE: /entities/0/camera/far: 1.5 is out of range (expected a number > 2)");
  EXPECT_EQ(loadError("albedo", levelJson(R"({"id": "a", "material": {"albedo": [0.5, 1.25, 0]}})")),
            "FILE: /entities/0/material/albedo/1: 1.25 is out of range (expected a number in [0, 1])");
  EXPECT_EQ(loadError("cone", levelJson(R"({"id": "a", "light": {"type": "spot", "inner_cone_deg": 40, "outer_cone_deg": 30}})")),
            "FILE: /entities/0/light/outer_cone_deg: 30 is out of range (expected a number in (40, 90])");
  EXPECT_EQ(loadError("levels", levelJson(R"({"id": "a", "mesh": {"asset": ")" + boxAsset() +
                                          R"(", "subdivision": {"scheme": "loop", "levels": 5}}})")),
            "FILE: /entities/0/mesh/subdivision/levels: 5 is out of range (expected an integer in [1, 4])");
  EXPECT_EQ(loadError("scale0", levelJson(R"({"id": "a", "transform": {"scale": [1, 0, 1]}})")),
            "FILE: /entities/0/transform/scale/1: scale 0 (expected a non-zero scale)");
  EXPECT_EQ(loadError("quat0", levelJson(R"({"id": "a", "transform": {"rotation": [0, 0, 0, 0]}})")),
            "FILE: /entities/0/transform/rotation: zero-length quaternion (expected a non-zero quaternion [x, y, z, w])");
  EXPECT_EQ(loadError("version", R"({"bounce_level": 2, "effects": [], "entities": []})"),
            "FILE: /bounce_level: unsupported version 2 (expected 1)");
}

TEST(LevelErrors, DuplicateId) {
  EXPECT_EQ(loadError("dup-id", levelJson(R"({"id": "a"}, {"id": "b"}, {"id": "a"})")),
            "FILE: /entities/2/id: duplicate id \"a\" (expected a unique id; first used at /entities/0/id)");
}

TEST(LevelErrors, UnknownParent) {
  EXPECT_EQ(loadError("ghost-parent", levelJson(R"({"id": "a", "parent": "ghost"})")),
            "FILE: /entities/0/parent: unknown id \"ghost\" (expected the id of another entity in this level)");
}

TEST(LevelErrors, ParentCycle) {
  const auto path = dataDir() / "cycle.json";
  ecs::Registry r;
  EXPECT_EQ(inputErrorOf([&] { instantiate(loadLevel(path), r); }),
            path.string() + ": /entities/1/parent: parent cycle \"c\" -> \"a\" -> \"b\" -> \"c\" (expected a hierarchy "
                            "without cycles)");
  EXPECT_EQ(r.alive(), 0u);
  EXPECT_EQ(loadError("self-parent", levelJson(R"({"id": "x"}, {"id": "a", "parent": "a"})")),
            "FILE: /entities/1/parent: parent cycle \"a\" -> \"a\" (expected a hierarchy without cycles)");
}

TEST(LevelErrors, UnknownEffect) {
  EXPECT_EQ(loadError("bad-effect", levelJson("", R"(["direct", "bloom"])")),
            "FILE: /effects/1: unknown effect \"bloom\" (expected one of: direct, shadows, probes, dnrt, vlm, sl, rtf, "
            "ssao, hbao)");
  EXPECT_EQ(loadError("dup-effect", levelJson("", R"(["sl", "sl"])")),
            "FILE: /effects/1: duplicate effect \"sl\" (expected each effect at most once)");
}

TEST(LevelErrors, MissingAssetFile) {
  const auto missing = (outDir() / "meshes/missing.glb").lexically_normal();
  EXPECT_EQ(loadError("missing-asset", levelJson(R"({"id": "a", "mesh": {"asset": "meshes/missing.glb"}})")),
            "FILE: /entities/0/mesh/asset: file not found: " + missing.string() +
                " (expected an existing file, relative to the level file)");
  EXPECT_EQ(loadError("bad-asset-type", levelJson(R"({"id": "a", "mesh": {"asset": "x.obj"}})")),
            "FILE: /entities/0/mesh/asset: unsupported file type \".obj\" (expected a .gltf or .glb file)");
}

TEST(LevelErrors, MotionScripts) {
  EXPECT_EQ(loadError("times", levelJson(R"({"id": "a", "motion": {"keyframes": {"times": [0, 1, 1], "scale": [[1,1,1],[2,2,2],[1,1,1]]}}})")),
            "FILE: /entities/0/motion/keyframes/times/2: time 1 is not after the previous 1 (expected strictly "
            "increasing times)");
  EXPECT_EQ(loadError("track", levelJson(R"({"id": "a", "motion": {"keyframes": {"times": [0, 1], "translation": [[0,0,0]]}}})")),
            "FILE: /entities/0/motion/keyframes/translation: 1 element (expected 2 values, one per time)");
  EXPECT_EQ(loadError("mode", levelJson(R"({"id": "a", "motion": {"keyframes": {"times": [0, 1], "scale": [[1,1,1],[2,2,2]], "mode": "bounce"}}})")),
            "FILE: /entities/0/motion/keyframes/mode: unknown mode \"bounce\" (expected one of: loop, ping-pong, once)");
  EXPECT_EQ(loadError("period", levelJson(R"({"id": "a", "motion": {"spin": {"axis": [0, 1, 0], "period_s": 0}}})")),
            "FILE: /entities/0/motion/spin/period_s: 0 is out of range (expected a number > 0)");
  EXPECT_EQ(loadError("axis", levelJson(R"({"id": "a", "motion": {"bob": {"axis": [0, 0, 0], "amplitude": 1, "period_s": 1}}})")),
            "FILE: /entities/0/motion/bob/axis: zero-length direction (expected a non-zero [x, y, z])");
  EXPECT_EQ(loadError("static-motion", levelJson(R"({"id": "a", "dynamic": false, "motion": {}})")),
            "FILE: /entities/0/dynamic: false, but the entity has a motion (expected true, or no \"dynamic\" key)");
}

TEST(LevelErrors, MalformedJsonGivesBytePosition) {
  EXPECT_EQ(loadError("syntax", "{\"bounce_level\": 1,,}"),
            "FILE: byte 20 (line 1, column 20): malformed JSON: syntax error while parsing object key - unexpected ','; "
            "expected string literal (expected valid JSON)");
  EXPECT_EQ(loadError("dup-key", levelJson(R"({"id": "a", "id": "b"})")),
            "FILE: /entities/0/id: duplicate key \"id\" (expected each key at most once per object)");
  EXPECT_EQ(loadError("empty", ""),
            "FILE: byte 1 (line 1, column 1): malformed JSON: syntax error while parsing value - unexpected end of "
            "input; expected '[', '{', or a literal (expected valid JSON)");
}

TEST(LevelErrors, TruncatedFile) {
  // The file is 114 bytes; the parser reports the 1-based position of the end of input.
  const auto path = dataDir() / "truncated.json";
  ecs::Registry r;
  EXPECT_EQ(inputErrorOf([&] { instantiate(loadLevel(path), r); }),
            path.string() + ": byte 115 (line 5, column 51): malformed JSON: syntax error while parsing array - "
                            "unexpected end of input; expected ']' (expected valid JSON)");
  EXPECT_EQ(r.alive(), 0u);
}

TEST(LevelErrors, HostileInput) {
  // 100k nested arrays: rejected at the 65th level, not by a stack overflow.
  std::string pointer;
  for (int i = 0; i < 64; ++i) pointer += "/0";
  EXPECT_EQ(loadError("deep", std::string(100000, '[')),
            "FILE: " + pointer + ": JSON nested deeper than 64 levels (expected at most 64)");
  // A 10 MB string.
  const std::string big(10u << 20, 'x');
  EXPECT_EQ(loadError("big-string", R"({"bounce_level": 1, "name": ")" + big + R"(", "effects": [], "entities": []})"),
            "FILE: /name: string of 10485760 bytes is too long (expected at most 4096 bytes)");
  // A 10 MB key: the message quotes only its start.
  EXPECT_EQ(loadError("big-key", R"({"bounce_level": 1, ")" + big + R"(": 1, "effects": [], "entities": []})"),
            "FILE: /" + std::string(64, 'x') + "...: unknown key \"" + std::string(64, 'x') +
                "...\" (expected one of: bounce_level, name, effects, background, probes, dnrt, rtf, vlm, entities)");
  // Integers beyond 64 bits become doubles: not an integer.
  EXPECT_EQ(loadError("huge-int", R"({"bounce_level": 123456789012345678901234567890, "effects": [], "entities": []})"),
            "FILE: /bounce_level: wrong type: number (expected an integer in [0, 1073741824])");
  EXPECT_EQ(loadError("huge-uint", R"({"bounce_level": 18446744073709551615, "effects": [], "entities": []})"),
            "FILE: /bounce_level: 18446744073709551615 is out of range (expected an integer in [0, 1073741824])");
  // Control characters in a key (JSON escapes) are shown as '?' in the pointer as in the quote, so
  // the message stays one line (fuzz_level found the pointer echoing them).
  EXPECT_EQ(loadError("control-key", R"({"bounce_level": 1, "a\nb\u007f": 1, "effects": [], "entities": []})"),
            "FILE: /a?b?: unknown key \"a?b?\" (expected one of: bounce_level, name, effects, background, probes, dnrt, rtf, vlm, "
            "entities)");
  // Invalid UTF-8 is reported without echoing the bytes.
  EXPECT_EQ(loadError("utf8", "{\"name\": \"\xff\"}"),
            "FILE: byte 11 (line 1, column 11): malformed JSON: syntax error while parsing value - invalid string: "
            "ill-formed UTF-8 byte (expected valid JSON)");
}

TEST(LevelErrors, InstantiateRejectsBrokenHandBuiltLevel) {
  Level level;
  level.entities.resize(2);
  level.entities[0].id = "a";
  level.entities[1].id = "b";
  level.entities[1].parent = "nobody";
  ecs::Registry r;
  EXPECT_THROW(instantiate(level, r), InternalError);
  EXPECT_EQ(r.alive(), 0u);
}

// The level's "probes" object: defaults when absent, exact values when given, and one-line errors
// at the offending key (the baker's own checks are in tests/unit/probes).
TEST(Level, ProbesSettingsParseWithDefaults) {
  const auto plain = writeTemp("probes-default.json", levelJson(""));
  const Level a = loadLevel(plain);
  EXPECT_FLOAT_EQ(a.probes.spacing, 0.1f);
  EXPECT_EQ(a.probes.order, 3);
  EXPECT_EQ(a.probes.rays, 256u);
  const auto set = writeTemp("probes-set.json", R"({"bounce_level": 1, "effects": ["probes"],
      "probes": {"spacing": 0.25, "order": 2, "rays": 576}, "entities": []})");
  const Level b = loadLevel(set);
  EXPECT_FLOAT_EQ(b.probes.spacing, 0.25f);
  EXPECT_EQ(b.probes.order, 2);
  EXPECT_EQ(b.probes.rays, 576u);
  EXPECT_FALSE(b.probes.relight);  // off unless asked
  const auto relit = writeTemp("probes-relight.json", R"({"bounce_level": 1, "effects": ["probes"],
      "probes": {"relight": true}, "entities": []})");
  EXPECT_TRUE(loadLevel(relit).probes.relight);
  EXPECT_FALSE(loadLevel(relit).probes.slBounce);  // off unless asked
  const auto slBounce = writeTemp("probes-sl-bounce.json", R"({"bounce_level": 1, "effects": ["probes"],
      "probes": {"relight": true, "sl_bounce": true}, "entities": []})");
  EXPECT_TRUE(loadLevel(slBounce).probes.slBounce);
}

TEST(LevelErrors, ProbesSettings) {
  auto with = [](const std::string& probes) {
    return R"({"bounce_level": 1, "effects": ["probes"], "probes": )" + probes + R"(, "entities": []})";
  };
  EXPECT_EQ(loadError("probes-order", with(R"({"order": 4})")), "FILE: /probes/order: SH order 4 (expected 2 or 3)");
  EXPECT_EQ(loadError("probes-rays", with(R"({"rays": 100})")),
            "FILE: /probes/rays: 100 rays (expected a square whose root is a multiple of 8 (64, 256, 576, 1024, ...))");
  EXPECT_EQ(loadError("probes-spacing", with(R"({"spacing": 0})")),
            "FILE: /probes/spacing: 0 is out of range (expected a number in [0.001, 1000])");
  EXPECT_EQ(loadError("probes-key", with(R"({"spacng": 0.2})")),
            "FILE: /probes/spacng: unknown key \"spacng\", did you mean \"spacing\"? (expected one of: spacing, order, rays, relight, sl_bounce)");
  EXPECT_EQ(loadError("probes-relight", with(R"({"relight": 1})")), "FILE: /probes/relight: wrong type: integer (expected true or false)");
  EXPECT_EQ(loadError("probes-sl-bounce", with(R"({"sl_bounce": true})")),
            "FILE: /probes/sl_bounce: sl_bounce without relight (expected \"relight\": true with it)");
}

// The "vlm" component (virtual lights, engine/gi/vlm) and "vlm_tag" (real geometry's id, thesis
// §3.4): exact data, the entity's mesh moves into the Vlm component (a VLM is never drawn), and
// one-line errors.
TEST(Level, VlmComponentsParseAndInstantiate) {
  const auto path = writeTemp("vlm.json", levelJson(R"({"id": "wall", "mesh": {"asset": ")" + boxAsset() +
                                                    R"("}, "vlm_tag": 3},
      {"id": "light", "mesh": {"asset": ")" + boxAsset() + R"("}, "material": {"albedo": [0.5, 0.1, 0.1]},
       "vlm": {"tag": 3, "color": [1, 0.5, 0.25], "intensity": 2}})",
                                                    R"(["direct", "vlm"])"));
  const Level level = loadLevel(path);
  ASSERT_EQ(level.entities.size(), 2u);
  EXPECT_EQ(level.entities[0].vlmTag, VlmTag{3});
  ASSERT_TRUE(level.entities[1].vlm);
  const Vlm& v = *level.entities[1].vlm;
  EXPECT_EQ(v.tag, 3);
  EXPECT_EQ(v.color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(v.intensity.value(), 2.0f);
  EXPECT_FALSE(v.reflectance);
  EXPECT_EQ(v.albedoOverride, glm::vec3(0.5f, 0.1f, 0.1f));
  EXPECT_EQ(v.mesh, *level.entities[1].mesh);
  ecs::Registry r;
  const auto es = instantiate(level, r);
  EXPECT_TRUE(r.has<MeshRef>(es[0]));
  EXPECT_EQ(r.get<VlmTag>(es[0]).tag, 3);
  EXPECT_FALSE(r.has<MeshRef>(es[1]));  // virtual geometry is not drawn
  EXPECT_EQ(r.get<Vlm>(es[1]), v);
  EXPECT_EQ(level.vlm.grid, 16);
  EXPECT_EQ(level.vlm.k, 32);
  EXPECT_FLOAT_EQ(level.vlm.range, 2.5f);
}

TEST(LevelErrors, VlmComponents) {
  const std::string mesh = R"("mesh": {"asset": ")" + boxAsset() + R"("})";
  EXPECT_EQ(loadError("vlm-no-mesh", levelJson(R"({"id": "a", "vlm": {"tag": 1}})")),
            "FILE: /entities/0/vlm: a VLM on an entity without a mesh (expected a \"mesh\" key)");
  EXPECT_EQ(loadError("vlm-no-tag", levelJson(R"({"id": "a", )" + mesh + R"(, "vlm": {}})")),
            "FILE: /entities/0/vlm: missing required key \"tag\" (expected an integer id >= 1)");
  EXPECT_EQ(loadError("vlm-tag-zero", levelJson(R"({"id": "a", )" + mesh + R"(, "vlm_tag": 0})")),
            "FILE: /entities/0/vlm_tag: 0 is out of range (expected an integer in [1, 16777216])");
  EXPECT_EQ(loadError("vlm-both", levelJson(R"({"id": "a", )" + mesh + R"(, "vlm": {"tag": 1}, "vlm_tag": 1})")),
            "FILE: /entities/0/vlm_tag: a vlm_tag on a VLM entity (the tag is in \"vlm\") (expected no \"vlm_tag\" key)");
  EXPECT_EQ(loadError("vlm-key", levelJson(R"({"id": "a", )" + mesh + R"(, "vlm": {"tag": 1, "colour": [1, 1, 1]}})")),
            "FILE: /entities/0/vlm/colour: unknown key \"colour\", did you mean \"color\"? (expected one of: tag, color, intensity, reflectance)");
  EXPECT_EQ(loadError("vlm-settings", R"({"bounce_level": 1, "effects": ["vlm"], "vlm": {"range": 0.5}, "entities": []})"),
            "FILE: /vlm/range: 0.5 is out of range (expected a number in [1, 100])");
}

// vlm.conservative_threshold (engine/gi/vlm/grid.hpp conservative overflow mode): off by default,
// a positive number when given.
TEST(Level, VlmConservativeThreshold) {
  const auto on = writeTemp("vlm-conservative.json",
                            R"({"bounce_level": 1, "effects": ["vlm"], "vlm": {"conservative_threshold": 0.25}, "entities": []})");
  EXPECT_FLOAT_EQ(loadLevel(on).vlm.conservativeThreshold, 0.25f);
  const auto off = writeTemp("vlm-default.json", R"({"bounce_level": 1, "effects": ["vlm"], "entities": []})");
  EXPECT_EQ(loadLevel(off).vlm.conservativeThreshold, 0.0f);
  EXPECT_EQ(loadError("vlm-conservative-zero",
                      R"({"bounce_level": 1, "effects": ["vlm"], "vlm": {"conservative_threshold": 0}, "entities": []})"),
            "FILE: /vlm/conservative_threshold: 0 is out of range (expected a number > 0)");
  EXPECT_EQ(loadError("vlm-conservative-type",
                      R"({"bounce_level": 1, "effects": ["vlm"], "vlm": {"conservative_threshold": "high"}, "entities": []})"),
            "FILE: /vlm/conservative_threshold: wrong type: string (expected a number > 0)");
}
