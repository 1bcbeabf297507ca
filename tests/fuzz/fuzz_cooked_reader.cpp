// Fuzz target: bytes → cooked-format reader. Half of the inputs get their checksum fixed up first
// (withChecksumFixedUp), so mutations reach the section parsers and validate() instead of
// stopping at the checksum.
#include "engine/asset/cook.hpp"
#include "engine/asset/cooked_format.hpp"
#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "tests/fuzz/fuzz_target.hpp"

#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  bounce::log::setLevel(bounce::log::Level::Quiet);
  const std::vector<std::uint8_t> bytes = withChecksumFixedUp(data, size);
  try {
    const bounce::asset::CookedAsset a = bounce::asset::parseCooked(bytes, "fuzz.bcook");
    // Whatever parses must be consistent enough to write back byte for byte.
    if (bounce::asset::serializeCooked(a) != bytes) throw std::logic_error("parsed cooked file does not round-trip");
  } catch (const bounce::InputError&) {
    // expected for most inputs
  }
  return 0;
}

std::vector<std::vector<std::uint8_t>> fuzzSeeds(const std::vector<std::string>& assetPaths) {
  bounce::log::setLevel(bounce::log::Level::Quiet);
  std::vector<std::vector<std::uint8_t>> out;
  for (const auto& p : assetPaths) {
    bounce::asset::CookOptions o;
    o.decodeImages = false;  // keeps seeds small; the texture section still has its headers
    out.push_back(bounce::asset::serializeCooked(bounce::asset::cook(p, o)));
  }
  return out;
}
