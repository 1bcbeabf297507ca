#pragma once
// Shared helpers for the metrics tests: deterministic images and a per-test output folder.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <random>
#include <string>

#include "engine/core/image.hpp"

namespace bounce::ref::test {

// A fresh, empty folder under BOUNCE_TEST_OUT named after the running test, so ctest can run
// tests in parallel without them sharing files.
inline std::filesystem::path testDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::path(BOUNCE_TEST_OUT) / "metrics" /
                   (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Uniform values in [lo, hi) from a fixed seed (std::mt19937's output is specified exactly by the
// standard, unlike the distributions, so values are computed from raw 32-bit draws).
inline ImageRGB randomImage(int w, int h, std::uint32_t seed, float lo = 0.0f, float hi = 1.0f) {
  std::mt19937 rng(seed);
  ImageRGB img(w, h);
  for (auto& p : img.pixels)
    for (int c = 0; c < 3; ++c) p[c] = lo + (hi - lo) * static_cast<float>(rng() >> 8) * (1.0f / 16777216.0f);
  return img;
}

}  // namespace bounce::ref::test
