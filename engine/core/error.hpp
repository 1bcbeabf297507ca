#pragma once
// Errors that reach the user. Two kinds, two exit codes (see game/main.cpp):
//  - InputError (exit 2): the user's file or argument is wrong. Its message is one line,
//    "file: where: what is wrong (expected …)", where `where` is a JSON pointer, a byte
//    offset, an accessor index — whatever lets the user find the place.
//  - InternalError (exit 1): a bug or an environment failure (no Vulkan device, disk full).
#include <stdexcept>
#include <string>

namespace bounce {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InternalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Formats "file: where: what (expected expected)"; parts left empty are omitted.
std::string formatInputError(const std::string& file, const std::string& where, const std::string& what,
                             const std::string& expected = {});

[[noreturn]] void throwInputError(const std::string& file, const std::string& where, const std::string& what,
                                  const std::string& expected = {});

}  // namespace bounce
