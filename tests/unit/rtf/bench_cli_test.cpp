// `bounce bench rtf`'s bad input: one `file: where: what (expected …)` line on stderr, exit 2,
// before any bake starts. (Its timings are not tested.)
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/cli_run.hpp"

namespace {

using bounce::testcli::lines;
using bounce::testcli::runBounce;

const std::filesystem::path kOut = std::filesystem::path(BOUNCE_TEST_OUT) / "rtf-cli";

TEST(RtfBenchCli, OutOfRangeSettingsAreOneLineAndExit2) {
  for (const auto& [option, value] : {std::pair<std::string, std::string>{"--bounces", "5"}, {"--proxies", "65"},
                                      {"--spheres", "1"}, {"--components", "0"}, {"--byte-components", "17"}, {"--byte-components", "-1"}, {"--radii", "4,2"},
                                      {"--radii", "0.5"}, {"--radii", "0,4"}}) {
    const auto r = runBounce({"bench", "rtf", option, value}, kOut / (option.substr(2) + "-" + value));
    EXPECT_EQ(r.code, 2) << option;
    const auto err = lines(r.err);
    ASSERT_EQ(err.size(), 1u) << r.err;
    EXPECT_NE(err[0].find(option), std::string::npos) << err[0];
    EXPECT_NE(err[0].find("expected"), std::string::npos) << err[0];
    EXPECT_TRUE(r.out.empty()) << "nothing baked or printed before the check";
  }
}

// --object: without --no-gpu, an id the level does not have, or an entity without a mesh (the
// camera). Checked against the level file, before anything is cooked.
TEST(RtfBenchCli, BadObjectIsOneLineAndExit2) {
  for (const auto& [args, what] :
       {std::pair<std::vector<std::string>, std::string>{{"--object", "prop-truck"}, "without --no-gpu"},
        {{"--object", "no-such-prop", "--no-gpu"}, "'no-such-prop' is no entity of cornell-5"},
        {{"--object", "camera", "--no-gpu"}, "'camera' has no mesh"}}) {
    std::vector<std::string> full{"bench", "rtf", "--level", "cornell-5"};
    full.insert(full.end(), args.begin(), args.end());
    const auto r = runBounce(full, kOut / ("object-" + args[1]));
    EXPECT_EQ(r.code, 2) << what;
    const auto err = lines(r.err);
    ASSERT_EQ(err.size(), 1u) << r.err;
    EXPECT_NE(err[0].find("--object: " + what), std::string::npos) << err[0];
    EXPECT_NE(err[0].find("expected"), std::string::npos) << err[0];
    EXPECT_TRUE(r.out.empty()) << "nothing baked or printed before the check";
  }
}

// --object takes any entity with a mesh, not only one with a dnrt component: cornell-5's room has
// neither a dnrt nor an rtf component. Baked at the command's settings (the smallest field there
// is, < 1 s), which its line reports; then one CPU bounce row for the one object. --byte-components 0
// is the default (all fp16) and must be accepted as such; the line reports n₈.
TEST(RtfBenchCli, ObjectIsAnyEntityWithAMesh) {
  const std::filesystem::path dir = kOut / "object-room";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "cache");
  const auto r = bounce::testcli::runShell(
      bounce::testcli::bounceCommand({"bench", "rtf", "--level", "cornell-5", "--no-gpu", "--object", "cornell-box",
                                      "--runs", "1", "--proxies", "1", "--spheres", "2", "--face", "1", "--rays", "1",
                                      "--vertex-rays", "1", "--clusters", "1", "--components", "1", "--byte-components", "0"},
                                     "BOUNCE_CACHE=" + bounce::testcli::quote((dir / "cache").string()) + " "),
      dir / "stdout.txt", dir / "stderr.txt");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto out = lines(r.out);
  ASSERT_EQ(out.size(), 2u) << r.out;
  EXPECT_EQ(out[0].rfind("object=cornell-box proxies=1 clusters=1 components=1 byte_components=0 ", 0), 0u) << out[0];
  EXPECT_EQ(out[1].rfind("objects=1 bounces=2 ", 0), 0u) << out[1];
}

TEST(RtfBenchCli, UnknownShadingResolutionIsOneLineAndExit2BeforeAnyBake) {
  const auto r = runBounce({"bench", "rtf", "--level", "cornell-5", "--no-gpu", "--rtf-resolution", "full,eighth"}, kOut / "resolution");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.out).size(), 0u) << r.out;  // nothing baked or printed first
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("--rtf-resolution: 'eighth' is not a resolution (expected full, half, quarter or a list"), std::string::npos) << r.err;
}

TEST(RtfBenchCli, MissingLevelIsOneLineAndExit2) {
  const auto r = runBounce({"bench", "rtf", "--level", "no-such-level"}, kOut / "level");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("no-such-level"), std::string::npos) << r.err;
}

}  // namespace
