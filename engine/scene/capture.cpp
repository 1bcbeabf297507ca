#include "engine/scene/capture.hpp"

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/scene/json_reader.hpp"
#include "engine/scene/motion.hpp"

namespace bounce::scene {

namespace {

CaptureScript captureFromJson(const nlohmann::json& doc, const std::filesystem::path& path) {
  const std::string file = path.string();
  const json::Node root(doc, "", file);
  if (doc.is_object() && doc.contains("bounce_level") && !doc.contains("bounce_capture"))
    throwInputError(file, "/bounce_level", "this is a level, not a capture script",
                    "a capture script (\"bounce_capture\": 1) whose \"level\" names it; 'bounce play' and 'bounce profile' take a level");
  const auto o = root.object({"bounce_capture", "level", "resolution", "dt", "frames", "capture", "camera", "effects"});

  const auto version = o.required("bounce_capture", "the format version 1");
  if (const auto v = version.integer(0, 1 << 30); v != 1) version.fail("unsupported version " + std::to_string(v), "1");

  CaptureScript s;
  s.source = std::filesystem::absolute(path).lexically_normal();
  const auto level = o.required("level", "a level path relative to the capture script");
  s.level = (s.source.parent_path() / std::filesystem::path(level.string())).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(s.level, ec))
    level.fail("file not found: " + json::printable(s.level.string()), "an existing file, relative to the capture script");

  const std::string resExpected = "[width, height], each an integer in [1, " + std::to_string(kMaxResolution) + "]";
  const auto res = o.required("resolution", resExpected).array(2, 2, resExpected);
  s.resolution = {std::uint32_t(res[0].integer(1, kMaxResolution)), std::uint32_t(res[1].integer(1, kMaxResolution))};
  s.dt = o.required("dt", "a time step in (0, 1] s").real64(json::Range::openClosed(0, 1));
  s.frames = std::uint32_t(o.required("frames", "an integer >= 1").integer(1, kMaxFrames));

  const auto capture = o.required("capture", "an array of frame indices");
  for (const auto& c : capture.array(0, s.frames, "at most " + std::to_string(s.frames) + " frame indices (one per frame)")) {
    const auto f = std::uint32_t(c.integer(0, std::int64_t(s.frames) - 1));
    if (!s.capture.empty() && f <= s.capture.back())
      c.fail("frame " + std::to_string(f) + " is not after the previous " + std::to_string(s.capture.back()),
             "strictly increasing frame indices");
    s.capture.push_back(f);
  }
  if (auto cam = o.optional("camera")) s.camera = parseMotion(*cam);
  if (auto eff = o.optional("effects")) s.effects = parseEffects(*eff);
  return s;
}

}  // namespace

CaptureScript loadCaptureScript(const std::filesystem::path& path) { return captureFromJson(json::parseFile(path), path); }

CaptureScript parseCaptureScript(std::string_view text, const std::filesystem::path& path) {
  return captureFromJson(json::parse(text, path.string()), path);
}

}  // namespace bounce::scene
