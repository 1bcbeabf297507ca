#pragma once
// Shared helpers for the asset tests: paths, scratch folders, and building hostile variants of
// real sample assets at run time.
#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace bounce::asset::test {

namespace fs = std::filesystem;

// BOUNCE_SHARED_DIR (the build's ../shared); the environment variable of the same name overrides
// it, for worktrees that do not sit next to the shared folder.
inline fs::path assets() {
  const char* env = std::getenv("BOUNCE_SHARED_DIR");
  return fs::path(env && *env ? env : BOUNCE_SHARED_DIR) / "assets";
}

// A fresh empty scratch folder per test: BOUNCE_TEST_OUT/asset/<suite>.<test>.
inline fs::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::path(BOUNCE_TEST_OUT) / "asset" / (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline CookOptions geometryOnly() {
  CookOptions o;
  o.decodeImages = false;
  return o;
}

inline nlohmann::json readJson(const fs::path& p) { return nlohmann::json::parse(readFileText(p)); }
inline void writeJson(const fs::path& p, const nlohmann::json& j) { writeFileAtomic(p, j.dump(1)); }

// Copies every file of `folder` into `dir` (so a modified .gltf still finds its .bin and images).
inline void copyFolder(const fs::path& folder, const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(folder))
    if (e.is_regular_file()) {
      fs::copy_file(e.path(), dir / e.path().filename(), fs::copy_options::overwrite_existing);
      fs::permissions(dir / e.path().filename(), fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::add);
    }
}

// Byte offset inside its buffer of element `element` of accessor `accessor`.
inline std::size_t elementOffset(const nlohmann::json& doc, int accessor, std::size_t element) {
  const auto& a = doc["accessors"][accessor];
  const auto& bv = doc["bufferViews"][a["bufferView"].get<int>()];
  const std::size_t componentBytes = a["componentType"].get<int>() == 5126 ? 4 : a["componentType"].get<int>() == 5123 ? 2 : 4;
  const std::size_t comps = a["type"] == "VEC3" ? 3 : a["type"] == "VEC2" ? 2 : a["type"] == "VEC4" ? 4 : 1;
  const std::size_t stride = bv.value("byteStride", componentBytes * comps);
  return bv.value("byteOffset", std::size_t(0)) + a.value("byteOffset", std::size_t(0)) + element * stride;
}

// Runs `fn`, expects an InputError whose message contains every string of `parts`; returns it.
inline std::string expectInputError(const std::function<void()>& fn, const std::vector<std::string>& parts) {
  try {
    fn();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "message is not one line: " << msg;
    return msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got other exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected an InputError, none thrown";
  return {};
}

}  // namespace bounce::asset::test
