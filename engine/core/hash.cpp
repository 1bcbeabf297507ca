#include "engine/core/hash.hpp"

namespace bounce {

Hasher& Hasher::bytes(const void* data, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    state_ ^= p[i];
    state_ *= 0x100000001b3ull;
  }
  return *this;
}

std::uint64_t Hasher::digest() const {
  std::uint64_t z = state_ + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

std::string Hasher::hex() const { return toHex(digest()); }

std::uint64_t hashBytes(std::span<const std::uint8_t> data) { return Hasher().bytes(data.data(), data.size()).digest(); }

std::string toHex(std::uint64_t v) {
  static const char* digits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, v >>= 4) s[static_cast<std::size_t>(i)] = digits[v & 15];
  return s;
}

}  // namespace bounce
