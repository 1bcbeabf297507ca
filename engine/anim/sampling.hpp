#pragma once
// Sampling one glTF animation sampler at one time (glTF 2.0 §3.11, Appendix C), as a small job in
// ozz-animation's shape: fill the inputs and the output span, validate(), run().
//
//   float out[4];
//   anim::SamplingJob job{&sampler, t, anim::ValueKind::Rotation, out};
//   job.run();   // returns false (and writes nothing) when validate() fails
//
// Interpolation (t_k ≤ t < t_k+1, td = t_k+1 − t_k, s = (t − t_k) / td):
//   STEP         v_k
//   LINEAR       (1 − s)·v_k + s·v_k+1; rotations: slerp along the shorter arc, then normalised
//   CUBICSPLINE  Hermite with tangents scaled by td (spec Appendix C):
//                (2s³ − 3s² + 1)·v_k + td·(s³ − 2s² + s)·b_k + (−2s³ + 3s²)·v_k+1 + td·(s³ − s²)·a_k+1
//                with a = in-tangent, b = out-tangent; rotations normalised after.
// Before the first key the first value is held, after the last key the last one; a single-key
// sampler is constant. Times are seconds in the clip's own time line.
#include <cstddef>
#include <span>

#include "engine/asset/cooked_asset.hpp"

namespace bounce::anim {

// What the sampled values are: rotations (x, y, z, w unit quaternions) are slerped and
// normalised; everything else (translation, scale, morph weights) is interpolated per component.
enum class ValueKind { Vector, Rotation };

struct SamplingJob {
  const asset::AnimationSampler* sampler = nullptr;
  float time = 0.0f;  // seconds
  ValueKind kind = ValueKind::Vector;
  std::span<float> output;  // sampler->components floats

  // A sampler with ≥ 1 key, matching output sizes (×3 for CUBICSPLINE), 4 components for a
  // rotation, and an output span of exactly `components` floats.
  bool validate() const;
  bool run() const;
};

// The clip's time span: the last key time over every sampler (0 for a clip without keys).
float clipDuration(const asset::Animation& clip);

}  // namespace bounce::anim
