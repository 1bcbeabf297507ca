#version 450
#extension GL_GOOGLE_include_directive : require
// RTF shading (engine/gi/rtf/node.hpp): one object's box, centre o, half-size (outer + Δr)·η —
// where its field is non-zero — from gl_VertexIndex (36 vertices, outward CCW, as dnrt.vert's box);
// the pipeline culls FRONT faces without a depth test, so each covered pixel runs once.
// The object's record and its X ranges are read here, once per vertex, and reach rtf.frag as flat
// varyings with the grid's constants folded: flat varyings cost llvmpipe's fragment shader less than
// uniform-block reads (DESIGN.md "What costs what in a fragment shader"; dnrt.vert does the same).
#include "frame.glsl"
#include "rtf/object.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 2, binding = 0) uniform ObjectUbo { RtfObject ob; };
layout(set = 2, binding = 2) uniform NetRange { vec4 range[7]; };  // xi.comp: m per slot of X's 8-bit texels

layout(location = 0) flat out vec4 outToQ[3];
layout(location = 3) flat out vec4 outToLocal[3];
layout(location = 6) flat out vec4 outRadial;  // inner (η), 1/Δr, spheres − 1, outer (η)
layout(location = 7) flat out vec4 outFace;    // n_r, 1/(6 n_r), 1/n_r, 1/(7 · spheres)
layout(location = 8) flat out vec4 outRange[7];
layout(location = 15) flat out uint outSelf;

const int kFaces[6][4] = int[6][4](int[4](1, 3, 7, 5), int[4](0, 4, 6, 2), int[4](2, 6, 7, 3),
                                   int[4](0, 1, 5, 4), int[4](4, 5, 7, 6), int[4](0, 2, 3, 1));
const int kQuad[6] = int[6](0, 1, 2, 0, 2, 3);

void main() {
  outToQ = ob.toQ;
  outToLocal = ob.toLocal;
  float spheres = ob.grid.x, n = ob.grid.y, inner = ob.grid.z, outer = ob.grid.w;
  outRadial = vec4(inner, (spheres - 1.0) / (outer - inner), spheres - 1.0, outer);
  outFace = vec4(n, 1.0 / (6.0 * n), 1.0 / n, 1.0 / (7.0 * spheres));
  outRange = range;
  outSelf = ob.ids.x;
  int corner = kFaces[gl_VertexIndex / 6][kQuad[gl_VertexIndex % 6]];
  vec3 p = vec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1) * 2.0 - 1.0;
  gl_Position = camera.viewProj * vec4(ob.centreWorld.xyz + ob.centreWorld.w * p, 1.0);
}
