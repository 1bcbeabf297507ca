#pragma once
// The engine's own binary files (cooked assets, DNRT and RTF fields, SL sphere sets): raw
// little-endian values back to back, read with bounds checks that turn every short or bad file
// into one InputError line "file: where: what (expected …)" (engine/core/error.hpp).
//
// The formats differ in two things only, the reader's parameters:
//  - `complete`: what a truncated file was expected to be ("a complete DNRT field file");
//  - `offset`: whether `where` carries the read position, as "where (byte N)" (SL), "where byte N"
//    (a cooked section) or not at all (DNRT, RTF: their `where` names the field).
// N is the read position when the check fails: before a read that runs out of bytes, after a
// value that was read and then refused. Tests pin each format's messages byte for byte
// (tests/unit/core/binary_io_messages_test.cpp).
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "engine/core/error.hpp"

namespace bounce {

class BinaryWriter {
 public:
  std::vector<std::uint8_t> bytes;
  void raw(const void* p, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(p);
    bytes.insert(bytes.end(), b, b + n);
  }
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void put(const T& v) { raw(&v, sizeof v); }
  // The elements only (no count): the reader knows how many from what it read before.
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void putAll(const std::vector<T>& v) { raw(v.data(), v.size() * sizeof(T)); }
};

enum class ByteOffset {
  None,           // "where"
  Parenthesised,  // "where (byte N)"
  Suffix,         // "where byte N"
};

class BinaryReader {
 public:
  BinaryReader(std::span<const std::uint8_t> bytes, std::string file, std::string complete,
               ByteOffset offset = ByteOffset::None)
      : bytes_(bytes), file_(std::move(file)), complete_(std::move(complete)), offset_(offset) {}

  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  bool atEnd() const { return pos_ == bytes_.size(); }

  [[noreturn]] void fail(std::string_view where, const std::string& what, const std::string& expected) const {
    std::string w(where);
    if (offset_ == ByteOffset::Parenthesised) w += " (byte " + std::to_string(pos_) + ")";
    if (offset_ == ByteOffset::Suffix) w += " byte " + std::to_string(pos_);
    throwInputError(file_, w, what, expected);
  }

  // n bytes into p; a file that ends first fails as "where: truncated (expected <complete>)".
  void raw(void* p, std::size_t n, std::string_view where) {
    if (n > remaining()) fail(where, "truncated", complete_);
    if (n == 0) return;  // an empty vector's data() may be null, and memcpy(null, …, 0) is UB
    std::memcpy(p, bytes_.data() + pos_, n);
    pos_ += n;
  }
  template <class T>
    requires std::is_trivially_copyable_v<T>
  T get(std::string_view where) {
    T v;
    raw(&v, sizeof v, where);
    return v;
  }
  // n elements; n is checked against the bytes left before anything is allocated, so a corrupt
  // count cannot allocate wildly.
  template <class T>
    requires std::is_trivially_copyable_v<T>
  std::vector<T> getAll(std::size_t n, std::string_view where) {
    if (n > remaining() / sizeof(T)) fail(where, "truncated", complete_);
    std::vector<T> v(n);
    raw(v.data(), n * sizeof(T), where);
    return v;
  }
  // The next n bytes, in place.
  std::span<const std::uint8_t> take(std::size_t n, std::string_view where) {
    if (n > remaining()) fail(where, "truncated", complete_);
    auto s = bytes_.subspan(pos_, n);
    pos_ += n;
    return s;
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::string file_, complete_;
  ByteOffset offset_;
  std::size_t pos_ = 0;
};

// The header the GI caches share: 8 magic bytes, then a u32 version.
inline void writeHeader(BinaryWriter& w, const char (&magic)[8], std::uint32_t version) {
  w.raw(magic, 8);
  w.put(version);
}

// Reads and checks that header. A wrong magic byte fails at once, as
// "header: <notA> (expected magic <MAGIC>)" (the magic up to its first NUL); a wrong version as
// "version: version V (expected version K)".
inline void readHeader(BinaryReader& r, const char (&magic)[8], std::uint32_t version, const std::string& notA) {
  for (char c : magic)
    if (r.get<char>("header") != c) {
      const std::string_view m(magic, 8);
      r.fail("header", notA, "magic " + std::string(m.substr(0, m.find('\0'))));
    }
  if (const auto v = r.get<std::uint32_t>("version"); v != version)
    r.fail("version", "version " + std::to_string(v), "version " + std::to_string(version));
}

}  // namespace bounce
