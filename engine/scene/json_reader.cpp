#include "engine/core/suggest.hpp"
#include "engine/scene/json_reader.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <set>

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"

namespace bounce::scene::json {

namespace {

// Follows nlohmann's parse callbacks to know the pointer of the value being parsed, rejects
// duplicate keys and deep nesting as they are met.
class Tracker {
 public:
  explicit Tracker(const std::string& file) : file_(file) {}

  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        if (int(frames_.size()) >= kMaxDepth)
          throwInputError(file_, pointer(), "JSON nested deeper than " + std::to_string(kMaxDepth) + " levels",
                          "at most " + std::to_string(kMaxDepth));
        frames_.push_back(Frame{event == E::array_start, 0, {}, {}});
        break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throwInputError(file_, pointer(), "duplicate key " + inQuotes(f.key), "each key at most once per object");
        break;
      }
      case E::value:
        advance();
        break;
      case E::object_end:
      case E::array_end:
        frames_.pop_back();
        advance();
        break;
    }
    return true;
  }

  // Pointer of the value being parsed now.
  std::string pointer() const {
    std::string p;
    for (const Frame& f : frames_) {
      p += '/';
      p += f.isArray ? std::to_string(f.index) : escapePointerToken(f.key);
    }
    return p;
  }

 private:
  struct Frame {
    bool isArray;
    std::size_t index;
    std::string key;
    std::set<std::string> keys;
  };
  void advance() {
    if (!frames_.empty() && frames_.back().isArray) ++frames_.back().index;
  }
  const std::string& file_;
  std::vector<Frame> frames_;
};

// nlohmann's message minus its "[json.exception.…] parse error at line L, column C: " prefix
// and its "; last read: '…'" echo (which may hold the invalid bytes themselves).
std::string cleanParseMessage(const std::string& m) {
  std::string s = m;
  if (s.rfind("[json.exception", 0) == 0)
    if (auto c = s.find("] "); c != std::string::npos) s = s.substr(c + 2);
  if (s.rfind("parse error", 0) == 0)
    if (auto c = s.find(": "); c != std::string::npos) s = s.substr(c + 2);
  if (auto lr = s.find("; last read"); lr != std::string::npos) s = s.substr(0, lr);
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) >= 0x7f) ch = '?';
  return s;
}

// "line L, column C" extracted from nlohmann's message, or "".
std::string lineColumn(const std::string& m) {
  const auto at = m.find("at line ");
  if (at == std::string::npos) return {};
  const auto colon = m.find(':', at);
  return m.substr(at + 3, colon == std::string::npos ? std::string::npos : colon - at - 3);
}

}  // namespace

nlohmann::json parse(std::string_view text, const std::string& file) {
  Tracker tracker(file);
  try {
    return nlohmann::json::parse(text.begin(), text.end(), std::ref(tracker));
  } catch (const nlohmann::json::parse_error& e) {
    const std::string lc = lineColumn(e.what());
    throwInputError(file, "byte " + std::to_string(e.byte) + (lc.empty() ? "" : " (" + lc + ")"),
                    "malformed JSON: " + cleanParseMessage(e.what()), "valid JSON");
  } catch (const nlohmann::json::out_of_range& e) {
    // Number overflow (id 406): "1e999" does not fit a double.
    throwInputError(file, tracker.pointer(), cleanParseMessage(e.what()), "a finite number");
  }
}

nlohmann::json parseFile(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxFileBytes)
    throwInputError(path.string(), "", "file is " + std::to_string(size) + " bytes",
                    "at most " + std::to_string(kMaxFileBytes) + " bytes");
  return parse(readFileText(path), path.string());
}

std::string escapePointerToken(std::string_view token) {
  std::string s;
  const bool shorten = token.size() > kMaxTokenInMessage;
  if (shorten) token = token.substr(0, kMaxTokenInMessage);
  for (char c : token) {
    if (c == '~')
      s += "~0";
    else if (c == '/')
      s += "~1";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      s += '?';  // as inQuotes: a raw newline would break the one-line message (found by fuzz_level)
    else
      s += c;
  }
  return shorten ? s + "..." : s;
}

std::string inQuotes(std::string_view s) {
  std::string out = "\"";
  for (char c : s.substr(0, kMaxTokenInMessage))
    out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  return out + (s.size() > kMaxTokenInMessage ? "...\"" : "\"");
}

std::string printable(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return out;
}

bool Range::contains(double v) const {
  const bool aboveLo = loOpen ? v > lo : v >= lo;
  const bool belowHi = hiOpen ? v < hi : v <= hi;
  return aboveLo && belowHi;
}

std::string Range::describe(std::string_view noun) const {
  const std::string n(noun);
  const bool hasLo = std::isfinite(lo), hasHi = std::isfinite(hi);
  if (!hasLo && !hasHi) return n;
  if (hasLo && !hasHi) return n + (loOpen ? " > " : " >= ") + formatNumber(lo);
  if (!hasLo) return n + (hiOpen ? " < " : " <= ") + formatNumber(hi);
  return n + " in " + (loOpen ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) + (hiOpen ? ")" : "]");
}

std::string formatNumber(double v) {
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

const char* typeName(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "object";
    case nlohmann::json::value_t::array: return "array";
    case nlohmann::json::value_t::string: return "string";
    case nlohmann::json::value_t::boolean: return "boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned: return "integer";
    case nlohmann::json::value_t::number_float: return "number";
    default: return "binary";
  }
}

void Node::fail(const std::string& what, const std::string& expected) const {
  throwInputError(*file_, pointer_, what, expected);
}

void Node::wrongType(const std::string& expected) const { fail(std::string("wrong type: ") + typeName(*value_), expected); }

bool Node::boolean() const {
  if (!value_->is_boolean()) wrongType("true or false");
  return value_->get<bool>();
}

double Node::real64(const Range& range) const {
  if (!value_->is_number()) wrongType(range.describe());
  const double v = value_->get<double>();
  // nlohmann rejects literal overflow, but keep the check: values can come from elsewhere.
  if (!std::isfinite(v)) fail("number is not finite", "a finite number");
  if (!range.contains(v)) fail(formatNumber(v) + " is out of range", range.describe());
  return v;
}

float Node::real(const Range& range) const {
  const double v = real64(range);
  if (std::abs(v) > double(std::numeric_limits<float>::max()))
    fail(formatNumber(v) + " does not fit a 32-bit float", "a number of magnitude <= 3.4e38");
  return float(v);
}

std::int64_t Node::integer(std::int64_t lo, std::int64_t hi) const {
  const std::string expected = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (value_->is_number_unsigned()) {
    const auto u = value_->get<std::uint64_t>();
    if ((lo > 0 && u < std::uint64_t(lo)) || (hi < 0 || u > std::uint64_t(hi)))
      fail(std::to_string(u) + " is out of range", expected);
    return std::int64_t(u);
  }
  if (!value_->is_number_integer()) wrongType(expected);
  const auto v = value_->get<std::int64_t>();
  if (v < lo || v > hi) fail(std::to_string(v) + " is out of range", expected);
  return v;
}

std::string Node::string(std::size_t maxBytes) const {
  if (!value_->is_string()) wrongType("a string");
  const auto& s = value_->get_ref<const std::string&>();
  if (s.empty()) fail("empty string", "a non-empty string");
  if (s.size() > maxBytes)
    fail("string of " + std::to_string(s.size()) + " bytes is too long", "at most " + std::to_string(maxBytes) + " bytes");
  return s;
}

glm::vec3 Node::vec3(const Range& each) const {
  const auto items = array(3, 3, "3 numbers [x, y, z]");
  return {items[0].real(each), items[1].real(each), items[2].real(each)};
}

glm::vec3 Node::direction() const {
  const glm::vec3 v = vec3();
  const double len = std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
  // Shorter than this, the direction is numerically meaningless after normalising in float.
  constexpr double kMinLength = 1e-6;
  if (!(len >= kMinLength)) fail("zero-length direction", "a non-zero [x, y, z]");
  return glm::vec3(double(v.x) / len, double(v.y) / len, double(v.z) / len);
}

std::vector<Node> Node::array(std::size_t minSize, std::size_t maxSize, const std::string& expected) const {
  if (!value_->is_array()) wrongType("an array of " + expected);
  const std::size_t n = value_->size();
  if (n < minSize || n > maxSize)
    fail(std::to_string(n) + (n == 1 ? " element" : " elements"), expected);
  std::vector<Node> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) out.push_back(element(i));
  return out;
}

Object Node::object(std::initializer_list<std::string_view> allowed) const {
  return object(std::vector<std::string_view>(allowed));
}

Object Node::object(const std::vector<std::string_view>& allowed) const {
  if (!value_->is_object()) wrongType("an object");
  for (const auto& [key, value] : value_->items()) {
    bool known = false;
    for (auto a : allowed) known = known || a == key;
    if (!known) {
      std::string list;
      std::vector<std::string> names;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a), names.emplace_back(a);
      child(key).fail("unknown key " + inQuotes(key) + didYouMean(key, names), "one of: " + list);
    }
  }
  return Object(*this);
}

Node Node::child(std::string_view key) const {
  return Node((*value_)[std::string(key)], pointer_ + "/" + escapePointerToken(key), *file_);
}

Node Node::element(std::size_t index) const {
  return Node((*value_)[index], pointer_ + "/" + std::to_string(index), *file_);
}

bool Object::has(std::string_view key) const { return node_.raw().contains(key); }

std::optional<Node> Object::optional(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return node_.child(key);
}

Node Object::required(std::string_view key, const std::string& expected) const {
  if (!has(key)) node_.fail("missing required key \"" + std::string(key) + "\"", expected);
  return node_.child(key);
}

}  // namespace bounce::scene::json
