// bounce: the Bounce executable. `bounce --help` lists the commands; exit codes: 0 success,
// 2 bad input (one line naming the file, the place and what was expected), 1 internal error —
// also when a Vulkan validation error was reported during the command (game::exitCodeAfterCommand).
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/core/suggest.hpp"
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
      using Run = int (*)(const cli::Args&);
      static const std::pair<const char*, Run> kRunners[] = {
          {"play", game::runPlay},           {"capture", game::runCapture},
          {"profile", game::runProfile},     {"graph", game::runGraph},
          {"cook", game::runCook},           {"demo", game::runDemo},
          {"reference", game::runReference}, {"export", game::runExport},
          {"bench", game::runBench},         {"bake", game::runBake},
          {"accuracy", game::runAccuracy},   {"vlm-make", game::runVlmMake},
          {"level", game::runLevel},
          {"cache", game::runCache},
      };
      for (const auto& [command, run] : kRunners)
        if (name == command) return game::exitCodeAfterCommand(name, run(args));
    }
    std::vector<std::string> names;
    for (const auto& spec : specs) names.push_back(spec.name);
    throwInputError("bounce", name, "unknown command" + didYouMean(name, names), "one of the commands in 'bounce --help'");
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bounce %s: internal error: %s\n", name.c_str(), e.what());
    return 1;
  }
}
