#pragma once
// The `bounce` subcommands. Each returns the process exit code (0 success); bad input is thrown
// as InputError (exit 2) and failures as InternalError (exit 1), see main.cpp.
#include <string>
#include <vector>

#include "game/cli.hpp"

namespace bounce::game {

const std::vector<cli::CommandSpec>& commandSpecs();

int runPlay(const cli::Args& args);
int runCapture(const cli::Args& args);
int runProfile(const cli::Args& args);
int runGraph(const cli::Args& args);
int runCook(const cli::Args& args);
int runDemo(const cli::Args& args);
int runReference(const cli::Args& args);
int runExport(const cli::Args& args);
int runBench(const cli::Args& args);
int runBenchDnrt(const cli::Args& args);  // `bench dnrt` (bench_dnrt.hpp)
int runBake(const cli::Args& args);
int runCache(const cli::Args& args);  // `cache --stats|--prune` (cmd_cache.cpp)
int runAccuracy(const cli::Args& args);
int runVlmMake(const cli::Args& args);
int runLevel(const cli::Args& args);  // cmd_level.cpp

// The Vulkan context for --device (or BOUNCE_DEVICE), headless unless `windowed`.
struct GpuOptions {
  std::string device;
  bool windowed = false;
};
GpuOptions gpuOptions(const cli::Args& args);

// The process exit code once `command` returned `code`: 1 when any Context of the process counted
// a Vulkan validation error (gpu::validationErrorsTotal()), so every run with validation on — the
// tests start `bounce` as a child process with BOUNCE_VALIDATION=1 — fails on one; else `code`.
// Prints one line `bounce COMMAND: N Vulkan validation error(s), printed above` unless the command
// already failed with exit 1.
int exitCodeAfterCommand(const std::string& command, int code);

}  // namespace bounce::game
