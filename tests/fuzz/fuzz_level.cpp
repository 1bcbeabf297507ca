// Fuzz target: bytes → the level and capture-script readers (engine/scene: strict JSON with
// pointers, entity components, motion scripts). Every input goes through both readers: a level is
// not a capture script, so at most one accepts it and the other stops at its first key. The input
// is read as if it were content/levels/fuzz.json (resp. content/captures/fuzz.json), so the real
// levels' relative asset paths (../src/...) resolve and mutations reach past the mesh checks.
//
// What must hold, else the target throws std::logic_error (a libFuzzer crash):
//  - a rejection is an InputError of one line "file: where: what (expected …)": it starts with the
//    file name and holds no control character (a raw newline from a hostile key would break the
//    one-line contract of README "Using bounce");
//  - whatever is accepted is usable: a level instantiates (one entity per description, cannot fail
//    on a loaded Level), every motion (entities', the capture camera's) evaluates at a few times.
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/log.hpp"
#include "engine/core/paths.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/scene/capture.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/motion.hpp"
#include "tests/fuzz/fuzz_target.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace {

using namespace bounce;

// Times a motion is evaluated at: the start, inside a typical clip, past any clip, negative.
constexpr double kTimes[] = {0.0, 0.37, 1.0e4, -2.5};

void checkMessage(const InputError& e, const std::string& file) {
  const std::string_view m = e.what();
  if (m.substr(0, file.size() + 2) != file + ": ")
    throw std::logic_error("error message does not start with the file name: " + std::string(m.substr(0, 200)));
  for (char c : m)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw std::logic_error("error message holds control character " + std::to_string(int(c)) + ": " +
                             std::string(m.substr(0, 200)));
}

void evaluate(const scene::Motion& m) {
  for (double t : kTimes) (void)scene::evaluateMotion(m, t);
}

const std::filesystem::path& levelPath() {
  static const std::filesystem::path p = contentDir() / "levels" / "fuzz.json";
  return p;
}
const std::filesystem::path& capturePath() {
  static const std::filesystem::path p = contentDir() / "captures" / "fuzz.json";
  return p;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  bounce::log::setLevel(bounce::log::Level::Quiet);
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const scene::Level level = scene::parseLevel(text, levelPath());
    ecs::Registry registry;
    if (scene::instantiate(level, registry).size() != level.entities.size())
      throw std::logic_error("instantiate made a different number of entities than the level describes");
    for (const auto& e : level.entities)
      if (e.motion) evaluate(*e.motion);
  } catch (const InputError& e) {
    checkMessage(e, levelPath().string());
  }
  try {
    const scene::CaptureScript script = scene::parseCaptureScript(text, capturePath());
    if (script.camera) evaluate(*script.camera);
  } catch (const InputError& e) {
    checkMessage(e, capturePath().string());
  }
  return 0;
}

// Seeds: the files themselves (content/levels/*.json, content/captures/*.json).
std::vector<std::vector<std::uint8_t>> fuzzSeeds(const std::vector<std::string>& paths) {
  std::vector<std::vector<std::uint8_t>> out;
  for (const auto& p : paths) out.push_back(readFileBytes(p));
  return out;
}
