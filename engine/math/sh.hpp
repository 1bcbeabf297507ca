#pragma once
// The SH library in one include: evaluation, projection, rotation, cosine convolution, products,
// windowing. See sh_eval.hpp for the basis convention (shared with shaders/common/sh.glsl).
#include "engine/math/sh_convolve.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/math/sh_product.hpp"
#include "engine/math/sh_project.hpp"
#include "engine/math/sh_rotate.hpp"
#include "engine/math/sh_window.hpp"
