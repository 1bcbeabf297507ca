#pragma once
// GoogleTest support for GPU tests. Including this header in any file of a test executable
// registers a listener that fails the running test when a Vulkan validation error was reported
// during it (by any Context), then resets the count for the next test. Tests that provoke an
// error on purpose assert on the count and call resetValidationErrorsTotal() themselves.
//
// sharedContext() is one headless Context per test process (ctest runs each TEST in its own
// process); tests that need special options build their own.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include "engine/gpu/context.hpp"

namespace bounce::gpu::testkit {

class ValidationListener : public ::testing::EmptyTestEventListener {
 public:
  void OnTestStart(const ::testing::TestInfo&) override { resetValidationErrorsTotal(); }
  // Failures raised in OnTestEnd are recorded against the test that just ran (the googletest
  // "leak checker" pattern), so the test and the executable fail.
  void OnTestEnd(const ::testing::TestInfo&) override {
    std::uint64_t errors = validationErrorsTotal();
    EXPECT_EQ(errors, 0u) << "Vulkan validation reported " << errors << " error(s) during this test (printed above)";
    resetValidationErrorsTotal();
  }
};

inline bool registerValidationListener() {
  ::testing::UnitTest::GetInstance()->listeners().Append(new ValidationListener);
  return true;
}
// Runs once per executable, before main(), however many files include this header.
inline const bool kValidationListenerRegistered = registerValidationListener();

// True when ctest runs this as a GPU test (bounce_test(... GPU) sets BOUNCE_GPU_TEST=1); such
// runs must have validation on, or "no validation errors" would prove nothing.
inline bool runningAsGpuTest() {
  const char* v = std::getenv("BOUNCE_GPU_TEST");
  return v && std::string(v) == "1";
}

inline Context& sharedContext() {
  static std::unique_ptr<Context> ctx = std::make_unique<Context>();
  return *ctx;
}

}  // namespace bounce::gpu::testkit
