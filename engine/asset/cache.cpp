// The cooked-asset cache. An entry is named by a hash of everything the cook depends on, so a
// changed input gives a new name; an entry that fails to read (corrupt, truncated, other format
// or cooker version) is re-cooked and overwritten, never trusted.
#include "engine/asset/cook.hpp"
#include "engine/asset/cooked_format.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "engine/core/progress.hpp"

namespace bounce::asset {

std::string cacheKey(const std::filesystem::path& source, const CookOptions& options) {
  Hasher h;
  h.str("bounce-cook").u64(kCookerVersion).u64(kCookedFormatVersion);
  const std::vector<std::uint8_t> bytes = readFileBytes(source);
  h.u64(bytes.size()).bytes(bytes.data(), bytes.size());
  std::vector<std::filesystem::path> refs;
  try {
    refs = referencedFiles(source);
  } catch (const InputError&) {
    // Unparseable: the key covers the bytes alone and cook() reports the error.
  }
  for (const auto& ref : refs) {
    h.str(ref.filename().string());
    std::error_code ec;
    if (!std::filesystem::is_regular_file(ref, ec)) {
      h.str("<missing>");  // cook() will report it; a file appearing later changes the key
      continue;
    }
    const std::vector<std::uint8_t> data = readFileBytes(ref);
    h.u64(data.size()).bytes(data.data(), data.size());
  }
  h.u64(options.decodeImages ? 1 : 0).u64(options.subdivision.size());
  for (const auto& [node, s] : options.subdivision) h.str(node).u64(std::uint64_t(s.scheme)).u64(s.levels);
  return h.hex();
}

CookedAsset loadOrCook(const std::filesystem::path& source, const std::filesystem::path& cacheDir,
                       const CookOptions& options) {
  const std::filesystem::path entry = cacheDir / (cacheKey(source, options) + ".bcook");
  std::error_code ec;
  if (std::filesystem::exists(entry, ec)) {
    try {
      return readCooked(entry);
    } catch (const InputError& e) {
      log::warn(std::string("cooked cache entry rejected, re-cooking: ") + e.what());
    }
  }
  CookedAsset asset = cook(source, options);
  writeCooked(asset, entry);
  return asset;
}

std::vector<CookedAsset> loadOrCookAll(const std::vector<std::filesystem::path>& sources,
                                       const std::filesystem::path& cacheDir, const CookOptions& options) {
  std::vector<CookedAsset> out;
  out.reserve(sources.size());
  Progress progress("cook", sources.size());
  for (const auto& s : sources) {
    out.push_back(loadOrCook(s, cacheDir, options));
    progress.advance();
  }
  progress.finish();
  return out;
}

}  // namespace bounce::asset
