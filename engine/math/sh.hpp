#pragma once
// The SH library in one include: evaluation, projection, rotation, cosine convolution, products,
// windowing. See sh_eval.hpp for the basis convention (shared with shaders/common/sh.glsl).
//
// Precision: evaluation, rotation, convolution and products are templates over float and double
// (float for the renderer's CPU paths, double for tests and bakes). Projection (Monte Carlo,
// quadrature, cube map) and the window search (minimalWindow) always run in double: they sum
// thousands of texel or sample terms, and the bisection compares minima against a tolerance near
// 0, where float accumulation error (~1e-7 per term, growing with the count) would decide it.
#include "engine/math/sh_convolve.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/math/sh_product.hpp"
#include "engine/math/sh_project.hpp"
#include "engine/math/sh_rotate.hpp"
#include "engine/math/sh_window.hpp"
