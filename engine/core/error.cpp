#include "engine/core/error.hpp"

namespace bounce {

std::string formatInputError(const std::string& file, const std::string& where, const std::string& what,
                             const std::string& expected) {
  std::string s = file.empty() ? std::string("<input>") : file;
  if (!where.empty()) s += ": " + where;
  s += ": " + what;
  if (!expected.empty()) s += " (expected " + expected + ")";
  // One line, always: a newline inside a user-facing error would split it in logs.
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

void throwInputError(const std::string& file, const std::string& where, const std::string& what,
                     const std::string& expected) {
  throw InputError(formatInputError(file, where, what, expected));
}

}  // namespace bounce
