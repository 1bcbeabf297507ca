// shaders/sl/gaunt.glsl (pass 2's unrolled SH square for the hybrid exp's squarings) is generated
// from sh::gauntTensor(), the one SH product of engine/math: this test regenerates the text and
// requires the file to be identical, so the shader cannot drift from the library. To regenerate
// after a change of the tensor: BOUNCE_UPDATE_GAUNT=1 ctest --preset release -R SlGauntGlsl.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/math/sh_product.hpp"

using namespace bounce;

namespace {

std::string generate() {
  std::string out =
      "// GENERATED from sh::gauntTensor() (engine/math/sh_product.hpp) by tests/unit/sl/gaunt_glsl_test.cpp; do\n"
      "// not edit (BOUNCE_UPDATE_GAUNT=1 ctest --preset release -R SlGauntGlsl rewrites it).\n"
      "// h = the projection of g·g onto the first kSlCoeffs coefficients: h_k = Σ_ij C_ijk g_i g_j, each unordered\n"
      "// pair {i, j} once (i ≤ j, ×2 when i < j), unrolled so g and h stay in registers. Needs kSlCoeffs (sl.glsl).\n"
      "void slSquare(in float g[16], out float h[16]) {\n"
      "  for (int i = 0; i < 16; ++i) h[i] = 0.0;\n";
  std::string order3, order4;
  char line[160];
  for (const sh::GauntEntry& e : sh::gauntTensor()) {
    if (e.i > e.j) continue;
    const double c = e.value * (e.i == e.j ? 1.0 : 2.0);
    std::snprintf(line, sizeof line, "  h[%d] += %.9e * g[%d] * g[%d];\n", int(e.k), c, int(e.i), int(e.j));
    (e.i < 9 && e.j < 9 && e.k < 9 ? order3 : order4) += line;
  }
  out += order3;
  out += "  if (kSlCoeffs > 9u) {\n";
  std::istringstream in(order4);
  for (std::string l; std::getline(in, l);) out += "  " + l + "\n";
  out += "  }\n}\n";

  // The shadow on the probes' light (shaders/sl/probe_shadow.glsl): a visibility v (kSlCoeffs) times a
  // band-limited c (order 3), projected onto order 3.
  out +=
      "\n// p = the projection of v·c onto the first 9 coefficients for v with kSlCoeffs and c with 9 coefficients:\n"
      "// p_k = Σ_ij C_ijk v_i c_j (sl/probe_shadow.glsl: the visibility times the clamped cosine).\n"
      "void slProduct9(in float v[16], in float c[9], out float p[9]) {\n"
      "  for (int i = 0; i < 9; ++i) p[i] = 0.0;\n";
  std::string low, high;
  for (const sh::GauntEntry& e : sh::gauntTensor()) {
    if (e.k >= 9 || e.j >= 9) continue;
    std::snprintf(line, sizeof line, "  p[%d] += %.9e * v[%d] * c[%d];\n", int(e.k), e.value, int(e.i), int(e.j));
    (e.i < 9 ? low : high) += line;
  }
  out += low;
  out += "  if (kSlCoeffs > 9u) {\n";
  std::istringstream in2(high);
  for (std::string l; std::getline(in2, l);) out += "  " + l + "\n";
  out += "  }\n}\n";
  return out;
}

}  // namespace

TEST(SlGauntGlsl, GeneratedShaderMatchesTheLibraryTensor) {
  const std::filesystem::path file = std::filesystem::path(BOUNCE_SOURCE_DIR) / "shaders/sl/gaunt.glsl";
  const std::string want = generate();
  const char* update = std::getenv("BOUNCE_UPDATE_GAUNT");
  if (update && std::string(update) == "1") {
    std::ofstream(file, std::ios::binary) << want;
    GTEST_SKIP() << "rewrote " << file;
  }
  std::ifstream f(file, std::ios::binary);
  ASSERT_TRUE(f.good()) << file;
  std::stringstream got;
  got << f.rdbuf();
  EXPECT_EQ(got.str(), want) << file << " is stale: regenerate with BOUNCE_UPDATE_GAUNT=1";
}
