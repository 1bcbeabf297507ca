#include "engine/core/paths.hpp"

#include <cstdlib>
#include <string>
#include <system_error>

namespace bounce {
namespace fs = std::filesystem;

namespace {

std::optional<fs::path> envPath(const char* name) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return std::nullopt;
  return fs::path(v);
}

bool isDir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

}  // namespace

fs::path executableDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || exe.empty()) return fs::current_path(ec);
  return exe.parent_path();
}

std::optional<fs::path> buildTreeDir() {
  std::error_code ec;
  for (fs::path dir = executableDir(); !dir.empty(); dir = dir.parent_path()) {
    if (fs::is_regular_file(dir / "CMakeCache.txt", ec)) return dir;
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

fs::path shaderDir() {
  if (auto env = envPath("BOUNCE_SHADER_DIR")) return *env;
  if (auto build = buildTreeDir(); build && isDir(*build / "shaders")) return *build / "shaders";
  const fs::path exe = executableDir();
  if (isDir(exe / "shaders")) return exe / "shaders";
  return exe.parent_path() / "share" / "bounce" / "shaders";
}

fs::path contentDir() {
  if (auto env = envPath("BOUNCE_CONTENT")) return *env;
  const fs::path exe = executableDir();
  if (isDir(exe / "content")) return exe / "content";
  if (isDir(exe.parent_path() / "share" / "bounce" / "content")) return exe.parent_path() / "share" / "bounce" / "content";
#ifdef BOUNCE_SOURCE_DIR
  if (buildTreeDir() && isDir(fs::path(BOUNCE_SOURCE_DIR) / "content")) return fs::path(BOUNCE_SOURCE_DIR) / "content";
#endif
  return fs::current_path() / "content";
}

fs::path cacheRoot() {
  if (auto env = envPath("BOUNCE_CACHE")) return *env;
  if (auto build = buildTreeDir()) return *build / "cache";
  if (auto xdg = envPath("XDG_CACHE_HOME")) return *xdg / "bounce";
  if (auto home = envPath("HOME")) return *home / ".cache" / "bounce";
  return fs::current_path() / ".bounce-cache";
}

fs::path cacheDir(std::string_view kind) { return cacheRoot() / std::string(kind); }

fs::path defaultOutputRoot() {
  if (auto build = buildTreeDir()) return *build;
  std::error_code ec;
  return fs::current_path(ec);
}

}  // namespace bounce
