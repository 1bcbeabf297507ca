// bounce: the Bounce executable. `bounce --help` lists the commands; exit codes: 0 success,
// 2 bad input (one line naming the file, the place and what was expected), 1 internal error —
// also when a Vulkan validation error was reported during the command (game::exitCodeAfterCommand).
#include <cstdio>
#include <cstring>
#include <string>

#include "engine/core/error.hpp"
#include "game/commands.hpp"

using namespace bounce;

int main(int argc, char** argv) {
  const auto& specs = game::commandSpecs();
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    std::fputs(cli::overviewText(specs).c_str(), stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  try {
    for (const auto& spec : specs) {
      if (spec.name != name) continue;
      cli::Args args = cli::parse(spec, argc, argv, 2);
      if (args.has("--help")) {
        std::fputs(cli::helpText(spec).c_str(), stdout);
        return 0;
      }
      if (name == "play") return game::exitCodeAfterCommand(name, game::runPlay(args));
      if (name == "capture") return game::exitCodeAfterCommand(name, game::runCapture(args));
      if (name == "profile") return game::exitCodeAfterCommand(name, game::runProfile(args));
      if (name == "graph") return game::exitCodeAfterCommand(name, game::runGraph(args));
      if (name == "cook") return game::exitCodeAfterCommand(name, game::runCook(args));
      if (name == "demo") return game::exitCodeAfterCommand(name, game::runDemo(args));
      if (name == "reference") return game::exitCodeAfterCommand(name, game::runReference(args));
      if (name == "export") return game::exitCodeAfterCommand(name, game::runExport(args));
      if (name == "bench") return game::exitCodeAfterCommand(name, game::runBench(args));
      if (name == "bake") return game::exitCodeAfterCommand(name, game::runBake(args));
      if (name == "accuracy") return game::exitCodeAfterCommand(name, game::runAccuracy(args));
    }
    throwInputError("bounce", name, "unknown command", "one of the commands in 'bounce --help'");
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bounce %s: internal error: %s\n", name.c_str(), e.what());
    return 1;
  }
}
