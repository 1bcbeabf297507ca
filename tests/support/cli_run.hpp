#pragma once
// Running the `bounce` executable from a test as a user would: one shell command, stdout and stderr
// captured in files beside the test's output, the exit code kept (-1 when it did not exit). One
// helper for every CLI test (exit codes, messages, bake jobs, README examples, the glTF viewer).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace bounce::testcli {

inline std::string readText(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string line; std::getline(s, line);) out.push_back(line);
  return out;
}

// A POSIX-shell single-quoted word: safe for any path or argument.
inline std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// What one command left: its exit code (-1 if it did not exit) and its output.
struct Outcome {
  int code = -1;
  std::string out, err;
};

// Runs `cmd` with /bin/sh, stdout into outFile and stderr into errFile, and reads both back.
inline Outcome runShell(const std::string& cmd, const std::filesystem::path& outFile,
                        const std::filesystem::path& errFile) {
  const int status = std::system((cmd + " >" + quote(outFile.string()) + " 2>" + quote(errFile.string())).c_str());
  Outcome r;
  if (status != -1 && WIFEXITED(status)) r.code = WEXITSTATUS(status);
  r.out = readText(outFile);
  r.err = readText(errFile);
  return r;
}

// `bounce ARGS` (BOUNCE_EXE, quoted), with an optional environment prefix ("VAR=value ").
inline std::string bounceCommand(const std::vector<std::string>& args, const std::string& envPrefix = {}) {
  std::string cmd = envPrefix + quote(BOUNCE_EXE);
  for (const auto& a : args) {  // append, not " " + quote(a): GCC 12 -O3 warns (-Wstringop-overflow) on a
    cmd += ' ';                   // literal prepended to a temporary, a false positive in its insert path
    cmd += quote(a);
  }
  return cmd;
}

// `bounce ARGS` with its output in dir/stdout.txt and dir/stderr.txt (dir is created).
inline Outcome runBounce(const std::vector<std::string>& args, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  return runShell(bounceCommand(args), dir / "stdout.txt", dir / "stderr.txt");
}

}  // namespace bounce::testcli
