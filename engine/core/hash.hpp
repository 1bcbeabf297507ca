#pragma once
// 64-bit content hashing for caches (cooked assets, bakes, references). Not cryptographic:
// a cache key only has to change when its inputs change. FNV-1a over bytes, finished with a
// splitmix64 avalanche so that nearby inputs give distant keys.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace bounce {

class Hasher {
 public:
  Hasher& bytes(const void* data, std::size_t size);
  Hasher& str(std::string_view s) {
    u64(s.size());
    return bytes(s.data(), s.size());
  }
  Hasher& u64(std::uint64_t v) { return bytes(&v, sizeof v); }
  template <class T>
    requires std::is_trivially_copyable_v<T>
  Hasher& pod(const T& v) {
    return bytes(&v, sizeof v);
  }
  std::uint64_t digest() const;
  std::string hex() const;  // 16 lowercase hex digits

 private:
  std::uint64_t state_ = 0xcbf29ce484222325ull;
};

std::uint64_t hashBytes(std::span<const std::uint8_t> data);
std::string toHex(std::uint64_t v);

}  // namespace bounce
