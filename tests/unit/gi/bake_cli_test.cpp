// `bounce bake` as a job graph (engine/gi/technique.hpp BakeJob, game/bake_jobs.hpp), run as users
// and ninja run it: the plan under `ninja -j2` writes byte-identical entries to a plain bake, a job
// run twice is a cache hit, a corrupt or truncated entry is re-baked, two processes baking one key at
// once leave one valid entry; the notes for effects that cannot run; `bounce cache`. Each test bakes
// tests/data/gi/bake-tiny.json (3 jobs, well under a second each) into its own BOUNCE_CACHE.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "game/session.hpp"
#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;

namespace {

using bounce::testcli::Outcome;
using bounce::testcli::quote;
using bounce::testcli::readText;
using bounce::testcli::lines;

const fs::path kSource = BOUNCE_SOURCE_DIR;
const fs::path kTiny = kSource / "tests/data/gi/bake-tiny.json";

// Every regular file under root/kind for the bake kinds, by path relative to root → bytes.
std::map<std::string, std::string> entries(const fs::path& root) {
  std::map<std::string, std::string> out;
  for (const char* kind : {"probes", "dnrt"}) {
    if (!fs::is_directory(root / kind)) continue;
    for (const auto& f : fs::directory_iterator(root / kind))
      if (f.is_regular_file()) out[fs::relative(f.path(), root).string()] = readText(f.path());
  }
  return out;
}

class BakeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(BOUNCE_TEST_OUT) / "gi-bake" / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    cooked_ = bounce::game::cookCacheDir();  // shared: cooking is not what these tests are about
  }
  // The environment of every command: its own cache root, the build's cooked assets.
  std::string env(const fs::path& root) const {
    return "BOUNCE_CACHE=" + quote(root.string()) + " BOUNCE_COOK_CACHE=" + quote(cooked_.string()) + " ";
  }
  std::string bounceCmd(const fs::path& root, const std::vector<std::string>& args) const {
    return bounce::testcli::bounceCommand(args, env(root));
  }
  Outcome sh(const std::string& cmd, const std::string& name = "run") {
    return bounce::testcli::runShell(cmd, dir_ / (name + ".out"), dir_ / (name + ".err"));
  }
  Outcome bounce(const fs::path& root, const std::vector<std::string>& args) { return sh(bounceCmd(root, args)); }
  // The keys of the tiny level's jobs, from --list-jobs.
  std::vector<std::string> keys(const fs::path& root) {
    const Outcome r = bounce(root, {"bake", kTiny.string(), "--list-jobs"});
    EXPECT_EQ(r.code, 0) << r.err;
    std::vector<std::string> out;
    for (const auto& line : lines(r.out)) {
      const auto at = line.find("\"key\": \"");
      if (at != std::string::npos) out.push_back(line.substr(at + 8, 16));
    }
    return out;
  }
  fs::path dir_, cooked_;
};

TEST_F(BakeCli, ListJobsIsOneJsonLinePerJob) {
  const Outcome r = bounce(dir_ / "cache", {"bake", kTiny.string(), "--list-jobs"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto ls = lines(r.out);
  ASSERT_EQ(ls.size(), 3u) << r.out;  // the probe volume and one field per `dnrt` box
  int probes = 0, dnrt = 0;
  for (const auto& l : ls) {
    EXPECT_EQ(l.front(), '{');
    EXPECT_EQ(l.back(), '}');
    for (const char* field : {"\"key\": ", "\"technique\": ", "\"command\": ", "\"inputs\": [", "\"output\": "})
      EXPECT_NE(l.find(field), std::string::npos) << field << " in " << l;
    const std::string key = l.substr(l.find("\"key\": \"") + 8, 16);
    EXPECT_NE(l.find("--job " + key), std::string::npos) << l;
    EXPECT_NE(l.find(" --only '"), std::string::npos) << "each job plans only itself: " << l;
    EXPECT_NE(l.find(key), l.rfind(key)) << "the output is named by the key: " << l;
    probes += l.find("\"technique\": \"probes\"") != std::string::npos;
    dnrt += l.find("\"technique\": \"dnrt\"") != std::string::npos;
  }
  EXPECT_EQ(probes, 1);
  EXPECT_EQ(dnrt, 2);
  EXPECT_TRUE(entries(dir_ / "cache").empty()) << "listing bakes nothing";
}

TEST_F(BakeCli, NinjaPlanGivesByteIdenticalEntriesToAPlainBake) {
  const Outcome plain = bounce(dir_ / "plain", {"bake", kTiny.string()});
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(lines(plain.out).size(), 3u) << plain.out;

  const fs::path plan = dir_ / "planned" / "bake.ninja";
  fs::create_directories(plan.parent_path());
  const Outcome wrote = bounce(dir_ / "planned", {"bake", kTiny.string(), "--plan", plan.string()});
  ASSERT_EQ(wrote.code, 0) << wrote.err;
  EXPECT_EQ(wrote.out, "3 bake job(s) -> " + plan.string() + "\n");
  EXPECT_TRUE(entries(dir_ / "planned").empty()) << "planning bakes nothing";
  // The plan carries its own BOUNCE_CACHE: ninja's environment does not matter.
  const Outcome ran = sh("cd " + quote(plan.parent_path().string()) + " && ninja -f bake.ninja -j2", "ninja");
  ASSERT_EQ(ran.code, 0) << ran.out << ran.err;

  const auto a = entries(dir_ / "plain"), b = entries(dir_ / "planned");
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), a.size());
  for (const auto& [name, bytes] : a) {
    ASSERT_TRUE(b.count(name)) << name << " missing from the ninja run";
    EXPECT_TRUE(b.at(name) == bytes) << name << " differs";
  }
  // Everything is up to date now: ninja has nothing left to do.
  const Outcome again = sh("cd " + quote(plan.parent_path().string()) + " && ninja -f bake.ninja -j2 -n", "ninja2");
  EXPECT_NE(again.out.find("no work to do"), std::string::npos) << again.out;
}

TEST_F(BakeCli, AJobRunTwiceIsACacheHit) {
  const fs::path root = dir_ / "cache";
  const auto ks = keys(root);
  ASSERT_EQ(ks.size(), 3u);
  for (const auto& key : ks) {
    const Outcome first = bounce(root, {"bake", kTiny.string(), "--job", key});
    ASSERT_EQ(first.code, 0) << first.err;
    ASSERT_EQ(lines(first.out).size(), 1u) << first.out;
    EXPECT_EQ(first.out.find(": cached "), std::string::npos) << first.out;
    const auto before = entries(root);
    const Outcome second = bounce(root, {"bake", kTiny.string(), "--job", key});
    ASSERT_EQ(second.code, 0) << second.err;
    EXPECT_NE(second.out.find(": cached "), std::string::npos) << second.out;
    EXPECT_EQ(entries(root), before) << "a cache hit writes nothing";
  }
  EXPECT_EQ(entries(root).size(), 3u);
}

TEST_F(BakeCli, CorruptOrTruncatedEntriesAreReBaked) {
  const fs::path root = dir_ / "cache";
  ASSERT_EQ(bounce(root, {"bake", kTiny.string()}).code, 0);
  const auto good = entries(root);
  ASSERT_EQ(good.size(), 3u);
  // Truncate one entry, flip one byte in the middle of each other one.
  int n = 0;
  for (const auto& [name, bytes] : good) {
    std::string bad = bytes;
    if (n++ == 0)
      bad.resize(bad.size() / 2);
    else
      bad[bad.size() / 2] = char(bad[bad.size() / 2] ^ 0x10);
    std::ofstream(root / name, std::ios::binary | std::ios::trunc) << bad;
  }
  const Outcome r = bounce(root, {"bake", kTiny.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const auto& line : lines(r.out)) EXPECT_EQ(line.find(": cached "), std::string::npos) << line;
  const auto errLines = lines(r.err);
  EXPECT_EQ(std::count_if(errLines.begin(), errLines.end(), [](const std::string& l) { return l.rfind("warning: ", 0) == 0; }),
            3)
      << "one warning per corrupt entry:\n"
      << r.err;
  EXPECT_EQ(entries(root), good) << "re-baked entries equal the originals (deterministic bakes)";
}

// A DNRT field is rigid: on a skinned or morphed mesh it is baked in the bind pose (issue 12, item 4). The
// bake says so once, for that object only, and still writes the entry; a rigid box gets no warning.
// Two entities, one mesh and one field setting: one job, one field entry. The first keeps the lights
// in its anti-radiance, the second leaves them out, so the shared job must also bake the
// occlusion-only field, whichever entity comes first, and declare it to Ninja (an implicit output).
TEST_F(BakeCli, SharedFieldJobBakesTheOcclusionFieldIfAnyEntityNeedsIt) {
  const fs::path level = kSource / "tests/data/gi/bake-shared-mesh.json";
  const fs::path root = dir_ / "cache";
  const Outcome listed = bounce(root, {"bake", level.string(), "--list-jobs"});
  ASSERT_EQ(listed.code, 0) << listed.err;
  ASSERT_EQ(lines(listed.out).size(), 1u) << listed.out;
  EXPECT_NE(listed.out.find("\"what\": \"dnrt box-a + occlusion (also dnrt box-b)\""), std::string::npos) << listed.out;
  // --only dnrt:box-b plans the same job (the group box-b is in).
  const Outcome onlyB = bounce(root, {"bake", level.string(), "--list-jobs", "--only", "dnrt:box-b"});
  ASSERT_EQ(onlyB.code, 0) << onlyB.err;
  EXPECT_EQ(onlyB.out, listed.out);

  const fs::path plan = root / "bake.ninja";
  fs::create_directories(root);
  const Outcome wrote = bounce(root, {"bake", level.string(), "--plan", plan.string()});
  ASSERT_EQ(wrote.code, 0) << wrote.err;
  std::vector<std::string> edges;
  for (const auto& l : lines(readText(plan)))
    if (l.rfind("build ", 0) == 0 && l.find(": bake") != std::string::npos) edges.push_back(l);
  ASSERT_EQ(edges.size(), 1u) << readText(plan);
  const std::string& edge = edges[0];
  const auto bar = edge.find(" | "), colon = edge.find(": bake");
  ASSERT_NE(bar, std::string::npos) << "the occlusion entry is an implicit output: " << edge;
  const fs::path field = edge.substr(6, bar - 6), occlusion = edge.substr(bar + 3, colon - bar - 3);
  EXPECT_EQ(field.parent_path(), root / "dnrt");
  EXPECT_EQ(occlusion.parent_path(), root / "dnrt");
  EXPECT_NE(field, occlusion);

  const Outcome ran = sh("cd " + quote(root.string()) + " && ninja -f bake.ninja -j2", "ninja");
  ASSERT_EQ(ran.code, 0) << ran.out << ran.err;
  EXPECT_TRUE(fs::is_regular_file(field));
  EXPECT_TRUE(fs::is_regular_file(occlusion));
  EXPECT_EQ(entries(root).size(), 2u);
  // Removing only the occlusion entry makes the edge dirty again (Ninja knows the output).
  fs::remove(occlusion);
  const Outcome again = sh("cd " + quote(root.string()) + " && ninja -f bake.ninja -j2 -n", "ninja2");
  EXPECT_EQ(again.out.find("no work to do"), std::string::npos) << again.out;
}

TEST_F(BakeCli, DnrtOnASkinnedMeshWarnsThatItsFieldIsTheBindPose) {
  const fs::path root = dir_ / "cache";
  const fs::path level = kSource / "tests/data/gi/bake-skinned.json";
  const Outcome r = bounce(root, {"bake", level.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto errLines = lines(r.err);
  ASSERT_EQ(errLines.size(), 1u) << r.err;
  EXPECT_EQ(errLines[0],
            "warning: dnrt arm: the mesh is skinned or morphed; its DNRT field is baked in the bind pose and does "
            "not follow the animation");
  EXPECT_EQ(entries(root).size(), 2u) << "both fields are written";
  const Outcome again = bounce(root, {"bake", level.string()});
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(again.err, "") << "a cache hit decodes nothing, so it does not warn again";
}

TEST_F(BakeCli, TwoProcessesBakingOneKeyLeaveOneValidEntry) {
  const fs::path root = dir_ / "cache";
  const auto ks = keys(root);
  ASSERT_FALSE(ks.empty());
  for (const auto& key : ks) {
    const std::string one = bounceCmd(root, {"bake", kTiny.string(), "--job", key});
    const Outcome both =
        sh(one + " & a=$!; " + one + " & b=$!; wait $a; ea=$?; wait $b; eb=$?; exit $((ea | eb))", "both-" + key);
    ASSERT_EQ(both.code, 0) << both.out << both.err;
    const Outcome check = bounce(root, {"bake", kTiny.string(), "--job", key});
    EXPECT_NE(check.out.find(": cached "), std::string::npos) << "the entry left is valid: " << check.out << check.err;
  }
  EXPECT_EQ(entries(root).size(), ks.size()) << "one entry per key, no temporary file left";
}

TEST_F(BakeCli, RtfWithoutParticipantsSaysSoInOneLine) {
  const Outcome r = bounce(dir_ / "cache", {"bake", kTiny.string(), "--effects", "direct,rtf"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "note: effect rtf is named but no entity takes part (no entity has an rtf component): no pass\n");
  EXPECT_EQ(r.out, "nothing to bake: no entity takes part in the effects that bake\n");
}

TEST_F(BakeCli, EffectWithoutParticipantsSaysSoInOneLine) {
  const Outcome r = bounce(dir_ / "cache", {"bake", kTiny.string(), "--effects", "direct,vlm"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.err,
            "note: effect vlm is named but no entity takes part (no entity has a vlm component or a mesh with "
            "extras.bounce_vlm): no pass\n");
}

TEST_F(BakeCli, UnknownJobKeyIsBadInput) {
  const Outcome r = bounce(dir_ / "cache", {"bake", kTiny.string(), "--job", "0123456789abcdef"});
  EXPECT_EQ(r.code, 2);
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("bake-tiny.json: --job: no bake job has key 0123456789abcdef (expected one of: "),
            std::string::npos)
      << r.err;
}

TEST_F(BakeCli, OnlyNamesATechniqueOfTheTable) {
  const Outcome r = bounce(dir_ / "cache", {"bake", kTiny.string(), "--only", "bloom", "--list-jobs"});
  EXPECT_EQ(r.code, 2);
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("bake-tiny.json: --only: no technique bloom (expected TECHNIQUE or TECHNIQUE:PART"),
            std::string::npos)
      << r.err;
  const Outcome one = bounce(dir_ / "cache", {"bake", kTiny.string(), "--only", "dnrt:box-b", "--list-jobs"});
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(lines(one.out).size(), 1u) << one.out;
  EXPECT_NE(one.out.find("\"what\": \"dnrt box-b\""), std::string::npos) << one.out;
}

TEST_F(BakeCli, CacheStatsAndPrune) {
  const fs::path root = dir_ / "cache";
  ASSERT_EQ(bounce(root, {"bake", kTiny.string()}).code, 0);
  std::ofstream(root / "probes" / "0000000000000000.bin") << "stale";  // referenced by no level
  std::ofstream(root / "dnrt" / "dnrt-0000000000000000.field.tmp-1") << "left by a killed job";
  const Outcome stats = bounce(root, {"cache", "--stats"});
  ASSERT_EQ(stats.code, 0) << stats.err;
  EXPECT_NE(stats.out.find("\nprobes              2 "), std::string::npos) << stats.out;
  EXPECT_NE(stats.out.find("\ndnrt                3 "), std::string::npos) << stats.out;
  const Outcome prune = bounce(root, {"cache", "--prune", kTiny.string()});
  ASSERT_EQ(prune.code, 0) << prune.err;
  EXPECT_EQ(prune.out.rfind("pruned 2 entries", 0), 0u) << prune.out;
  EXPECT_EQ(entries(root).size(), 3u);
  EXPECT_EQ(bounce(root, {"cache", "--stats", "--prune"}).code, 2);
}

// Issue 11: the references `bounce accuracy` traces are bake jobs too, planned with --only
// reference (a level names no accuracy run): one per reference kind the rows use (direct, 1bounce,
// all), with and without the dynamic objects, and the half-sample ones of the noise estimate; a job
// run twice is a cache hit, a corrupt entry is traced again.
TEST_F(BakeCli, ReferencesAreJobsWithOnlyReference) {
  const fs::path root = dir_ / "cache";
  const Outcome techniques = bounce(root, {"bake", kTiny.string(), "--list-jobs"});
  EXPECT_EQ(techniques.out.find("\"technique\": \"reference\""), std::string::npos) << techniques.out;
  const Outcome r = bounce(root, {"bake", kTiny.string(), "--only", "reference", "--list-jobs"});
  ASSERT_EQ(r.code, 0) << r.err;
  std::set<std::string> whats, keysSeen;
  std::string directKey;
  for (const auto& l : lines(r.out)) {
    EXPECT_NE(l.find("\"technique\": \"reference\""), std::string::npos) << l;
    const std::string key = l.substr(l.find("\"key\": \"") + 8, 16);
    EXPECT_TRUE(keysSeen.insert(key).second) << "duplicate key in " << l;
    EXPECT_NE(l.find("\"output\": \"" + (root / "reference" / (key + ".pfm")).string() + "\""), std::string::npos) << l;
    const auto at = l.find("\"what\": \"reference ") + 19;
    whats.insert(l.substr(at, l.find('"', at) - at));
    if (l.find("\"what\": \"reference direct\"") != std::string::npos) directKey = key;
  }
  EXPECT_EQ(whats, (std::set<std::string>{"direct", "direct-static", "1bounce", "1bounce-static", "1bounce-half", "all",
                                          "all-static", "all-half", "1bounce-static-half", "all-static-half"}));
  ASSERT_EQ(directKey.size(), 16u);
  EXPECT_TRUE(!fs::exists(root / "reference") || fs::is_empty(root / "reference")) << "planning traces nothing";

  // The direct-only reference (1 spp: exact, and quick): traced once, then a cache hit.
  const std::vector<std::string> job = {"bake", kTiny.string(), "--only", "reference:direct", "--job", directKey};
  const Outcome first = bounce(root, job);
  ASSERT_EQ(first.code, 0) << first.err;
  EXPECT_EQ(first.out.find(": cached "), std::string::npos) << first.out;
  const fs::path entry = root / "reference" / (directKey + ".pfm");
  ASSERT_TRUE(fs::exists(entry));
  const std::string bytes = readText(entry);
  const Outcome second = bounce(root, job);
  EXPECT_EQ(second.out, "reference direct: cached " + entry.string() + "\n") << second.err;
  std::ofstream(entry, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
  const Outcome again = bounce(root, job);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(again.out.find(": cached "), std::string::npos) << "a truncated entry is traced again: " << again.out;
  EXPECT_TRUE(readText(entry) == bytes) << "the same image again (deterministic tracer)";
}

// Issue 11: `cache --prune` also drops cooked assets no level uses (in <root>/cooked) and
// references no level's reference job names, and keeps the ones they name.
TEST_F(BakeCli, PruneConsidersCookedAssetsAndReferences) {
  const fs::path root = dir_ / "cache";
  const std::string ownCook = "BOUNCE_CACHE=" + quote(root.string()) + " BOUNCE_COOK_CACHE=" + quote((root / "cooked").string()) + " ";
  auto run = [&](const std::vector<std::string>& args) { return sh(bounce::testcli::bounceCommand(args, ownCook)); };
  const Outcome listed = run({"bake", kTiny.string(), "--only", "reference:direct", "--list-jobs"});
  ASSERT_EQ(listed.code, 0) << listed.err;
  const std::string key = listed.out.substr(listed.out.find("\"key\": \"") + 8, 16);
  ASSERT_EQ(run({"bake", kTiny.string(), "--only", "reference:direct", "--job", key}).code, 0);
  std::set<std::string> cooked;
  for (const auto& f : fs::directory_iterator(root / "cooked")) cooked.insert(f.path().filename().string());
  ASSERT_FALSE(cooked.empty()) << "the job cooked the level's assets into <root>/cooked";
  std::ofstream(root / "cooked" / "0000000000000000.bcook") << "no level uses it";
  std::ofstream(root / "reference" / "0000000000000000.pfm") << "no job names it";
  const Outcome prune = run({"cache", "--prune", kTiny.string()});
  ASSERT_EQ(prune.code, 0) << prune.err;
  EXPECT_EQ(prune.out.rfind("pruned 2 entries", 0), 0u) << prune.out;
  EXPECT_FALSE(fs::exists(root / "cooked" / "0000000000000000.bcook"));
  EXPECT_FALSE(fs::exists(root / "reference" / "0000000000000000.pfm"));
  EXPECT_TRUE(fs::exists(root / "reference" / (key + ".pfm")));
  std::set<std::string> after;
  for (const auto& f : fs::directory_iterator(root / "cooked")) after.insert(f.path().filename().string());
  EXPECT_EQ(after, cooked) << "the cooks the level uses are kept";
}

}  // namespace
