#include "engine/anim/sampling.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace bounce::anim {

namespace {

glm::quat quatAt(const float* p) { return glm::quat(p[3], p[0], p[1], p[2]); }  // glTF x, y, z, w
void store(const glm::quat& q, float* out) {
  out[0] = q.x;
  out[1] = q.y;
  out[2] = q.z;
  out[3] = q.w;
}

void normalizeQuat(float* q) {
  const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (len > 0.0f)
    for (int i = 0; i < 4; ++i) q[i] /= len;
}

// Spherical linear interpolation along the shorter arc (glTF Appendix C's reference): nearly
// parallel quaternions fall back to a normalised lerp, where slerp's sin θ would divide by ~0.
glm::quat slerpShort(glm::quat a, glm::quat b, float s) {
  float d = glm::dot(a, b);
  if (d < 0.0f) {
    b = -b;
    d = -d;
  }
  constexpr float kLerpAbove = 0.9995f;  // cos of ~1.8°: lerp error below fp32 resolution there
  if (d > kLerpAbove) return glm::normalize(a * (1.0f - s) + b * s);
  const float theta = std::acos(d);
  const float sinTheta = std::sin(theta);
  return glm::normalize(a * (std::sin((1.0f - s) * theta) / sinTheta) + b * (std::sin(s * theta) / sinTheta));
}

}  // namespace

bool SamplingJob::validate() const {
  if (!sampler || sampler->input.empty() || sampler->components == 0) return false;
  const std::size_t perKey = sampler->interpolation == asset::Interpolation::CubicSpline ? 3 : 1;
  if (sampler->output.size() != sampler->input.size() * perKey * sampler->components) return false;
  if (kind == ValueKind::Rotation && sampler->components != 4) return false;
  return output.size() == sampler->components && std::isfinite(time);
}

bool SamplingJob::run() const {
  if (!validate()) return false;
  const auto& in = sampler->input;
  const std::size_t n = sampler->components;
  const bool cubic = sampler->interpolation == asset::Interpolation::CubicSpline;
  const std::size_t stride = cubic ? 3 * n : n;            // floats per key
  const std::size_t valueOffset = cubic ? n : 0;           // the value sits after the in-tangent
  const float* out = sampler->output.data();
  auto value = [&](std::size_t key) { return out + key * stride + valueOffset; };

  // Hold the first / last value outside the keys (and for a single key).
  if (in.size() == 1 || time <= in.front()) {
    std::copy_n(value(0), n, output.data());
    return true;
  }
  if (time >= in.back()) {
    std::copy_n(value(in.size() - 1), n, output.data());
    return true;
  }
  // k: the last key with t_k ≤ time (in.front() < time < in.back() here, so 0 ≤ k < size − 1).
  const std::size_t k = std::size_t(std::upper_bound(in.begin(), in.end(), time) - in.begin()) - 1;
  const float td = in[k + 1] - in[k];
  const float s = (time - in[k]) / td;
  switch (sampler->interpolation) {
    case asset::Interpolation::Step:
      std::copy_n(value(k), n, output.data());
      return true;
    case asset::Interpolation::Linear:
      if (kind == ValueKind::Rotation) {
        store(slerpShort(quatAt(value(k)), quatAt(value(k + 1)), s), output.data());
      } else {
        for (std::size_t c = 0; c < n; ++c) output[c] = (1.0f - s) * value(k)[c] + s * value(k + 1)[c];
      }
      return true;
    case asset::Interpolation::CubicSpline: {
      const float s2 = s * s, s3 = s2 * s;
      const float h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
      const float* outTangent = out + k * stride + 2 * n;  // b_k
      const float* inTangent = out + (k + 1) * stride;     // a_k+1
      for (std::size_t c = 0; c < n; ++c)
        output[c] = h00 * value(k)[c] + td * h10 * outTangent[c] + h01 * value(k + 1)[c] + td * h11 * inTangent[c];
      if (kind == ValueKind::Rotation) normalizeQuat(output.data());
      return true;
    }
  }
  return false;
}

float clipDuration(const asset::Animation& clip) {
  float d = 0.0f;
  for (const auto& s : clip.samplers)
    if (!s.input.empty()) d = std::max(d, s.input.back());
  return d;
}

}  // namespace bounce::anim
