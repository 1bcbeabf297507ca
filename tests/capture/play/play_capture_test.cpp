// `bounce play` end to end: run the real executable in a virtual X server (xvfb-run) with Vulkan
// validation on (ctest's environment), then check its screenshot — not blank, the Cornell box's red
// wall on the left and green wall on the right, equal to `bounce capture` of the same frame, and
// the overlay drawn only when asked for — and its bad-input behaviour.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/gpu/image_io.hpp"

namespace fs = std::filesystem;
using bounce::gpu::CpuImage;

namespace {

// A blank (or constant) picture has luminance variance 0; the Cornell view measures ~4900 (8-bit
// levels²: walls, shadows and the lamp-lit floor). 400 (a standard deviation of 20 levels) is far
// from both.
constexpr double kMinLumaVariance = 400.0;
// Mean colour of a third of the image: the wall's channel must exceed both others by this many
// 8-bit levels. Measured at frame 2 of cornell-1: left R − max(G,B) = 24.6, right
// G − max(R,B) = 8.5 (the right third also holds the white floor and the prop's shadow).
constexpr double kLeftRedMargin = 12.0;
constexpr double kRightGreenMargin = 4.0;
// Wall pixels: a channel 1.5× both others and above 40 (not shadow). At least this fraction of a
// third shows its own wall (measured 0.18 red on the left, 0.25 green on the right) ...
constexpr double kMinWallFraction = 0.08;
// ... and essentially none shows the opposite wall (measured 0: the walls never swap sides).
constexpr double kMaxWrongWallFraction = 0.01;
// play --frames and capture run the same renderer at the same simulation time; they differ only
// in how t is rounded (f/60 vs f·dt), which could move a few edge pixels (measured: 0 exactly).
constexpr double kMaxMeanAbsDiffVsCapture = 0.25;
// What the scripted keys change must show: the capture's frame 0 and frame 2 differ by 0.91
// (the prop moves 4 mm and turns 3°), with and without shadows by 1.88 (frame 2; 4.8 before the
// level named probes, whose indirect light fills the shadows in and brightens the whole frame
// towards white, where the tonemap compresses differences).
constexpr double kMinDiffFromMotion = 0.5;
constexpr double kMinDiffFromShadows = 1.0;
// The overlay panel (top left) changes the picture under it by tens of levels on average ...
constexpr double kMinOverlayDiff = 5.0;
// ... and nothing in the far corner it does not reach (exactly 0 expected; the frame is fixed).
constexpr double kMaxDiffOutsideOverlay = 0.01;

const fs::path kLevel = fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";

struct ProcessRun {
  int code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Runs `args` with the bounce executable (under xvfb-run when `display`); stdout and stderr go to
// files in `dir`. xvfb-run -a can lose a race for a server number against a parallel test, and its
// own cleanup can fail after the program ran ("problem while cleaning up temporary directory", exit
// 5, seen under asan in CI): both are the wrapper's failures, not bounce's, and the attempt is retried.
// `wrapper` goes between xvfb-run and the executable (e.g. "timeout 120 ").
ProcessRun runBounce(const fs::path& dir, const std::string& args, bool display, const std::string& wrapper = "") {
  fs::create_directories(dir);
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  // Under the sanitizer environment ctest preloads the Vulkan driver (LD_PRELOAD, tests/sanitizer);
  // it is for bounce only. Inherited by xvfb-run's own helpers (xauth, Xvfb, the `rm` of its cleanup)
  // it loads lavapipe and LLVM into each: our best explanation for the cleanup's `rm` failing with no
  // message (exit 5; three attempts in a row once under asan in CI, never without the preload; not
  // reproduced by hand). So the helpers run without it, and bounce gets it back through `env`.
  const char* preload = std::getenv("LD_PRELOAD");
  const std::string keepPreload = preload && *preload ? "env LD_PRELOAD=" + quoted(preload) + " " : "";
  const std::string prefix = (display ? "env -u LD_PRELOAD xvfb-run -a " + keepPreload : "") + wrapper;
  const std::string cmd =
      prefix + quoted(BOUNCE_EXE) + " " + args + " >" + quoted(out.string()) + " 2>" + quoted(err.string());
  ProcessRun r;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int status = std::system(cmd.c_str());
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    if (r.err.find("Xvfb failed to start") == std::string::npos &&
        r.err.find("xvfb-run: error: problem while cleaning up") == std::string::npos)
      break;
  }
  return r;
}

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

struct Region {
  std::uint32_t x0, y0, x1, y1;  // half-open pixel rectangle
};

struct RegionStats {
  double mean[3] = {0, 0, 0};
  double redFraction = 0, greenFraction = 0;
};

std::uint8_t at(const CpuImage& img, std::uint32_t x, std::uint32_t y, int c) {
  return img.bytes[(std::size_t(y) * img.width + x) * 4 + c];
}

RegionStats stats(const CpuImage& img, Region r) {
  RegionStats s;
  std::size_t n = 0, red = 0, green = 0;
  for (std::uint32_t y = r.y0; y < r.y1; ++y)
    for (std::uint32_t x = r.x0; x < r.x1; ++x) {
      const double R = at(img, x, y, 0), G = at(img, x, y, 1), B = at(img, x, y, 2);
      s.mean[0] += R;
      s.mean[1] += G;
      s.mean[2] += B;
      red += R > 1.5 * G && R > 1.5 * B && R > 40;
      green += G > 1.5 * R && G > 1.5 * B && G > 40;
      ++n;
    }
  for (double& m : s.mean) m /= double(n);
  s.redFraction = double(red) / double(n);
  s.greenFraction = double(green) / double(n);
  return s;
}

double lumaVariance(const CpuImage& img) {
  double sum = 0, sum2 = 0;
  const std::size_t n = std::size_t(img.width) * img.height;
  for (std::size_t i = 0; i < n; ++i) {
    const double l = 0.2126 * img.bytes[i * 4] + 0.7152 * img.bytes[i * 4 + 1] + 0.0722 * img.bytes[i * 4 + 2];
    sum += l;
    sum2 += l * l;
  }
  const double mean = sum / double(n);
  return sum2 / double(n) - mean * mean;
}

// Mean absolute difference of the RGB channels over a region.
double meanAbsDiff(const CpuImage& a, const CpuImage& b, Region r) {
  double sum = 0;
  for (std::uint32_t y = r.y0; y < r.y1; ++y)
    for (std::uint32_t x = r.x0; x < r.x1; ++x)
      for (int c = 0; c < 3; ++c) sum += std::abs(double(at(a, x, y, c)) - double(at(b, x, y, c)));
  return sum / (3.0 * double(r.x1 - r.x0) * double(r.y1 - r.y0));
}

Region whole(const CpuImage& img) { return {0, 0, img.width, img.height}; }

void expectCleanRun(const ProcessRun& r) {
  EXPECT_EQ(r.code, 0) << "stderr:\n" << r.err;
  EXPECT_EQ(lower(r.err).find("validation"), std::string::npos) << "stderr:\n" << r.err;
}

const fs::path kOut = fs::path(BOUNCE_TEST_OUT) / "play";

// Frame `index` of cornell-1 at 256×256 through `bounce capture` (headless) with dt = 1/60 s;
// `extraJson` adds keys to the capture script (e.g. an effects override).
CpuImage captureFrame(const fs::path& dir, const std::string& extraJson, int index) {
  fs::create_directories(dir);
  const fs::path script = dir / "script.json";
  std::ofstream(script) << R"({"bounce_capture": 1, "level": ")" << kLevel.generic_string()
                        << R"(", "resolution": [256, 256], "dt": 0.016666666666666666, "frames": )" << index + 1
                        << R"(, "capture": [)" << index << "]" << extraJson << "}";
  const ProcessRun r = runBounce(dir, "capture " + quoted(script.string()) + " --out " + quoted(dir.string()), false);
  expectCleanRun(r);
  char name[32];
  std::snprintf(name, sizeof name, "frame-%04d.png", index);
  return bounce::gpu::readPng(dir / name);
}

// `bounce play` of cornell-1 for 3 frames at 256×256 in xvfb; the screenshot of frame 2.
CpuImage playFrames(const fs::path& dir, const std::string& extraArgs) {
  const fs::path shot = dir / "play.png";
  const ProcessRun r = runBounce(dir, "play " + quoted(kLevel.string()) + " --frames 3 --screenshot " +
                                          quoted(shot.string()) + " --resolution 256x256" + extraArgs, true);
  expectCleanRun(r);
  return bounce::gpu::readPng(shot);
}

}  // namespace

TEST(PlayScreenshot, CornellShowsWallsAndMatchesCapture) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
  const fs::path dir = kOut / "walls";
  fs::remove_all(dir);
  const CpuImage img = playFrames(dir, "");
  ASSERT_EQ(img.width, 256u);
  ASSERT_EQ(img.height, 256u);

  EXPECT_GT(lumaVariance(img), kMinLumaVariance);
  const RegionStats left = stats(img, {0, 0, 256 / 3, 256});
  const RegionStats right = stats(img, {256 - 256 / 3, 0, 256, 256});
  EXPECT_GT(left.mean[0] - std::max(left.mean[1], left.mean[2]), kLeftRedMargin);
  EXPECT_GT(right.mean[1] - std::max(right.mean[0], right.mean[2]), kRightGreenMargin);
  EXPECT_GT(left.redFraction, kMinWallFraction);
  EXPECT_GT(right.greenFraction, kMinWallFraction);
  EXPECT_LT(left.greenFraction, kMaxWrongWallFraction);
  EXPECT_LT(right.redFraction, kMaxWrongWallFraction);

  // The same frame (index 2, t = 2/60 s) through `bounce capture` (headless, no window).
  const CpuImage ref = captureFrame(dir / "capture", "", 2);
  ASSERT_EQ(ref.width, img.width);
  EXPECT_LT(meanAbsDiff(img, ref, whole(img)), kMaxMeanAbsDiffVsCapture);
}

// Keys pressed at run time (--keys, as a user would) change the frame exactly as the equivalent
// capture settings do: P at frame 0 holds the motion at t = 0; 2 at frame 1 removes shadows
// (and the shadow pass) for frame 2.
TEST(PlayScreenshot, ScriptedKeysPauseAndToggleShadows) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
  const fs::path dir = kOut / "keys";
  fs::remove_all(dir);
  const CpuImage frame0 = captureFrame(dir / "capture-0", "", 0);
  const CpuImage frame2 = captureFrame(dir / "capture-2", "", 2);
  // The level's effects without `shadows` (what key 2 toggles).
  const CpuImage frame2NoShadows = captureFrame(dir / "capture-2-direct", R"(, "effects": ["direct", "probes", "dnrt"])", 2);

  const CpuImage paused = playFrames(dir / "paused", " --keys P@0");
  EXPECT_LT(meanAbsDiff(paused, frame0, whole(paused)), kMaxMeanAbsDiffVsCapture);
  EXPECT_GT(meanAbsDiff(paused, frame2, whole(paused)), kMinDiffFromMotion);

  const CpuImage noShadows = playFrames(dir / "no-shadows", " --keys 2@1");
  EXPECT_LT(meanAbsDiff(noShadows, frame2NoShadows, whole(noShadows)), kMaxMeanAbsDiffVsCapture);
  EXPECT_GT(meanAbsDiff(noShadows, frame2, whole(noShadows)), kMinDiffFromShadows);
}

TEST(PlayScreenshot, OverlayOnlyWhenAsked) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
  const fs::path dir = kOut / "overlay";
  fs::remove_all(dir);
  auto shoot = [&](const std::string& name, const std::string& extra) {
    const fs::path shot = dir / (name + ".png");
    const ProcessRun r = runBounce(dir / name, "play " + quoted(kLevel.string()) + " --frames 3 --screenshot " +
                                            quoted(shot.string()) + " --resolution 640x480" + extra, true);
    expectCleanRun(r);
    return bounce::gpu::readPng(shot);
  };
  const CpuImage plain = shoot("default", "");
  const CpuImage with = shoot("on", " --overlay on");
  ASSERT_EQ(plain.width, 640u);
  ASSERT_EQ(with.width, 640u);
  // The panel sits at the top left (its first lines: level name, frame time, GPU table).
  EXPECT_GT(meanAbsDiff(plain, with, {8, 8, 200, 120}), kMinOverlayDiff);
  EXPECT_LT(meanAbsDiff(plain, with, {540, 400, 640, 480}), kMaxDiffOutsideOverlay);
}

TEST(PlayErrors, MissingLevelExits2WithOneLine) {
  const ProcessRun r = runBounce(kOut / "missing", "play missing.json", false);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("missing.json", 0), 0u) << r.err;  // the line starts with the file
}

TEST(PlayErrors, BadOnOffValueExits2) {
  const ProcessRun r = runBounce(kOut / "bad-overlay", "play " + quoted(kLevel.string()) + " --overlay maybe", false);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "bounce play: --overlay: 'maybe' (expected on or off)\n");
}

TEST(PlayHelp, ListsKeyMapAndOverlayOption) {
  const ProcessRun r = runBounce(kOut / "help", "play --help", false);
  EXPECT_EQ(r.code, 0);
  for (const char* needle : {"W/A/S/D", "1=direct", "9=hbao", "F1=lit", "F6=entity-id", "Esc quit", "--overlay on|off"})
    EXPECT_NE(r.out.find(needle), std::string::npos) << needle << " missing from:\n" << r.out;
}

// Issue 16: the overlay is laid out before it is drawn, so `--frames 1` already shows the whole
// panel (it used to show nothing on frame 1 and "median of 0 frames" on frame 2), and it fits a
// 640x360 window; a scripted run prints no key table.
TEST(PlayScreenshot, OverlayOnFrameOneFits640x360) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
  const fs::path dir = kOut / "overlay-frame1";
  fs::remove_all(dir);
  auto shoot = [&](const std::string& name, const std::string& extra) {
    const fs::path shot = dir / (name + ".png");
    const ProcessRun r = runBounce(dir / name, "play " + quoted(kLevel.string()) + " --frames 1 --screenshot " +
                                            quoted(shot.string()) + " --resolution 640x360" + extra, true);
    expectCleanRun(r);
    EXPECT_EQ(r.out.find("keys:"), std::string::npos) << "no key table on a scripted run:\n" << r.out;
    return bounce::gpu::readPng(shot);
  };
  const CpuImage plain = shoot("plain", "");
  const CpuImage with = shoot("overlay", " --overlay on");
  ASSERT_EQ(with.height, 360u);
  // Frame 1 has the panel: its title bar and first rows at the top left ...
  EXPECT_GT(meanAbsDiff(plain, with, {8, 8, 200, 120}), kMinOverlayDiff);
  // ... and it ends above the window's bottom edge and left of its right edge.
  EXPECT_LT(meanAbsDiff(plain, with, {0, 354, 640, 360}), kMaxDiffOutsideOverlay);
  EXPECT_LT(meanAbsDiff(plain, with, {560, 0, 640, 360}), kMaxDiffOutsideOverlay);
}

// F12 (here scripted) writes the frame as PNG + PFM without the overlay: the PNG equals
// `bounce capture` of the same frame.
TEST(PlayScreenshot, F12WritesPngAndPfm) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
  const fs::path dir = kOut / "f12";
  fs::remove_all(dir);
  const ProcessRun r = runBounce(dir, "play " + quoted(kLevel.string()) + " --frames 3 --keys F12@2 --resolution 256x256", true);
  expectCleanRun(r);
  const auto at = r.out.find("screenshot: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  std::istringstream line(r.out.substr(at + 12));
  std::string png, pfm;
  line >> png >> pfm;
  ASSERT_TRUE(fs::exists(png)) << png;
  ASSERT_TRUE(fs::exists(pfm)) << pfm;
  const CpuImage shot = bounce::gpu::readPng(png);
  const CpuImage ref = captureFrame(dir / "capture", "", 2);
  ASSERT_EQ(shot.width, ref.width);
  EXPECT_LT(meanAbsDiff(shot, ref, whole(shot)), kMaxMeanAbsDiffVsCapture);
  EXPECT_EQ(bounce::gpu::readPfm(pfm).width, 256u);
  fs::remove(png);
  fs::remove(pfm);
}

// Issue 16: `bounce play` checks the render size against the device (image side limit, memory)
// before it opens the window. An interactive run (no --frames, no --keys) prints its key table as
// soon as the window is open, so an empty stdout shows the refusal came first; exit 2, one line.
TEST(PlayErrors, OversizedResolutionIsRefusedBeforeTheWindow) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
  // The guard: a device that holds such frames would run the interactive window until killed.
  const ProcessRun r = runBounce(kOut / "oversized", "play " + quoted(kLevel.string()) + " --resolution 16384x16384", true,
                                 "timeout 300 ");
  if (r.code == 124) GTEST_SKIP() << "this device holds 16384x16384 frames (play ran until the guard's timeout)";
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("bounce play: --resolution: 16384x16384 ", 0), 0u) << r.err;
  EXPECT_EQ(r.out, "") << "nothing (no key table: no window) before the refusal";
}

// Issue 16: DNRT's mode is a run-time setting (key M, or the overlay's "dnrt mode" control): every
// object switches to the paper's full-screen pass, which shades the same pixels as the default
// outer-cube draw, so the frame still matches `bounce capture`; the switch is logged.
TEST(PlayScreenshot, KeyMSwitchesDnrtToTheFullScreenPass) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
  const fs::path dir = kOut / "dnrt-mode";
  fs::remove_all(dir);
  const fs::path shot = dir / "play.png";
  const ProcessRun r = runBounce(dir / "run", "play " + quoted(kLevel.string()) + " --frames 3 --keys M@0 --screenshot " +
                                                  quoted(shot.string()) + " --resolution 256x256", true);
  expectCleanRun(r);
  EXPECT_NE(r.err.find("dnrt mode: full-screen pass per object"), std::string::npos) << r.err;
  const CpuImage img = bounce::gpu::readPng(shot);
  const CpuImage ref = captureFrame(dir / "capture", "", 2);
  ASSERT_EQ(img.width, ref.width);
  EXPECT_LT(meanAbsDiff(img, ref, whole(img)), kMaxMeanAbsDiffVsCapture);
}
