// README.md's examples run as written: each ```json block that is a level or a capture script is
// saved where the README says such files live (a levels/ or captures/ folder beside src/), captured
// with `bounce capture` (Vulkan validation on), and its first frame must show the Cornell box from
// inside (red wall on the left, green on the right), not the outside of the front wall; every
// command in the "Using bounce" table answers `--help` with exit 0.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/gpu/image_io.hpp"
#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;
using bounce::gpu::CpuImage;

namespace {

using bounce::testcli::Outcome;
using bounce::testcli::quote;
using bounce::testcli::readText;
using bounce::testcli::runBounce;

const fs::path kSource = BOUNCE_SOURCE_DIR;
const fs::path kOut = fs::path(BOUNCE_TEST_OUT) / "readme";
// Wall pixels: a channel 1.5x both others and above 40 (as tests/capture/play). Inside the box at
// least this fraction of the left third is red wall and of the right third green wall (cornell-1's
// camera: 0.18 and 0.25 at 256x256); from outside the front wall (white) both are 0.
constexpr double kMinWallFraction = 0.05;


std::vector<std::string> jsonBlocks(const std::string& readme) {
  std::vector<std::string> blocks;
  const std::string open = "```json\n", close = "```";
  for (std::size_t pos = readme.find(open); pos != std::string::npos; pos = readme.find(open, pos)) {
    const std::size_t start = pos + open.size(), end = readme.find(close, start);
    blocks.push_back(readme.substr(start, end - start));
    pos = end;
  }
  return blocks;
}

// A folder laid out like content/: src/ and every shipped level reachable as levels/NAME.json.
fs::path contentLikeRoot() {
  const fs::path root = kOut / "content";
  fs::remove_all(root);
  fs::create_directories(root / "levels");
  fs::create_directories(root / "captures");
  fs::create_directory_symlink(kSource / "content/src", root / "src");
  for (const auto& e : fs::directory_iterator(kSource / "content/levels"))
    fs::create_symlink(e.path(), root / "levels" / e.path().filename());
  return root;
}

// Fractions of the left third that is red wall and of the right third that is green wall.
std::pair<double, double> wallFractions(const CpuImage& img) {
  std::size_t red = 0, green = 0, n = 0;
  const std::uint32_t third = img.width / 3;
  for (std::uint32_t y = 0; y < img.height; ++y)
    for (std::uint32_t x = 0; x < third; ++x) {
      auto px = [&](std::uint32_t xx, int c) { return double(img.bytes[(std::size_t(y) * img.width + xx) * 4 + c]); };
      const double R = px(x, 0), G = px(x, 1), B = px(x, 2);
      red += R > 1.5 * G && R > 1.5 * B && R > 40;
      const std::uint32_t xr = img.width - 1 - x;
      const double R2 = px(xr, 0), G2 = px(xr, 1), B2 = px(xr, 2);
      green += G2 > 1.5 * R2 && G2 > 1.5 * B2 && G2 > 40;
      ++n;
    }
  return {double(red) / double(n), double(green) / double(n)};
}

void expectInsideTheBox(const fs::path& png) {
  const CpuImage img = bounce::gpu::readPng(png);
  const auto [red, green] = wallFractions(img);
  EXPECT_GT(red, kMinWallFraction) << png << ": red wall on the left";
  EXPECT_GT(green, kMinWallFraction) << png << ": green wall on the right";
}

}  // namespace

TEST(ReadmeExamples, LevelAndCaptureScriptBlocksRunAsWritten) {
  const fs::path root = contentLikeRoot();
  int levels = 0, scripts = 0;
  for (const std::string& block : jsonBlocks(readText(kSource / "README.md"))) {
    if (block.find("\"bounce_level\"") != std::string::npos) {
      const std::string name = "readme-level-" + std::to_string(levels++);
      const fs::path level = root / "levels" / (name + ".json");
      std::ofstream(level) << block;
      // One frame of it, as `bounce capture` of a one-frame script.
      const fs::path script = root / "captures" / (name + ".json");
      std::ofstream(script) << "{\"bounce_capture\": 1, \"level\": \"../levels/" << name
                            << ".json\", \"resolution\": [96, 96], \"dt\": 0.0166667, \"frames\": 1, \"capture\": [0]}\n";
      const fs::path out = kOut / name;
      const Outcome r = runBounce({"capture", script.string(), "--out", out.string()}, out);
      ASSERT_EQ(r.code, 0) << block << "\n" << r.err;
      expectInsideTheBox(out / "frame-0000.png");
    } else if (block.find("\"bounce_capture\"") != std::string::npos) {
      const std::string name = "readme-capture-" + std::to_string(scripts++);
      const fs::path script = root / "captures" / (name + ".json");
      std::ofstream(script) << block;
      const fs::path out = kOut / name;
      const Outcome r = runBounce({"capture", script.string(), "--out", out.string(), "--resolution", "96x96"}, out);
      ASSERT_EQ(r.code, 0) << block << "\n" << r.err;
      const std::string text = readText(script);
      // Every frame the script lists is written; the first shows the box from inside.
      const std::smatch m = [&] {
        std::smatch mm;
        std::regex_search(text, mm, std::regex("\"capture\"\\s*:\\s*\\[([0-9, ]+)\\]"));
        return mm;
      }();
      ASSERT_FALSE(m.empty()) << text;
      std::stringstream list(m[1].str());
      std::string first;
      for (std::string item; std::getline(list, item, ',');) {
        const int f = std::stoi(item);
        char file[32];
        std::snprintf(file, sizeof file, "frame-%04d.png", f);
        EXPECT_TRUE(fs::exists(out / file)) << file;
        if (first.empty()) first = file;
      }
      expectInsideTheBox(out / first);
    }
  }
  EXPECT_EQ(levels, 1) << "README.md has one level example";
  EXPECT_EQ(scripts, 1) << "README.md has one capture-script example";
}

TEST(ReadmeExamples, EveryCommandInTheTableAnswersHelp) {
  const std::string readme = readText(kSource / "README.md");
  std::set<std::string> commands;
  const std::regex row("\\n\\| `bounce ([a-z-]+)");
  for (auto it = std::sregex_iterator(readme.begin(), readme.end(), row); it != std::sregex_iterator(); ++it)
    commands.insert((*it)[1].str());
  // The table lists exactly the commands `bounce --help` lists.
  const fs::path helpDir = kOut / "help";
  ASSERT_EQ(runBounce({"--help"}, helpDir).code, 0);
  const std::string help = readText(helpDir / "stdout.txt");
  std::set<std::string> listed;
  const std::regex line("\n  ([a-z-]+) ");
  for (auto it = std::sregex_iterator(help.begin(), help.end(), line); it != std::sregex_iterator(); ++it)
    listed.insert((*it)[1].str());
  EXPECT_EQ(commands, listed) << help;
  for (const auto& c : commands) {
    const Outcome r = runBounce({c, "--help"}, kOut / ("help-" + c));
    EXPECT_EQ(r.code, 0) << "bounce " << c << " --help: " << r.err;
  }
}
