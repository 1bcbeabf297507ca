#pragma once
// Command-line parsing for `bounce <command> [options] [arguments]`. Each command declares its
// options; the parser checks them and produces one-line errors ("bounce profile: --frames: …
// (expected a positive integer)"), which main() turns into exit code 2.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bounce::cli {

struct OptionSpec {
  std::string name;        // "--frames"
  std::string valueName;   // "N" — empty for a flag
  std::string help;
};

struct CommandSpec {
  std::string name;        // "profile"
  std::string usage;       // "LEVEL [--frames N] ..."
  std::string summary;     // one line for `bounce --help`
  std::vector<OptionSpec> options;
  std::size_t minPositional = 0;
  std::size_t maxPositional = 0;  // SIZE_MAX for "any number"
};

class Args {
 public:
  std::string command;
  std::vector<std::string> positional;
  std::map<std::string, std::string> values;  // option → value ("" for flags)

  bool has(const std::string& option) const { return values.count(option) != 0; }
  std::string str(const std::string& option, const std::string& fallback = {}) const;
  // Typed getters validate and throw InputError naming the command and option.
  int positiveInt(const std::string& option, int fallback) const;
  int nonNegativeInt(const std::string& option, int fallback) const;  // 0 allowed (e.g. "none")
  // "WxH" with 1 ≤ W, H ≤ 16384.
  std::optional<std::pair<int, int>> resolution(const std::string& option) const;
  // Comma-separated list; empty items are an error.
  std::optional<std::vector<std::string>> list(const std::string& option) const;
};

// Parses argv[first..] against the spec. Throws InputError on unknown options, missing values or a
// wrong number of positional arguments. "--help" is always accepted (Args::has("--help")).
Args parse(const CommandSpec& spec, int argc, const char* const* argv, int first);

std::string helpText(const CommandSpec& spec);
std::string overviewText(const std::vector<CommandSpec>& specs);

}  // namespace bounce::cli
