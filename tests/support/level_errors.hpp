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
void expectOneLineLoadErrors(std::span<const std::pair<const char*, std::string>> cases, Write&& write) {
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

}  // namespace bounce::testlevel
