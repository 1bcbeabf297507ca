#include "game/cli.hpp"

#include <climits>
#include <cstdint>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/core/suggest.hpp"

namespace bounce::cli {
namespace {

[[noreturn]] void fail(const std::string& command, const std::string& where, const std::string& what,
                       const std::string& expected = {}) {
  throwInputError("bounce " + command, where, what, expected);
}

const OptionSpec* find(const CommandSpec& spec, const std::string& name) {
  for (const auto& o : spec.options)
    if (o.name == name) return &o;
  return nullptr;
}

}  // namespace

std::string Args::str(const std::string& option, const std::string& fallback) const {
  auto it = values.find(option);
  return it == values.end() ? fallback : it->second;
}

namespace {
// The one integer reader behind positiveInt and nonNegativeInt: the whole value must be a decimal
// integer in [lo, INT_MAX], else one line naming the command and option.
int intAtLeast(const Args& a, const std::string& option, int fallback, int lo, const char* expected) {
  auto it = a.values.find(option);
  if (it == a.values.end()) return fallback;
  const std::string& v = it->second;
  std::size_t used = 0;
  long long n = 0;
  try {
    n = std::stoll(v, &used);
  } catch (...) {
    used = 0;
  }
  if (used != v.size() || v.empty() || n < lo || n > INT_MAX)
    fail(a.command, option, "'" + v + "' is not a valid count", expected);
  return static_cast<int>(n);
}
}  // namespace

int Args::positiveInt(const std::string& option, int fallback) const {
  return intAtLeast(*this, option, fallback, 1, "a positive integer");
}

int Args::nonNegativeInt(const std::string& option, int fallback) const {
  return intAtLeast(*this, option, fallback, 0, "a non-negative integer");
}

std::optional<std::pair<int, int>> Args::resolution(const std::string& option) const {
  auto it = values.find(option);
  if (it == values.end()) return std::nullopt;
  const std::string& v = it->second;
  auto x = v.find('x');
  auto parse = [&](const std::string& s) -> int {
    if (s.empty() || s.size() > 5 || s.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stoi(s);
  };
  int w = x == std::string::npos ? -1 : parse(v.substr(0, x));
  int h = x == std::string::npos ? -1 : parse(v.substr(x + 1));
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    fail(command, option, "'" + v + "' is not a resolution", "WIDTHxHEIGHT, each 1..16384");
  return std::pair{w, h};
}

std::optional<std::vector<std::string>> Args::list(const std::string& option) const {
  auto it = values.find(option);
  if (it == values.end()) return std::nullopt;
  std::vector<std::string> items;
  std::stringstream ss(it->second);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) fail(command, option, "empty item in '" + it->second + "'", "a comma-separated list");
    items.push_back(item);
  }
  if (items.empty()) fail(command, option, "empty list", "a comma-separated list");
  return items;
}

Args parse(const CommandSpec& spec, int argc, const char* const* argv, int first) {
  Args args;
  args.command = spec.name;
  for (int i = first; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      args.values["--help"] = "";
      continue;
    }
    if (a.rfind("--", 0) == 0) {
      std::string value;
      bool inlineValue = false;
      if (auto eq = a.find('='); eq != std::string::npos) {
        value = a.substr(eq + 1);
        a = a.substr(0, eq);
        inlineValue = true;
      }
      const OptionSpec* o = find(spec, a);
      if (!o) {
        std::vector<std::string> names{"--help"};
        for (const auto& option : spec.options) names.push_back(option.name);
        fail(spec.name, a, "unknown option" + didYouMean(a, names), "one of the options in 'bounce " + spec.name + " --help'");
      }
      if (!o->valueName.empty() && !inlineValue) {
        if (i + 1 >= argc) fail(spec.name, a, "missing value", o->valueName);
        value = argv[++i];
      } else if (o->valueName.empty() && inlineValue) {
        fail(spec.name, a, "takes no value");
      }
      args.values[a] = value;
      continue;
    }
    args.positional.push_back(a);
  }
  if (args.has("--help")) return args;
  if (args.positional.size() < spec.minPositional || args.positional.size() > spec.maxPositional)
    fail(spec.name, "arguments", "got " + std::to_string(args.positional.size()) + " argument(s)",
         "usage: bounce " + spec.name + " " + spec.usage);
  return args;
}

std::string helpText(const CommandSpec& spec) {
  std::ostringstream out;
  out << "usage: bounce " << spec.name << " " << spec.usage << "\n\n" << spec.summary << "\n";
  if (!spec.options.empty()) out << "\noptions:\n";
  for (const auto& o : spec.options) {
    std::string left = o.name + (o.valueName.empty() ? "" : " " + o.valueName);
    out << "  " << left << std::string(left.size() < 26 ? 26 - left.size() : 1, ' ') << o.help << "\n";
  }
  out << "  --help                    show this help\n";
  return out.str();
}

std::string overviewText(const std::vector<CommandSpec>& specs) {
  std::ostringstream out;
  out << "usage: bounce <command> [options]\n\nBounce: real-time indirect light from dynamic objects.\n\ncommands:\n";
  for (const auto& s : specs)
    out << "  " << s.name << std::string(s.name.size() < 12 ? 12 - s.name.size() : 1, ' ') << s.summary << "\n";
  out << "\n'bounce <command> --help' shows a command's options. Exit codes: 0 success, 2 bad input, 1 internal error.\n";
  return out.str();
}

}  // namespace bounce::cli
