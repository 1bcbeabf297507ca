#pragma once
// Where the running `bounce` (or a test binary) finds its compiled shaders, its content, its tools
// and its caches — found at run time, never compiled in, so a build or an installed prefix can be
// moved and still run.
//
// Layouts recognised:
//   build tree:  <build>/bounce, <build>/tests/..., <build>/CMakeCache.txt, <build>/shaders/, and the
//                links <build>/content and <build>/tools into the source tree (made at configure time)
//   installed:   <prefix>/bin/bounce, <prefix>/share/bounce/{shaders,content,tools} (`cmake --install`)
// Each folder can be overridden by an environment variable (BOUNCE_SHADER_DIR, BOUNCE_CONTENT,
// BOUNCE_CACHE); an empty variable counts as unset.
//
// Every rule lives in resolveLayout(), a pure function of the executable's folder and the
// environment, so tests can check a build tree, an installed prefix and each override without
// moving the test binary. The free functions below apply it to the running process.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace bounce {

// The environment variables the layout reads; an empty string is an unset variable.
struct PathEnv {
  std::string shaderDir;  // BOUNCE_SHADER_DIR
  std::string content;    // BOUNCE_CONTENT
  std::string cache;      // BOUNCE_CACHE
  std::string xdgCache;   // XDG_CACHE_HOME
  std::string home;       // HOME

  static PathEnv fromProcess();
};

// Every folder the program reads or writes without being told, for one executable location.
struct Layout {
  std::optional<std::filesystem::path> buildTree;  // nearest folder at or above the executable holding CMakeCache.txt
  std::filesystem::path shaders;     // compiled SPIR-V
  std::filesystem::path content;     // levels/, captures/, src/
  std::filesystem::path tools;       // helper scripts (plot_accuracy.py)
  std::filesystem::path cacheRoot;   // one sub-folder per cache kind
  std::filesystem::path outputRoot;  // where `bounce demo` writes when no --out is given
};

// The layout for an executable in `exeDir`, given the environment and the current directory
// (the last resort for the content, tools and output folders). Rules, first match wins:
//   shaders:  $BOUNCE_SHADER_DIR · <build>/shaders · <exe>/shaders · <exe>/../share/bounce/shaders
//   content:  $BOUNCE_CONTENT · <exe>/content · <exe>/../share/bounce/content · <build>/content · <cwd>/content
//   tools:    <exe>/tools · <exe>/../share/bounce/tools · <build>/tools · <cwd>/tools
//   cache:    $BOUNCE_CACHE · <build>/cache · $XDG_CACHE_HOME/bounce · $HOME/.cache/bounce · <cwd>/.bounce-cache
//   output:   <build> · <cwd>
// A folder candidate counts only if it exists; the last one of each list is taken as is.
Layout resolveLayout(const std::filesystem::path& exeDir, const PathEnv& env, const std::filesystem::path& cwd);

// resolveLayout(executableDir(), PathEnv::fromProcess(), current directory).
Layout currentLayout();

// Folder holding the running executable (from /proc/self/exe).
std::filesystem::path executableDir();

// The nearest folder at or above executableDir() that holds CMakeCache.txt: the build tree this
// binary was built in, if it still sits in one.
std::optional<std::filesystem::path> buildTreeDir();

// The running process's folders (currentLayout()'s members).
std::filesystem::path shaderDir();
std::filesystem::path contentDir();
std::filesystem::path toolsDir();
std::filesystem::path cacheRoot();
std::filesystem::path defaultOutputRoot();

// cacheRoot()/kind — one folder per kind ("cooked", "probes", "dnrt", "reference", ...).
std::filesystem::path cacheDir(std::string_view kind);

}  // namespace bounce
