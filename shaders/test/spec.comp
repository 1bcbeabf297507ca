#version 450
// Test shader for specialization constants (engine/gpu compute test): v[i] = sign · (i + kAdd) for
// i < 64, sign = −1 when kNegate. Unspecialised: v[i] = i.
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kAdd = 0u;
layout(constant_id = 1) const bool kNegate = false;
layout(std430, set = 0, binding = 0) buffer Out { float v[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  float x = float(i + kAdd);
  v[i] = kNegate ? -x : x;
}
