// engine/core/paths.hpp: the folder rules for a build tree, an installed prefix (also after it is
// moved), a folder with everything beside the executable, each environment override, and the
// running test binary's own build tree.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <unistd.h>

#include "engine/core/paths.hpp"

using namespace bounce;
namespace fs = std::filesystem;

namespace {

// A scratch folder outside any build tree: a fake prefix under BOUNCE_TEST_OUT would find the real
// build's CMakeCache.txt above it and be taken for a build tree.
class PathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("bounce-paths-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "cwd");
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path dir(const fs::path& rel) {
    fs::create_directories(root_ / rel);
    return root_ / rel;
  }
  void file(const fs::path& rel) {
    fs::create_directories((root_ / rel).parent_path());
    std::ofstream(root_ / rel) << "x";
  }
  // A build tree as CMake leaves it: CMakeCache.txt, shaders/, and the content/ and tools/ links.
  fs::path buildTree(const fs::path& rel) {
    file(rel / "CMakeCache.txt");
    dir(rel / "shaders");
    dir("src/content");
    dir("src/tools");
    fs::create_directory_symlink(root_ / "src/content", root_ / rel / "content");
    fs::create_directory_symlink(root_ / "src/tools", root_ / rel / "tools");
    dir(rel / "tests/unit/core");
    return root_ / rel;
  }
  // An installed prefix as `cmake --install` leaves it.
  fs::path prefix(const fs::path& rel) {
    dir(rel / "bin");
    for (const char* d : {"shaders", "content", "tools"}) dir(rel / "share/bounce" / d);
    return root_ / rel;
  }
  fs::path cwd() const { return root_ / "cwd"; }

  fs::path root_;
};

PathEnv homeOnly() {
  PathEnv env;
  env.xdgCache = "/xdg";
  env.home = "/home/u";
  return env;
}

}  // namespace

TEST_F(PathsTest, BuildTreeFromTheRootAndFromATestFolder) {
  const fs::path build = buildTree("build/release");
  for (const fs::path& exe : {build, build / "tests/unit/core"}) {
    SCOPED_TRACE(exe.string());
    const Layout l = resolveLayout(exe, homeOnly(), cwd());
    ASSERT_TRUE(l.buildTree.has_value());
    EXPECT_EQ(*l.buildTree, build);
    EXPECT_EQ(l.shaders, build / "shaders");
    EXPECT_EQ(l.content, build / "content");
    EXPECT_EQ(l.tools, build / "tools");
    EXPECT_EQ(l.cacheRoot, build / "cache");  // a build keeps its caches, XDG_CACHE_HOME notwithstanding
    EXPECT_EQ(l.outputRoot, build);
  }
}

TEST_F(PathsTest, InstalledPrefixAndTheSamePrefixMoved) {
  const fs::path first = prefix("opt/bounce");
  const Layout a = resolveLayout(first / "bin", homeOnly(), cwd());
  EXPECT_FALSE(a.buildTree.has_value());
  EXPECT_EQ(a.shaders, first / "share/bounce/shaders");
  EXPECT_EQ(a.content, first / "share/bounce/content");
  EXPECT_EQ(a.tools, first / "share/bounce/tools");
  EXPECT_EQ(a.cacheRoot, fs::path("/xdg/bounce"));
  EXPECT_EQ(a.outputRoot, cwd());

  const fs::path moved = root_ / "elsewhere";
  fs::rename(first, moved);
  const Layout b = resolveLayout(moved / "bin", homeOnly(), cwd());
  EXPECT_EQ(b.shaders, moved / "share/bounce/shaders");
  EXPECT_EQ(b.content, moved / "share/bounce/content");
  EXPECT_EQ(b.tools, moved / "share/bounce/tools");
}

TEST_F(PathsTest, InstalledCacheFallsBackFromXdgToHomeToCwd) {
  const fs::path p = prefix("p");
  PathEnv env = homeOnly();
  env.xdgCache.clear();
  EXPECT_EQ(resolveLayout(p / "bin", env, cwd()).cacheRoot, fs::path("/home/u/.cache/bounce"));
  env.home.clear();
  EXPECT_EQ(resolveLayout(p / "bin", env, cwd()).cacheRoot, cwd() / ".bounce-cache");
}

TEST_F(PathsTest, FoldersBesideTheExecutableWinOverShare) {
  // A flat folder, bounce beside its data (a hand-made copy): bounce, shaders/, content/, tools/.
  const fs::path flat = dir("flat");
  for (const char* d : {"shaders", "content", "tools"}) dir(fs::path("flat") / d);
  dir("share/bounce/content");  // flat/../share/bounce: must lose to flat/content
  const Layout l = resolveLayout(flat, homeOnly(), cwd());
  EXPECT_EQ(l.shaders, flat / "shaders");
  EXPECT_EQ(l.content, flat / "content");
  EXPECT_EQ(l.tools, flat / "tools");
}

TEST_F(PathsTest, EnvironmentOverridesEveryLayout) {
  const fs::path build = buildTree("b");
  const fs::path p = prefix("p");
  PathEnv env = homeOnly();
  env.shaderDir = "/s";
  env.content = "/c";
  env.cache = "/k";
  for (const fs::path& exe : {build, p / "bin"}) {
    SCOPED_TRACE(exe.string());
    const Layout l = resolveLayout(exe, env, cwd());
    EXPECT_EQ(l.shaders, fs::path("/s"));
    EXPECT_EQ(l.content, fs::path("/c"));
    EXPECT_EQ(l.cacheRoot, fs::path("/k"));
  }
}

TEST_F(PathsTest, EmptyVariablesCountAsUnset) {
  const fs::path build = buildTree("b");
  PathEnv env = homeOnly();  // shaderDir, content, cache: ""
  const Layout l = resolveLayout(build, env, cwd());
  EXPECT_EQ(l.shaders, build / "shaders");
  EXPECT_EQ(l.content, build / "content");
  EXPECT_EQ(l.cacheRoot, build / "cache");
}

TEST_F(PathsTest, NothingFoundGivesTheInstalledShadersAndTheCurrentDirectory) {
  const fs::path bare = dir("bare/bin");
  const Layout l = resolveLayout(bare, homeOnly(), cwd());
  EXPECT_EQ(l.shaders, root_ / "bare/share/bounce/shaders");  // named in the error when a shader is missing
  EXPECT_EQ(l.content, cwd() / "content");
  EXPECT_EQ(l.tools, cwd() / "tools");
}

// The test binary itself: it runs in the build tree CMake made (BOUNCE_TEST_OUT is <build>/test-out),
// whose content/ and tools/ links lead to the source tree.
TEST(PathsRunning, TestBinaryFindsItsBuildTree) {
  ::unsetenv("BOUNCE_SHADER_DIR"), ::unsetenv("BOUNCE_CONTENT"), ::unsetenv("BOUNCE_CACHE");
  const fs::path build = fs::canonical(fs::path(BOUNCE_TEST_OUT).parent_path());
  ASSERT_TRUE(buildTreeDir().has_value());
  EXPECT_EQ(fs::canonical(*buildTreeDir()), build);
  EXPECT_EQ(fs::canonical(shaderDir()), build / "shaders");
  EXPECT_TRUE(fs::is_regular_file(shaderDir() / "test/fill.comp.spv"));
  EXPECT_TRUE(fs::equivalent(contentDir(), fs::path(BOUNCE_SOURCE_DIR) / "content"));
  EXPECT_TRUE(fs::equivalent(toolsDir(), fs::path(BOUNCE_SOURCE_DIR) / "tools"));
  EXPECT_TRUE(fs::is_regular_file(toolsDir() / "plot_accuracy.py"));
  EXPECT_EQ(fs::canonical(defaultOutputRoot()), build);
  EXPECT_EQ(cacheDir("dnrt"), *buildTreeDir() / "cache" / "dnrt");
}

TEST(PathsRunning, ProcessEnvironmentIsRead) {
  ::setenv("BOUNCE_CACHE", "/tmp/bounce-paths-cache", 1);
  ::setenv("BOUNCE_SHADER_DIR", "/tmp/bounce-paths-shaders", 1);
  ::setenv("BOUNCE_CONTENT", "", 1);  // empty: unset
  EXPECT_EQ(cacheDir("cooked"), fs::path("/tmp/bounce-paths-cache/cooked"));
  EXPECT_EQ(shaderDir(), fs::path("/tmp/bounce-paths-shaders"));
  EXPECT_TRUE(fs::equivalent(contentDir(), fs::path(BOUNCE_SOURCE_DIR) / "content"));
  ::unsetenv("BOUNCE_CACHE"), ::unsetenv("BOUNCE_SHADER_DIR"), ::unsetenv("BOUNCE_CONTENT");
}
