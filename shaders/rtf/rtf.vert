#version 450
#extension GL_GOOGLE_include_directive : require
// RTF shading (engine/gi/rtf/node.hpp): one object's box, centre o, half-size (outer + Δr)·η —
// where its field is non-zero — from gl_VertexIndex (36 vertices, outward CCW, as dnrt.vert's box);
// the pipeline culls FRONT faces without a depth test, so each covered pixel runs once.
#include "frame.glsl"
#include "rtf/object.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 2, binding = 0) uniform ObjectUbo { RtfObject ob; };

const int kFaces[6][4] = int[6][4](int[4](1, 3, 7, 5), int[4](0, 4, 6, 2), int[4](2, 6, 7, 3),
                                   int[4](0, 1, 5, 4), int[4](4, 5, 7, 6), int[4](0, 2, 3, 1));
const int kQuad[6] = int[6](0, 1, 2, 0, 2, 3);

void main() {
  int corner = kFaces[gl_VertexIndex / 6][kQuad[gl_VertexIndex % 6]];
  vec3 p = vec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1) * 2.0 - 1.0;
  gl_Position = camera.viewProj * vec4(ob.centreWorld.xyz + ob.centreWorld.w * p, 1.0);
}
