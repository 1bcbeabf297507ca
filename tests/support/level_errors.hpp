#pragma once
// A level-wide key's bad input, checked the same way for each technique's key (tests/unit/dnrt/
// level_test.cpp "dnrt", tests/unit/rtf/technique_test.cpp "rtf"): every case is one InputError line that
// starts with the level file's path and the expected place and message.
#include <gtest/gtest.h>

#include <filesystem>
#include <span>
#include <string>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/scene/level.hpp"

namespace bounce::testlevel {

// Each case (json, want): `write(json)` writes a level whose key holds `json` and returns its path;
// loading it must throw one line beginning with that path followed by `want`.
template <class Write>
void expectOneLineLoadErrors(std::span<const std::pair<std::string, std::string>> cases, Write&& write) {
  for (const auto& [json, want] : cases) {
    const std::filesystem::path path = write(json);
    try {
      scene::loadLevel(path);
      ADD_FAILURE() << json;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path.string() + want, 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

// A level-wide `{"resolution": …}` object under `key` ("dnrt", "rtf"; gi/resolution.hpp's names): an
// unknown name, a number, a key the object does not take (`otherKey`) and a string in place of the object,
// each one line at its place.
template <class Write>
void expectResolutionKeyErrors(const std::string& key, const std::string& otherKey, Write&& write) {
  const std::pair<std::string, std::string> cases[] = {
      {R"({"resolution": "eighth"})",
       ": /" + key + "/resolution: unknown resolution \"eighth\" (expected full, half or quarter)"},
      {R"({"resolution": 2})", ": /" + key + "/resolution: wrong type: integer (expected a string)"},
      {"{\"" + otherKey + "\": 2}", ": /" + key + "/" + otherKey + ": "},
      {R"("half")", ": /" + key + ": "},
  };
  expectOneLineLoadErrors(cases, std::forward<Write>(write));
}

}  // namespace bounce::testlevel
