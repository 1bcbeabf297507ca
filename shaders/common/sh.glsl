// Real orthonormal spherical harmonics, the GPU mirror of engine/math/sh_eval.hpp and
// sh_convolve.hpp: same index i = l*(l+1)+m, same signs (no Condon–Shortley phase:
// Y_1,-1 = c*y, Y_1,0 = c*z, Y_1,1 = c*x), same constants. tests/unit/math compiles this file as
// C++ against glm and compares it with engine/math, so keep to the GLSL/C++ common subset:
// float literals with an f suffix, no swizzles, no array constructors, in/out only as qualifiers.
#ifndef BOUNCE_SH_GLSL
#define BOUNCE_SH_GLSL

const float SH_Y00 = 0.28209479177387814f;   // 1/(2√π)
const float SH_Y1 = 0.48860251190291992f;    // √(3/(4π))
const float SH_Y2A = 1.0925484305920792f;    // √(15/π)/2   (xy, yz, xz)
const float SH_Y20 = 0.31539156525252005f;   // √(5/π)/4    (3z²-1)
const float SH_Y22 = 0.54627421529603959f;   // √(15/π)/4   (x²-y²)
const float SH_Y33 = 0.59004358992664352f;   // √(35/(2π))/4
const float SH_Y32A = 2.8906114426405538f;   // √(105/π)/2  (xyz)
const float SH_Y31 = 0.45704579946446572f;   // √(21/(2π))/4
const float SH_Y30 = 0.37317633259011546f;   // √(7/π)/4
const float SH_Y32B = 1.4453057213202769f;   // √(105/π)/4  (z(x²-y²))

// Clamped-cosine convolution factors Â_l (E(n) = Σ Â_l L_lm Y_lm(n)); Â_3 = 0.
const float SH_A0 = 3.14159265358979324f;    // π
const float SH_A1 = 2.09439510239319549f;    // 2π/3
const float SH_A2 = 0.78539816339744831f;    // π/4

// Basis values at unit direction d, orders 1..4 (1, 4, 9, 16 values).
void shEval4(vec3 d, out float y[4]) {
  y[0] = SH_Y00;
  y[1] = SH_Y1 * d.y;
  y[2] = SH_Y1 * d.z;
  y[3] = SH_Y1 * d.x;
}

void shEval9(vec3 d, out float y[9]) {
  float x = d.x;
  float yy = d.y;
  float z = d.z;
  y[0] = SH_Y00;
  y[1] = SH_Y1 * yy;
  y[2] = SH_Y1 * z;
  y[3] = SH_Y1 * x;
  y[4] = SH_Y2A * x * yy;
  y[5] = SH_Y2A * yy * z;
  y[6] = SH_Y20 * (3.0f * z * z - 1.0f);
  y[7] = SH_Y2A * x * z;
  y[8] = SH_Y22 * (x * x - yy * yy);
}

void shEval16(vec3 d, out float y[16]) {
  float x = d.x;
  float yy = d.y;
  float z = d.z;
  float x2 = x * x;
  float y2 = yy * yy;
  float z2 = z * z;
  y[0] = SH_Y00;
  y[1] = SH_Y1 * yy;
  y[2] = SH_Y1 * z;
  y[3] = SH_Y1 * x;
  y[4] = SH_Y2A * x * yy;
  y[5] = SH_Y2A * yy * z;
  y[6] = SH_Y20 * (3.0f * z2 - 1.0f);
  y[7] = SH_Y2A * x * z;
  y[8] = SH_Y22 * (x2 - y2);
  y[9] = SH_Y33 * yy * (3.0f * x2 - y2);
  y[10] = SH_Y32A * x * yy * z;
  y[11] = SH_Y31 * yy * (5.0f * z2 - 1.0f);
  y[12] = SH_Y30 * z * (5.0f * z2 - 3.0f);
  y[13] = SH_Y31 * x * (5.0f * z2 - 1.0f);
  y[14] = SH_Y32B * z * (x2 - y2);
  y[15] = SH_Y33 * x * (x2 - 3.0f * y2);
}

// f(d) = Σ c_i Y_i(d), RGB coefficients.
vec3 shEvalSum4(in vec3 c[4], vec3 d) {
  float y[4];
  shEval4(d, y);
  vec3 sum = vec3(0.0f);
  for (int i = 0; i < 4; ++i) sum += c[i] * y[i];
  return sum;
}

vec3 shEvalSum9(in vec3 c[9], vec3 d) {
  float y[9];
  shEval9(d, y);
  vec3 sum = vec3(0.0f);
  for (int i = 0; i < 9; ++i) sum += c[i] * y[i];
  return sum;
}

vec3 shEvalSum16(in vec3 c[16], vec3 d) {
  float y[16];
  shEval16(d, y);
  vec3 sum = vec3(0.0f);
  for (int i = 0; i < 16; ++i) sum += c[i] * y[i];
  return sum;
}

// Irradiance E(n) = Σ Â_l L_lm Y_lm(n) from RADIANCE coefficients L (RGB), n unit length.
vec3 shIrradiance4(in vec3 L[4], vec3 n) {
  float y[4];
  shEval4(n, y);
  vec3 e = L[0] * (SH_A0 * y[0]);
  for (int i = 1; i < 4; ++i) e += L[i] * (SH_A1 * y[i]);
  return e;
}

vec3 shIrradiance9(in vec3 L[9], vec3 n) {
  float y[9];
  shEval9(n, y);
  vec3 e = L[0] * (SH_A0 * y[0]);
  for (int i = 1; i < 4; ++i) e += L[i] * (SH_A1 * y[i]);
  for (int i = 4; i < 9; ++i) e += L[i] * (SH_A2 * y[i]);
  return e;
}

// Band 3 of radiance does not reach irradiance (Â_3 = 0), so 16 coefficients give exactly the
// 9-coefficient result; this overload only saves callers a copy.
vec3 shIrradiance16(in vec3 L[16], vec3 n) {
  float y[9];
  shEval9(n, y);
  vec3 e = L[0] * (SH_A0 * y[0]);
  for (int i = 1; i < 4; ++i) e += L[i] * (SH_A1 * y[i]);
  for (int i = 4; i < 9; ++i) e += L[i] * (SH_A2 * y[i]);
  return e;
}

#endif  // BOUNCE_SH_GLSL
