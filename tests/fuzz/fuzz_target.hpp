#pragma once
// The interface shared by the fuzz targets and standalone_driver.cpp.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

// libFuzzer's entry point: must return 0 for every input; an InputError is an expected outcome,
// any other exception escapes and counts as a failure.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

// Seed inputs for the standalone driver, made from real asset files (absolute paths).
std::vector<std::vector<std::uint8_t>> fuzzSeeds(const std::vector<std::string>& assetPaths);
