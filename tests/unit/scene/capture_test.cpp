// Capture scripts: exact contents and validation.
#include <gtest/gtest.h>

#include "engine/scene/capture.hpp"
#include "test_util.hpp"

using namespace bounce;
using namespace bounce::scene;
using namespace bounce::scene::test;

namespace {
std::string scriptError(const std::string& name, const std::string& body) {
  // Scripts written to the test-out folder point at the data level by absolute path.
  const std::string level = (dataDir() / "valid.json").string();
  const auto path = writeTemp(name + ".json", R"({"bounce_capture": 1, "level": ")" + level + "\", " + body + "}");
  std::string msg = inputErrorOf([&] { loadCaptureScript(path); });
  const std::string prefix = path.string() + ": ";
  return msg.rfind(prefix, 0) == 0 ? "FILE: " + msg.substr(prefix.size()) : msg;
}
const std::string kRest = R"("resolution": [64, 64], "dt": 0.5, "frames": 4)";
}  // namespace

TEST(Capture, ValidScriptLoads) {
  const CaptureScript s = loadCaptureScript(dataDir() / "capture.json");
  EXPECT_EQ(s.level, (dataDir() / "valid.json").lexically_normal());
  EXPECT_EQ(s.resolution, glm::uvec2(320, 240));
  EXPECT_EQ(s.dt, 0.25);
  EXPECT_EQ(s.frames, 8u);
  EXPECT_EQ(s.capture, (std::vector<std::uint32_t>{0, 3, 7}));
  ASSERT_TRUE(s.camera && s.camera->keyframes);
  EXPECT_EQ(s.camera->keyframes->times, (std::vector<float>{0, 1}));
  EXPECT_EQ(s.camera->keyframes->translation, (std::vector<glm::vec3>{{0, 1, 5}, {1, 1, 5}}));
  EXPECT_EQ(s.camera->keyframes->mode, PlayMode::Once);
  ASSERT_TRUE(s.effects);
  EXPECT_EQ(s.effects->names(), (std::vector<std::string>{"direct"}));
}

TEST(Capture, CaptureIndexMustBeBelowFrames) {
  EXPECT_EQ(scriptError("cap-index", kRest + R"(, "capture": [0, 4])"),
            "FILE: /capture/1: 4 is out of range (expected an integer in [0, 3])");
  EXPECT_EQ(scriptError("cap-order", kRest + R"(, "capture": [2, 1])"),
            "FILE: /capture/1: frame 1 is not after the previous 2 (expected strictly increasing frame indices)");
}

TEST(Capture, ResolutionWithinLimits) {
  EXPECT_EQ(scriptError("res0", R"("resolution": [0, 64], "dt": 0.5, "frames": 4, "capture": [])"),
            "FILE: /resolution/0: 0 is out of range (expected an integer in [1, 16384])");
  EXPECT_EQ(scriptError("res-big", R"("resolution": [64, 16385], "dt": 0.5, "frames": 4, "capture": [])"),
            "FILE: /resolution/1: 16385 is out of range (expected an integer in [1, 16384])");
  EXPECT_EQ(scriptError("res-3", R"("resolution": [64, 64, 3], "dt": 0.5, "frames": 4, "capture": [])"),
            "FILE: /resolution: 3 elements (expected [width, height], each an integer in [1, 16384])");
}

TEST(Capture, OtherFieldsValidated) {
  EXPECT_EQ(scriptError("dt", R"("resolution": [8, 8], "dt": 0, "frames": 4, "capture": [])"),
            "FILE: /dt: 0 is out of range (expected a number in (0, 1])");
  EXPECT_EQ(scriptError("missing-frames", R"("resolution": [8, 8], "dt": 0.5, "capture": [])"),
            "FILE: missing required key \"frames\" (expected an integer >= 1)");
  EXPECT_EQ(scriptError("effects", kRest + R"(, "capture": [], "effects": ["rtf", "gi"])"),
            "FILE: /effects/1: unknown effect \"gi\" (expected one of: direct, shadows, probes, dnrt, vlm, sl, rtf, "
            "ssao, hbao)");
  EXPECT_EQ(scriptError("camera", kRest + R"(, "capture": [], "camera": {"spin": {"axis": [0, 1, 0]}})"),
            "FILE: /camera/spin: missing required key \"period_s\" (expected a number > 0)");
  const auto path = writeTemp("no-level.json", R"({"bounce_capture": 1, "level": "nowhere/level.json"})");
  EXPECT_EQ(inputErrorOf([&] { loadCaptureScript(path); }),
            path.string() + ": /level: file not found: " + (outDir() / "nowhere/level.json").lexically_normal().string() +
                " (expected an existing file, relative to the capture script)");
  // A path from the script is echoed with its control characters shown as '?': the message stays one
  // line (fuzz_level found a raw DEL echoed; parseCaptureScript is the fuzz target's entry point).
  const auto fake = outDir() / "fuzz.json";
  EXPECT_EQ(inputErrorOf([&] { parseCaptureScript(R"({"bounce_capture": 1, "level": "a\nb\u007f.json"})", fake); }),
            fake.string() + ": /level: file not found: " + (outDir() / "a?b?.json").string() +
                " (expected an existing file, relative to the capture script)");
}
