#pragma once
// The interface shared by the fuzz targets and standalone_driver.cpp.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "engine/core/hash.hpp"

// libFuzzer's entry point: must return 0 for every input; an InputError is an expected outcome,
// any other exception escapes and counts as a failure.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

// Seed inputs for the standalone driver, made from real asset files (absolute paths).
std::vector<std::vector<std::uint8_t>> fuzzSeeds(const std::vector<std::string>& assetPaths);

// The input as bytes, for readers whose files end in an 8-byte hashBytes checksum of the rest: half
// of the inputs (chosen by a middle byte) get that checksum fixed up, so mutations reach the
// parsers behind it instead of stopping at the checksum.
inline std::vector<std::uint8_t> withChecksumFixedUp(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  if (size > 8 && (data[size / 2] & 1) == 0) {
    const std::uint64_t sum = bounce::hashBytes(std::span(bytes.data(), size - 8));
    std::memcpy(bytes.data() + size - 8, &sum, 8);
  }
  return bytes;
}
