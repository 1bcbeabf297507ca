#pragma once
// Where the running `bounce` (or a test binary) finds its compiled shaders, its content and its
// caches — found at run time, never compiled in, so a build or an installed prefix can be moved.
//
// Layouts recognised, in order:
//   build tree:  <build>/bounce, <build>/tests/..., <build>/shaders/, <build>/CMakeCache.txt
//   installed:   <prefix>/bin/bounce, <prefix>/share/bounce/{shaders,content}
// Each folder can be overridden by an environment variable (BOUNCE_SHADER_DIR, BOUNCE_CONTENT,
// BOUNCE_CACHE); an empty variable counts as unset.
#include <filesystem>
#include <optional>
#include <string_view>

namespace bounce {

// Folder holding the running executable (from /proc/self/exe).
std::filesystem::path executableDir();

// The nearest folder at or above executableDir() that holds CMakeCache.txt: the build tree this
// binary was built in, if it still sits in one.
std::optional<std::filesystem::path> buildTreeDir();

// Compiled SPIR-V: $BOUNCE_SHADER_DIR, else <build>/shaders, else <exe>/../share/bounce/shaders.
std::filesystem::path shaderDir();

// The content/ folder (levels, captures, glTF sources): $BOUNCE_CONTENT, else <exe>/content,
// <exe>/../share/bounce/content, else the source tree's content/ when the build tree is one.
std::filesystem::path contentDir();

// Root of every cache (cooked assets, probe volumes, technique bakes, reference images):
// $BOUNCE_CACHE, else <build>/cache in a build tree, else $XDG_CACHE_HOME/bounce
// (~/.cache/bounce) for an installed or moved binary.
std::filesystem::path cacheRoot();

// cacheRoot()/kind — one folder per kind ("cooked", "probes", "dnrt", "reference", ...).
std::filesystem::path cacheDir(std::string_view kind);

// Where commands write output nobody asked a path for (e.g. `bounce demo`): <build> in a build
// tree, else the current directory.
std::filesystem::path defaultOutputRoot();

}  // namespace bounce
