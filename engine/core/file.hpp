#pragma once
// File helpers. Reads throw InputError naming the file; writes are atomic (temp + rename)
// so that an interrupted cook or bake never leaves a half-written cache entry behind.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace bounce {

std::vector<std::uint8_t> readFileBytes(const std::filesystem::path& path);
std::string readFileText(const std::filesystem::path& path);

// Writes to "<path>.tmp-<pid>" then renames over `path`. Creates parent folders.
void writeFileAtomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void writeFileAtomic(const std::filesystem::path& path, const std::string& text);

}  // namespace bounce
