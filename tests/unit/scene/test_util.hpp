#pragma once
// Shared helpers for the scene tests: write a level file, catch the one-line error.
#include <filesystem>
#include <functional>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"

namespace bounce::scene::test {

inline std::filesystem::path dataDir() { return std::filesystem::path(BOUNCE_SOURCE_DIR) / "tests/data/levels"; }
inline std::filesystem::path outDir() { return std::filesystem::path(BOUNCE_TEST_OUT) / "scene"; }

// Writes `text` to BOUNCE_TEST_OUT/scene/<name> and returns the path.
inline std::filesystem::path writeTemp(const std::string& name, const std::string& text) {
  const auto path = outDir() / name;
  writeFileAtomic(path, text);
  return path;
}

// The InputError message fn throws, or "(no error)".
inline std::string inputErrorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace bounce::scene::test
