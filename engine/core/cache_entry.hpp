#pragma once
// One bake cache entry, the same for every technique: load it when present and valid, else bake
// and write it. A corrupt or truncated entry (its loader throws InputError) is re-baked, never
// trusted; `warning` prefixes the loader's message in the one warning line.
#include <filesystem>
#include <string>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"

namespace bounce {

// load(path) -> T (InputError when corrupt); bake() -> T; save(const T&, path) writes atomically.
// `fromCache` (may be null): whether the entry was loaded rather than baked.
template <class Load, class Bake, class Save>
auto loadOrBake(const std::filesystem::path& path, const std::string& warning, Load load, Bake bake, Save save,
                bool* fromCache) -> decltype(load(path)) {
  if (std::filesystem::exists(path)) {
    try {
      auto value = load(path);
      if (fromCache) *fromCache = true;
      return value;
    } catch (const InputError& e) {
      log::warn(warning + e.what());
    }
  }
  auto value = bake();
  std::filesystem::create_directories(path.parent_path());
  save(value, path);
  if (fromCache) *fromCache = false;
  return value;
}

}  // namespace bounce
