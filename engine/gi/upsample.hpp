#pragma once
// C++ reference of the edge-aware upsample of a reduced-resolution irradiance target
// (shaders/common/upsample.glsl, the same operations in the same order, in double), shared by SL pass 2
// ("sl.half" / "sl.quarter", shaders/sl/upsample.frag) and DNRT and RTF at reduced resolution
// ("dnrt.half" / "dnrt.quarter", "rtf.half" / "rtf.quarter": shaders/passes/reduced_upsample.frag): the
// reduced target holds E at G-buffer pixel step·j (engine/gi/resolution.hpp); a full-resolution
// pixel blends its 4 nearest samples with bilinear weights times a receiver match —
// exp(−(|n·(p_q − p)| / (eye · kUpsamplePlaneScale))²), the sample's distance from this pixel's tangent
// plane relative to the eye distance, times max(0, n·n_q)^8 —
// so light does not cross depth or crease edges; all samples rejected (Σ weight ≤ kUpsampleMinWeight):
// the best-matching sample alone. Tests: tests/unit/sl/upsample_gpu_test.cpp (GLSL = this).
#include <array>

#include <glm/glm.hpp>

namespace bounce::gi {

inline constexpr double kUpsamplePlaneScale = 0.01;  // upsample.glsl kUpPlaneScale
inline constexpr double kUpsampleNormalPower = 8.0;  // kUpNormalPower
inline constexpr double kUpsampleMinWeight = 1e-4;   // kUpMinWeight

// upsampleTaps: the 4 reduced samples j (clamped to `reduced`), the G-buffer pixels q = min(step·j,
// full − 1) they hold, and the bilinear fractions f = (pixel − step·⌊pixel/step⌋) / step.
struct UpsampleTaps {
  std::array<glm::ivec2, 4> j{}, q{};
  glm::dvec2 f{0.0};
};
UpsampleTaps upsampleTaps(glm::ivec2 pixel, int step, glm::ivec2 reduced, glm::ivec2 full);

// One tap's receiver and E.
struct UpsampleSample {
  glm::dvec3 p{0.0}, n{0.0, 0.0, 1.0};
  bool valid = true;  // false: background (depth 1), never matched
  glm::dvec3 e{0.0};  // W/m²
};
// upsampleMatch.
double upsampleMatch(const glm::dvec3& p, const glm::dvec3& n, double eye, const UpsampleSample& s);
// upsampleBlend: this pixel's receiver (p, n, eye distance) and f; taps in upsampleTaps' order.
glm::dvec3 upsampleBlend(const glm::dvec3& p, const glm::dvec3& n, double eye, glm::dvec2 f,
                         const std::array<UpsampleSample, 4>& taps);

}  // namespace bounce::gi
