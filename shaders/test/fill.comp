#version 450
// Test shader: v[i] = a·i² + b for i < count (engine/gpu compute test). With a = 0.5, b = 3 and
// i < 2048 every value is exact in float32.
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) buffer Out { float v[]; };
layout(push_constant) uniform Push {
  uint count;
  float a;
  float b;
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  float x = float(i);
  v[i] = pc.a * x * x + pc.b;
}
