#include "engine/core/paths.hpp"

#include <cstdlib>
#include <initializer_list>
#include <system_error>

namespace bounce {
namespace fs = std::filesystem;

namespace {

std::string envString(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

bool isDir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

// The first candidate that is an existing folder, else `fallback`. Empty candidates are skipped.
fs::path firstDir(std::initializer_list<fs::path> candidates, const fs::path& fallback) {
  for (const auto& c : candidates)
    if (!c.empty() && isDir(c)) return c;
  return fallback;
}

std::optional<fs::path> findBuildTree(const fs::path& exeDir) {
  std::error_code ec;
  for (fs::path dir = exeDir; !dir.empty(); dir = dir.parent_path()) {
    if (fs::is_regular_file(dir / "CMakeCache.txt", ec)) return dir;
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

}  // namespace

PathEnv PathEnv::fromProcess() {
  return {envString("BOUNCE_SHADER_DIR"), envString("BOUNCE_CONTENT"), envString("BOUNCE_CACHE"),
          envString("XDG_CACHE_HOME"), envString("HOME")};
}

Layout resolveLayout(const fs::path& exeDir, const PathEnv& env, const fs::path& cwd) {
  Layout l;
  l.buildTree = findBuildTree(exeDir);
  const fs::path build = l.buildTree.value_or(fs::path());
  const fs::path share = exeDir.parent_path() / "share" / "bounce";
  const auto inBuild = [&](const char* name) { return build.empty() ? fs::path() : build / name; };

  l.shaders = !env.shaderDir.empty()
                  ? fs::path(env.shaderDir)
                  : firstDir({inBuild("shaders"), exeDir / "shaders"}, share / "shaders");
  l.content = !env.content.empty()
                  ? fs::path(env.content)
                  : firstDir({exeDir / "content", share / "content", inBuild("content")}, cwd / "content");
  l.tools = firstDir({exeDir / "tools", share / "tools", inBuild("tools")}, cwd / "tools");

  if (!env.cache.empty()) l.cacheRoot = env.cache;
  else if (!build.empty()) l.cacheRoot = build / "cache";
  else if (!env.xdgCache.empty()) l.cacheRoot = fs::path(env.xdgCache) / "bounce";
  else if (!env.home.empty()) l.cacheRoot = fs::path(env.home) / ".cache" / "bounce";
  else l.cacheRoot = cwd / ".bounce-cache";

  l.outputRoot = build.empty() ? cwd : build;
  return l;
}

fs::path executableDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || exe.empty()) return fs::current_path(ec);
  return exe.parent_path();
}

Layout currentLayout() {
  std::error_code ec;
  return resolveLayout(executableDir(), PathEnv::fromProcess(), fs::current_path(ec));
}

std::optional<fs::path> buildTreeDir() { return findBuildTree(executableDir()); }

fs::path shaderDir() { return currentLayout().shaders; }
fs::path contentDir() { return currentLayout().content; }
fs::path toolsDir() { return currentLayout().tools; }
fs::path cacheRoot() { return currentLayout().cacheRoot; }
fs::path defaultOutputRoot() { return currentLayout().outputRoot; }

fs::path cacheDir(std::string_view kind) { return cacheRoot() / std::string(kind); }

}  // namespace bounce
