// Fuzz target: bytes → cooked-format reader. Half of the inputs get their checksum fixed up first
// (chosen by the first byte), so mutations reach the section parsers and validate() instead of
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
  std::vector<std::uint8_t> bytes(data, data + size);
  if (size > 8 && (data[size / 2] & 1) == 0) {
    const std::uint64_t sum = bounce::hashBytes(std::span(bytes.data(), size - 8));
    std::memcpy(bytes.data() + size - 8, &sum, 8);
  }
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
