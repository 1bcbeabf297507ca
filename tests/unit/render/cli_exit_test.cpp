// The `bounce` executable as users run it: exit codes (0 success, 2 bad input), the one-line error
// format `file: /json/pointer: what (expected …)`, the files `graph`, `profile` and `cook`
// write, `--help` of every command, and `cook LEVEL`. Each command runs as a child process (std::system) with stdout/stderr in files under
// BOUNCE_TEST_OUT/render-cli/<test name>/.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;

namespace {

using bounce::testcli::Outcome;
using bounce::testcli::quote;
using bounce::testcli::readText;
using bounce::testcli::lines;

const fs::path kSource = BOUNCE_SOURCE_DIR;
const fs::path kBadLevel = kSource / "tests/data/render/bad-unknown-key.json";
const fs::path kCornell = kSource / "content/levels/cornell-1.json";

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(BOUNCE_TEST_OUT) / "render-cli" / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  Outcome bounce(const std::vector<std::string>& args) { return bounce::testcli::runBounce(args, dir_); }
  fs::path dir_;
};

}  // namespace

TEST_F(Cli, UnknownLevelKeyIsOneLineNamingFileAndPointer) {
  const Outcome r = bounce({"graph", kBadLevel.string(), "--dot", (dir_ / "g.dot").string()});
  EXPECT_EQ(r.code, 2);
  const auto errLines = lines(r.err);
  ASSERT_EQ(errLines.size(), 1u) << r.err;
  EXPECT_NE(errLines[0].find("bad-unknown-key.json"), std::string::npos) << errLines[0];
  EXPECT_NE(errLines[0].find("/entities/0/colour"), std::string::npos) << errLines[0];
  EXPECT_FALSE(fs::exists(dir_ / "g.dot")) << "nothing is written for a bad level";
}

TEST_F(Cli, MissingCaptureScriptIsBadInput) {
  const Outcome r = bounce({"capture", (dir_ / "no-such-script.json").string(), "--out", (dir_ / "out").string()});
  EXPECT_EQ(r.code, 2);
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("no-such-script.json"), std::string::npos) << r.err;
}

TEST_F(Cli, ProfileWithZeroFramesIsBadInput) {
  const Outcome r = bounce({"profile", kCornell.string(), "--frames", "0"});
  EXPECT_EQ(r.code, 2);
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
}

TEST_F(Cli, GraphWithDirectOnlyHasNoShadowPass) {
  const fs::path dot = dir_ / "cornell.dot";
  const Outcome r = bounce({"graph", kCornell.string(), "--dot", dot.string(), "--effects", "direct"});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = readText(dot);
  EXPECT_EQ(text.rfind("digraph", 0), 0u);
  EXPECT_NE(text.find("gbuffer"), std::string::npos);
  EXPECT_EQ(text.find("shadow"), std::string::npos);
}

TEST_F(Cli, ProfileCsvHasHeaderAndOneRowPerPassPlusFrame) {
  const fs::path csv = dir_ / "profile.csv";
  const Outcome r = bounce({"profile", kCornell.string(), "--frames", "3", "--resolution", "64x64", "--csv", csv.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = lines(readText(csv));
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0], "pass,object,frames,median_ms,p95_ms");
  std::vector<std::string> passes, objects;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::string& row = rows[i];
    passes.push_back(row.substr(0, row.find(',')));
    // pass, object (empty: whole-pass rows), frames, median, p95.
    ASSERT_EQ(std::count(row.begin(), row.end(), ','), 4) << row;
    std::stringstream fields(row);
    std::string pass, object, frames, median, p95;
    std::getline(fields, pass, ',');
    std::getline(fields, object, ',');
    std::getline(fields, frames, ',');
    std::getline(fields, median, ',');
    std::getline(fields, p95, ',');
    objects.push_back(object);  // empty on whole-pass rows; DNRT adds a row per object it ran for
    // Exactly the 3 measured frames (warm-up excluded): every resolved frame is collected, also
    // the ones FrameRing::waitIdle() resolves together at the end.
    EXPECT_EQ(std::stoi(frames), 3) << row;
    EXPECT_GE(std::stod(median), 0.0) << row;
    EXPECT_GE(std::stod(p95), std::stod(median)) << row;
  }
  // cornell-1 names direct, shadows, probes and dnrt and relights its probes (probes.relight); its one
  // prop carries a DNRT field (dnrt.combine sums its transfer per grid vertex before the draw).
  EXPECT_EQ(passes, (std::vector<std::string>{"shadow", "gbuffer", "lighting", "probes.relight", "probes.tiles", "probes",
                                              "dnrt.combine", "dnrt", "dnrt", "tonemap", "frame"}));
  EXPECT_EQ(objects, (std::vector<std::string>{"", "", "", "", "", "", "", "", "prop-textured-box", "", ""}));
}

// The Cornell VLM level: both phases give the dynamic VLM on the moving prop its own row
// ("vlm.lights/<entity>" and "vlm/<entity>", issue 5 §7), and the table ends with the grids' overflow line (the
// level's 20 virtual lights never fill K = 32 slots, so no cell overflows). The CSV stays five
// timing columns.
TEST_F(Cli, ProfileOfCornellVlmHasPerObjectVlmRowAndOverflowLine) {
  const fs::path csv = dir_ / "profile-vlm.csv";
  const Outcome r = bounce({"profile", (kSource / "content/levels/cornell-vlm.json").string(), "--frames", "3",
                            "--resolution", "64x64", "--csv", csv.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = lines(readText(csv));
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0], "pass,object,frames,median_ms,p95_ms");
  std::vector<std::string> vlmRows;
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i].rfind("vlm", 0) == 0) vlmRows.push_back(rows[i].substr(0, rows[i].find(',', rows[i].find(',') + 1)));
  EXPECT_EQ(vlmRows, (std::vector<std::string>{"vlm.lights,", "vlm.lights,vlm-prop", "vlm,", "vlm,vlm-prop"}));
  const auto out = lines(r.out);
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out.back(), "vlm overflow: static 0/4096 cells, dynamic 0/4096 (most 0), K 32");
}

// The VLM benches print one line per setting in a fixed shape; the numbers are not checked (no
// timed tests), the structure and the settings are. Tiny frames keep this cheap on lavapipe.
TEST_F(Cli, VlmBenchesPrintOneLinePerSetting) {
  const Outcome lightsRun =
      bounce({"bench", "vlm-lights", "--counts", "20,40", "--resolution", "32x32", "--frames", "1"});
  ASSERT_EQ(lightsRun.code, 0) << lightsRun.err;
  const auto l = lines(lightsRun.out);
  ASSERT_EQ(l.size(), 2u) << lightsRun.out;
  EXPECT_EQ(l[0].rfind("lights=20 grid=1 k=20 32x32 vlm_ms=", 0), 0u) << l[0];
  EXPECT_EQ(l[1].rfind("lights=40 grid=1 k=40 32x32 vlm_ms=", 0), 0u) << l[1];
  EXPECT_NE(l[1].find(" vlm_lights_ms="), std::string::npos) << l[1];

  const Outcome kRun = bounce({"bench", "vlm-k", "--counts", "10", "--lights", "60", "--resolution", "32x32", "--frames", "1"});
  ASSERT_EQ(kRun.code, 0) << kRun.err;
  const auto k = lines(kRun.out);
  ASSERT_EQ(k.size(), 1u) << kRun.out;
  EXPECT_EQ(k[0].rfind("k=10 lights=60 grid=16 32x32 vlm_ms=", 0), 0u) << k[0];
  // Range 100 and 60 lights: every cell lists more than 10 candidates.
  EXPECT_NE(k[0].find(" overflow_cells=4096/4096 frames=1"), std::string::npos) << k[0];

  const Outcome grid = bounce({"bench", "vlm-grid", "--lights", "200", "--grid", "4", "--runs", "1", "--no-gather"});
  ASSERT_EQ(grid.code, 0) << grid.err;
  EXPECT_EQ(grid.out.rfind("lights=200 grid=4 k=32 scatter_ms=", 0), 0u) << grid.out;
  EXPECT_NE(grid.out.find(" gather_ms=skipped overflow_cells="), std::string::npos) << grid.out;

  const Outcome bad = bounce({"bench", "vlm-lights", "--counts", "20,x"});
  EXPECT_EQ(bad.code, 2);
  ASSERT_EQ(lines(bad.err).size(), 1u) << bad.err;
  EXPECT_NE(bad.err.find("--counts"), std::string::npos) << bad.err;
}

// `bounce bench sl` on its default level, characters.json, which reads the blocked light from the
// probes' direction maps: their uniform block holds 64 SLs in all (gi::sl::kMaxMappedSpheres), so the
// 128-sphere count is benched with the SH and its lines say so, where the level alone is bad input
// (session 21: the default counts stopped at 128 with that error). Numbers not checked (no timed tests).
TEST_F(Cli, SlBenchReadsTheShWhereTheMapsCannotHoldTheSpheres) {
  const Outcome r = bounce({"bench", "sl", "--counts", "64,128", "--resolution", "32x18", "--frames", "1"});
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<std::string> l;
  for (const std::string& line : lines(r.out))
    if (line.rfind("spheres=", 0) == 0) l.push_back(line);
  ASSERT_EQ(l.size(), 4u) << r.out;
  const char* kStart[] = {"spheres=64 blocking=per-sphere 32x18 sl_ms=", "spheres=64 blocking=per-object 32x18 sl_ms=",
                          "spheres=128 blocking=per-sphere 32x18 sl_ms=", "spheres=128 blocking=per-object 32x18 sl_ms="};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(l[i].rfind(kStart[i], 0), 0u) << l[i];
    const std::string end = std::string(" influence=12 resolution=full blocked_read=") + (i < 2 ? "map" : "sh");
    EXPECT_EQ(l[i].substr(l[i].size() - std::min(l[i].size(), end.size())), end) << l[i];
  }
}

TEST_F(Cli, CookWritesIntoOutputFolder) {
  const fs::path out = dir_ / "cooked";
  const Outcome r = bounce({"cook", (fs::path(BOUNCE_SHARED_DIR) / "assets/Box/glTF/Box.gltf").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(out))
    if (e.is_regular_file() && e.file_size() > 0) ++files;
  EXPECT_GE(files, 1u) << "cook wrote nothing into " << out;
}

// `bounce bake`: one line per bake; --force bakes, a second run finds every entry in the cache,
// a level whose effects need no bake says so, and an unknown effect is bad input. cornell-1 relights
// its probes: the relight bake, and the prop's occlusion-only field (DNRT's lights out of the
// anti-radiance, gi/dnrt/runtime.hpp) baked with its field in one job, one line.
TEST_F(Cli, BakeReportsEachBakeThenTheCache) {
  const std::string effects = "direct,probes,dnrt";
  const Outcome forced = bounce({"bake", kCornell.string(), "--effects", effects, "--force"});
  ASSERT_EQ(forced.code, 0) << forced.err;
  const auto first = lines(forced.out);
  ASSERT_EQ(first.size(), 3u) << forced.out;
  EXPECT_EQ(first[0].rfind("probes  6x6x6 at 0.1 m, SH order 3, 256 rays: ", 0), 0u) << first[0];
  EXPECT_EQ(first[1].rfind("probes.relight  4096 surfels, 216 probes", 0), 0u) << first[1];
  // one trace bakes the field and its occlusion-only field (bakeCachedWithOcclusion): one line, both files
  EXPECT_EQ(first[2].rfind("dnrt    prop-textured-box: 32^3 x 256 rays, 4 SH: ", 0), 0u) << first[2];
  EXPECT_NE(first[2].find(".field + occlusion only -> "), std::string::npos) << first[2];
  EXPECT_EQ(forced.out.find("cached"), std::string::npos);

  const Outcome again = bounce({"bake", kCornell.string(), "--effects", effects});
  ASSERT_EQ(again.code, 0) << again.err;
  const auto second = lines(again.out);
  ASSERT_EQ(second.size(), 3u) << again.out;
  for (const auto& l : second) EXPECT_NE(l.find(": cached "), std::string::npos) << l;

  const Outcome none = bounce({"bake", kCornell.string(), "--effects", "direct,shadows"});
  EXPECT_EQ(none.code, 0);
  EXPECT_EQ(none.out, "nothing to bake: the effects name none of probes, dnrt, sl, nor rtf\n");

  const Outcome bad = bounce({"bake", kCornell.string(), "--effects", "direct,glow"});
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(lines(bad.err).size(), 1u) << bad.err;
}

// Every command listed by `bounce --help` answers `bounce COMMAND --help` with exit 0, its usage
// line first and nothing on stderr — without its required arguments.
TEST_F(Cli, EveryCommandHasHelp) {
  const Outcome overview = bounce({"--help"});
  ASSERT_EQ(overview.code, 0) << overview.err;
  std::vector<std::string> names;
  bool inCommands = false;
  for (const auto& line : lines(overview.out)) {
    if (line == "commands:") inCommands = true;
    else if (line.empty()) inCommands = false;
    // A command row is "  name  summary"; continuation lines (play's key map) are indented deeper.
    else if (inCommands && line.size() > 2 && line[0] == ' ' && line[1] == ' ' && line[2] != ' ')
      names.push_back(line.substr(2, line.find(' ', 2) - 2));
  }
  for (const char* expected : {"play", "capture", "profile", "graph", "cook", "reference", "demo", "accuracy", "bake",
                               "export", "bench"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected << " missing from --help";
  for (const auto& name : names) {
    SCOPED_TRACE(name);
    const Outcome r = bounce({name, "--help"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const auto out = lines(r.out);
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out[0].rfind("usage: bounce " + name + " ", 0), 0u) << out[0];
    EXPECT_NE(r.out.find("  --help "), std::string::npos);
  }
  // The key map is part of play's help (README "Playing" quotes it).
  EXPECT_NE(bounce({"play", "--help"}).out.find("keys: W/A/S/D move"), std::string::npos);
}

// `bounce cook LEVEL` cooks each asset the level names once, into the same cache entry as cooking
// that asset file itself; a Cornell level gives one entry per distinct asset path.
TEST_F(Cli, CookLevelCooksEveryAssetItUses) {
  auto entries = [](const fs::path& dir) {
    std::vector<std::string> names;
    if (fs::exists(dir))
      for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file() && e.path().extension() == ".bcook") names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  };
  const fs::path level = kSource / "tests/data/render/plane-debug.json";  // quad.gltf, used twice
  const Outcome fromLevel = bounce({"cook", level.string(), "--out", (dir_ / "level").string()});
  ASSERT_EQ(fromLevel.code, 0) << fromLevel.err;
  const Outcome fromFile =
      bounce({"cook", (kSource / "tests/data/render/quad.gltf").string(), "--out", (dir_ / "file").string()});
  ASSERT_EQ(fromFile.code, 0) << fromFile.err;
  const auto a = entries(dir_ / "level"), b = entries(dir_ / "file");
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a, b);
  EXPECT_EQ(readText(dir_ / "level" / a[0]), readText(dir_ / "file" / b[0]));

  // Distinct "asset" paths of cornell-1 (each resolved against the level's folder).
  const std::string text = readText(kCornell);
  std::vector<std::string> assets;
  for (std::size_t at = text.find("\"asset\""); at != std::string::npos; at = text.find("\"asset\"", at + 1)) {
    const std::size_t open = text.find('"', text.find(':', at) + 1), close = text.find('"', open + 1);
    assets.push_back(text.substr(open + 1, close - open - 1));
  }
  std::sort(assets.begin(), assets.end());
  assets.erase(std::unique(assets.begin(), assets.end()), assets.end());
  ASSERT_GE(assets.size(), 2u);
  const Outcome cornell = bounce({"cook", kCornell.string(), "--out", (dir_ / "cornell").string()});
  ASSERT_EQ(cornell.code, 0) << cornell.err;
  EXPECT_EQ(entries(dir_ / "cornell").size(), assets.size());
}

TEST_F(Cli, GraphTakesDevice) {
  // A device name that matches nothing is bad input listing the devices (exit 2, one line), so
  // --device reaches the Context; an empty match is not silently ignored.
  const Outcome r = bounce({"graph", kCornell.string(), "--dot", (dir_ / "g.dot").string(), "--device", "no-such-gpu"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("vulkan: --device: no Vulkan device matches --device 'no-such-gpu' (expected a substring of a device name; available: '"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "g.dot"));
}
