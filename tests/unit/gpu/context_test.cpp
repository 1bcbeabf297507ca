// Context creation and device choice.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "engine/core/error.hpp"
#include "engine/gpu/testing.hpp"

using namespace bounce;
using namespace bounce::gpu;

TEST(Context, PicksAUsableDevice) {
  Context& ctx = testkit::sharedContext();
  EXPECT_FALSE(ctx.deviceName().empty());
  EXPECT_GE(ctx.apiVersion(), VK_API_VERSION_1_2);
  EXPECT_NE(ctx.device(), VK_NULL_HANDLE);
  EXPECT_NE(ctx.queue(), VK_NULL_HANDLE);
  if (testkit::runningAsGpuTest()) {
    EXPECT_TRUE(ctx.validationEnabled());
  }
  std::string quoted = std::string(1, '\'').append(ctx.deviceName()).append(1, '\'');
  std::size_t matches = 0;
  for (const std::string& d : describeDevices()) matches += d.find(quoted) != std::string::npos;
  EXPECT_GE(matches, 1u);
}

TEST(Context, ChoosesByCaseInsensitiveNameSubstring) {
  std::string name = testkit::sharedContext().deviceName();
  std::string part = name.substr(0, std::min<std::size_t>(name.size(), 6));
  for (char& c : part) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  ContextOptions o;
  o.deviceName = part;
  Context ctx(o);
  EXPECT_EQ(ctx.deviceName().substr(0, 6), name.substr(0, 6));
}

TEST(Context, UnknownDeviceNameIsAClearError) {
  ContextOptions o;
  o.deviceName = "no-such-gpu-9000";
  try {
    Context ctx(o);
    FAIL() << "expected an error";
  } catch (const InputError& e) {  // the user's argument: exit 2 (issue 16)
    std::string msg = e.what();
    EXPECT_NE(msg.find("no Vulkan device matches --device 'no-such-gpu-9000'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("available: '" + testkit::sharedContext().deviceName() + "'"), std::string::npos) << msg;
  }
}

TEST(Context, UnknownDeviceFromEnvironmentNamesTheVariable) {
  ::setenv("BOUNCE_DEVICE", "still-no-such-gpu", 1);
  try {
    Context ctx;
    ::unsetenv("BOUNCE_DEVICE");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    ::unsetenv("BOUNCE_DEVICE");
    EXPECT_NE(std::string(e.what()).find("BOUNCE_DEVICE 'still-no-such-gpu'"), std::string::npos) << e.what();
  }
}
