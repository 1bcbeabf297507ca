#version 450
// The GPU face of engine/anim/subdivision.cpp (LimitStencilJob; tests/unit/skinning holds the two
// equal): a subdivided deformed mesh's limit stencils (OpenSubdiv, built once at cook time)
// evaluated on its cage as the skinning pass just posed it, once per frame per instance, into the
// same posed-vertex buffer every raster pass reads. For refined vertex v and its weights k:
//   S = Σ w_k·P[i_k],  ∂S/∂u = Σ wu_k·P[i_k],  ∂S/∂v = Σ wv_k·P[i_k]
//   N = normalize(∂S/∂u × ∂S/∂v), or normalize(Σ w_k·N[i_k]) where the tangents are parallel
//       (|∂S/∂u × ∂S/∂v| ≤ kParallelTangents·|∂S/∂u|·|∂S/∂v|, kParallelTangents as on the CPU)
layout(local_size_x = 64) in;

// MeshVertex, 8 floats: position, normal, uv. The cage is read from srcBase, the refined vertices
// written from dstBase (disjoint ranges of the one buffer).
layout(std430, set = 0, binding = 0) buffer Posed { float posed[]; };
// Per refined vertex: first weight, weight count, u, v (uv as uint bits).
layout(std430, set = 0, binding = 1) readonly buffer Rows { uvec4 rows[]; };
// Per weight: cage vertex (mesh-wide), then w, wu, wv as float bits.
layout(std430, set = 0, binding = 2) readonly buffer Weights { uvec4 weights[]; };

layout(push_constant) uniform Push {
  uint vertexCount;  // refined vertices of this mesh
  uint srcBase;      // this instance's first posed cage vertex in `posed`
  uint dstBase;      // this instance's first refined vertex in `posed`
} pc;

const float kParallelTangents = 1e-6;

void main() {
  const uint v = gl_GlobalInvocationID.x;
  if (v >= pc.vertexCount) return;
  const uvec4 row = rows[v];
  vec3 s = vec3(0.0), du = vec3(0.0), dv = vec3(0.0), n = vec3(0.0);
  // do…while with a guarded body: llvmpipe runs a `for` body once more with every lane masked
  // (README "Loop bodies III"), so a row of n weights costs n bodies, not n + 1.
  uint k = row.x;
  do {
    if (k < row.x + row.y) {
      const uvec4 e = weights[k];
      const uint o = (pc.srcBase + e.x) * 8u;
      const vec3 p = vec3(posed[o + 0], posed[o + 1], posed[o + 2]);
      const float w = uintBitsToFloat(e.y);
      s += w * p;
      du += uintBitsToFloat(e.z) * p;
      dv += uintBitsToFloat(e.w) * p;
      n += w * vec3(posed[o + 3], posed[o + 4], posed[o + 5]);
    }
    ++k;
  } while (k < row.x + row.y);
  const vec3 c = cross(du, dv);
  const float len = length(c);
  if (len > kParallelTangents * length(du) * length(dv) && !isinf(len) && !isnan(len)) {
    n = c / len;
  } else {
    const float nl = length(n);
    n = nl > 0.0 ? n / nl : vec3(0.0, 1.0, 0.0);
  }
  const uint o = (pc.dstBase + v) * 8u;
  posed[o + 0] = s.x;
  posed[o + 1] = s.y;
  posed[o + 2] = s.z;
  posed[o + 3] = n.x;
  posed[o + 4] = n.y;
  posed[o + 5] = n.z;
  posed[o + 6] = uintBitsToFloat(row.z);
  posed[o + 7] = uintBitsToFloat(row.w);
}
