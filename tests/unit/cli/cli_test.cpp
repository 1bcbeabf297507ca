#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "engine/core/suggest.hpp"
#include "game/cli.hpp"

using namespace bounce;

namespace {
cli::CommandSpec profileSpec() {
  return {"profile", "LEVEL [options]", "per-pass GPU cost",
          {{"--frames", "N", "frames"}, {"--resolution", "WxH", "size"}, {"--effects", "LIST", "effects"},
           {"--no-cull", "", "keep all passes"}},
          1, 1};
}
cli::Args run(std::vector<const char*> argv) {
  return cli::parse(profileSpec(), static_cast<int>(argv.size()), argv.data(), 0);
}
std::string errorOf(std::vector<const char*> argv) {
  try {
    auto a = run(argv);
    a.positiveInt("--frames", 1);
    a.resolution("--resolution");
    a.list("--effects");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Cli, ParsesValuesFlagsAndPositionals) {
  auto a = run({"level.json", "--frames", "30", "--resolution=640x360", "--effects", "direct,shadows", "--no-cull"});
  EXPECT_EQ(a.positional, std::vector<std::string>{"level.json"});
  EXPECT_EQ(a.positiveInt("--frames", 1), 30);
  EXPECT_EQ(a.resolution("--resolution"), (std::pair{640, 360}));
  EXPECT_EQ(*a.list("--effects"), (std::vector<std::string>{"direct", "shadows"}));
  EXPECT_TRUE(a.has("--no-cull"));
  EXPECT_EQ(a.positiveInt("--absent", 7), 7);
}

// nonNegativeInt: the same reader with 0 allowed (a count whose default is none, such as bench rtf's
// --byte-components); below 0 or not a number is one line.
TEST(Cli, NonNegativeIntTakesZeroAndRejectsBelow) {
  EXPECT_EQ(run({"l.json", "--frames", "0"}).nonNegativeInt("--frames", 5), 0);
  EXPECT_EQ(run({"l.json"}).nonNegativeInt("--frames", 5), 5);
  for (const char* bad : {"-1", "x", "3.5", ""}) {
    std::string e;
    try {
      run({"l.json", "--frames", bad}).nonNegativeInt("--frames", 5);
    } catch (const InputError& x) {
      e = x.what();
    }
    EXPECT_EQ(e, std::string("bounce profile: --frames: '") + bad + "' is not a valid count (expected a non-negative integer)");
  }
}

TEST(Cli, BadInputIsOneLineNamingCommandAndOption) {
  EXPECT_EQ(errorOf({"l.json", "--frames", "0"}),
            "bounce profile: --frames: '0' is not a valid count (expected a positive integer)");
  EXPECT_EQ(errorOf({"l.json", "--frames", "12abc"}),
            "bounce profile: --frames: '12abc' is not a valid count (expected a positive integer)");
  EXPECT_EQ(errorOf({"l.json", "--resolution", "640by360"}),
            "bounce profile: --resolution: '640by360' is not a resolution (expected WIDTHxHEIGHT, each 1..16384)");
  EXPECT_EQ(errorOf({"l.json", "--effects", "direct,,shadows"}),
            "bounce profile: --effects: empty item in 'direct,,shadows' (expected a comma-separated list)");
  EXPECT_EQ(errorOf({"l.json", "--bogus"}),
            "bounce profile: --bogus: unknown option (expected one of the options in 'bounce profile --help')");
  EXPECT_EQ(errorOf({"l.json", "--frames"}), "bounce profile: --frames: missing value (expected N)");
  EXPECT_EQ(errorOf({}), "bounce profile: arguments: got 0 argument(s) (expected usage: bounce profile LEVEL [options])");
  EXPECT_EQ(errorOf({"l.json", "--no-cull=1"}), "bounce profile: --no-cull: takes no value");
}

TEST(Cli, HelpSkipsPositionalCheckAndListsOptions) {
  auto a = run({"--help"});
  EXPECT_TRUE(a.has("--help"));
  auto text = cli::helpText(profileSpec());
  EXPECT_NE(text.find("usage: bounce profile LEVEL [options]"), std::string::npos);
  EXPECT_NE(text.find("--resolution WxH"), std::string::npos);
}

// "Did you mean …" (engine/core/suggest.hpp, issue 16): one slip in a short name, two in a long
// one, a swap of neighbours counts once; unrelated words get no suggestion.
TEST(Suggest, NearestNameWithinATypo) {
  const std::vector<std::string> effects{"direct", "shadows", "probes", "dnrt", "vlm", "sl", "rtf", "ssao", "hbao"};
  EXPECT_EQ(editDistance("shdaows", "shadows"), 1u);
  EXPECT_EQ(editDistance("Probes", "probes"), 0u);
  // Optimal string alignment: "ca" → "abc" is 3 (a swap is not followed by an insertion between
  // the swapped pair); the empty string is as far as the other's length.
  EXPECT_EQ(editDistance("ca", "abc"), 3u);
  EXPECT_EQ(editDistance("", "rtf"), 3u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(nearestName("shadow", effects), "shadows");
  EXPECT_EQ(nearestName("prboes", effects), "probes");
  EXPECT_EQ(nearestName("dnr", effects), "dnrt");
  EXPECT_EQ(nearestName("bloom", effects), std::nullopt);
  EXPECT_EQ(nearestName("x", effects), std::nullopt);
  // A 1 MB name: as far from every candidate as its length says, so none is suggested.
  EXPECT_EQ(nearestName(std::string(1u << 20, 's'), effects), std::nullopt);
  EXPECT_EQ(didYouMean("captur", {"play", "capture", "profile"}), ", did you mean \"capture\"?");
  EXPECT_EQ(didYouMean("zzz", {"play", "capture"}), "");
}

TEST(Cli, UnknownOptionSuggestsTheNearest) {
  EXPECT_EQ(errorOf({"l.json", "--frame", "3"}),
            "bounce profile: --frame: unknown option, did you mean \"--frames\"? (expected one of the options in 'bounce profile --help')");
}
