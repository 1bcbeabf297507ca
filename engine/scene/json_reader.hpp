#pragma once
// Strict, pointer-aware JSON reading for level and capture files (and later technique
// components). Every failure is an InputError of one line:
//   "file: /json/pointer: what is wrong (expected …)"
// with an RFC 6901 pointer to the offending value ("" for the document root, which
// formatInputError omits).
//
// parse() adds what nlohmann::json does not check on its own: duplicate object keys, nesting
// deeper than kMaxDepth (hostile input), numbers that overflow a double (reported at their
// pointer), and it turns syntax errors into "byte N (line L, column C)" messages.
#include <cmath>  // HUGE_VAL
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
// Declarations only (nlohmann::json as a reference/pointer type): the full json.hpp (~130k lines
// preprocessed, ~2 s of gcc per TU) is included by the .cpp files that read JSON, not by every TU
// that reaches this header through game/session.hpp or engine/gi/participants.hpp (CI time).
#include <nlohmann/json_fwd.hpp>

namespace bounce::scene::json {

inline constexpr int kMaxDepth = 64;                            // levels nest ~6 deep
inline constexpr std::size_t kMaxStringBytes = 4096;           // ids, names, paths
inline constexpr std::uintmax_t kMaxFileBytes = 64u << 20;      // 64 MiB: far above any level

nlohmann::json parse(std::string_view text, const std::string& file);
// Reads (size-checked) and parses a file; `file` in messages is path.string().
nlohmann::json parseFile(const std::filesystem::path& path);

// User text quoted in messages (keys, ids) is cut to this many bytes, so that a hostile
// 10 MB key gives a short error line.
inline constexpr std::size_t kMaxTokenInMessage = 64;

// "~" -> "~0", "/" -> "~1" (RFC 6901), control characters shown as '?'; a token longer than
// kMaxTokenInMessage is cut and marked "..." (pointers here are for people to read).
std::string escapePointerToken(std::string_view token);
// "\"text\"", cut like a pointer token, control characters shown as '?'.
std::string inQuotes(std::string_view s);
// The text with control characters shown as '?', not cut (paths built from user text).
std::string printable(std::string_view s);

// A closed/open/half-open interval of allowed numbers, and its wording for messages.
struct Range {
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  bool loOpen = false, hiOpen = false;

  static Range any() { return {}; }
  static Range atLeast(double v) { return {v, HUGE_VAL, false, false}; }
  static Range greaterThan(double v) { return {v, HUGE_VAL, true, false}; }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range open(double a, double b) { return {a, b, true, true}; }
  static Range closedOpen(double a, double b) { return {a, b, false, true}; }
  static Range openClosed(double a, double b) { return {a, b, true, false}; }

  bool contains(double v) const;
  // "a number", "a number >= 0", "a number > 0", "a number in (0, 180)".
  std::string describe(std::string_view noun = "a number") const;
};

// Shortest round-trip text of a number ("0.5", "-1", "1e+39").
std::string formatNumber(double v);

class Object;

// A value at a known pointer in a known file.
class Node {
 public:
  Node(const nlohmann::json& value, std::string pointer, const std::string& file)
      : value_(&value), pointer_(std::move(pointer)), file_(&file) {}

  const nlohmann::json& raw() const { return *value_; }
  const std::string& pointer() const { return pointer_; }
  const std::string& file() const { return *file_; }
  [[noreturn]] void fail(const std::string& what, const std::string& expected) const;
  // "wrong type: string (expected …)".
  [[noreturn]] void wrongType(const std::string& expected) const;

  bool boolean() const;
  // A finite number within `range` that also fits a 32-bit float.
  float real(const Range& range = Range::any()) const;
  double real64(const Range& range = Range::any()) const;
  std::int64_t integer(std::int64_t lo, std::int64_t hi) const;
  // A non-empty string of at most maxBytes.
  std::string string(std::size_t maxBytes = kMaxStringBytes) const;
  // [x, y, z], each in `each`.
  glm::vec3 vec3(const Range& each = Range::any()) const;
  // A non-zero [x, y, z] normalised to unit length.
  glm::vec3 direction() const;
  // An array with minSize..maxSize elements; `expected` words it ("2 or more times").
  std::vector<Node> array(std::size_t minSize, std::size_t maxSize, const std::string& expected) const;
  // An object whose keys are all in `allowed` (else "unknown key").
  Object object(std::initializer_list<std::string_view> allowed) const;
  Object object(const std::vector<std::string_view>& allowed) const;

  Node child(std::string_view key) const;
  Node element(std::size_t index) const;

 private:
  const nlohmann::json* value_;
  std::string pointer_;
  const std::string* file_;
};

class Object {
 public:
  explicit Object(Node node) : node_(std::move(node)) {}
  const Node& node() const { return node_; }
  bool has(std::string_view key) const;
  std::optional<Node> optional(std::string_view key) const;
  // `expected` words the value, for the "missing required key" message.
  Node required(std::string_view key, const std::string& expected) const;

 private:
  Node node_;
};

// "array", "string", … as a reader would say it.
const char* typeName(const nlohmann::json& v);

}  // namespace bounce::scene::json
