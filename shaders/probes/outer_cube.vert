#version 450
#extension GL_GOOGLE_include_directive : require
// The probes pass drawn as DNRT's fused object's outer cube (probes node, FusedDnrt::split; README "DNRT's
// fused term only inside its outer cube, session 19"): the cube's 12 triangles from gl_VertexIndex, drawn
// twice with the G-buffer depth as a read-only attachment — by the fused pipeline where the pixel's surface
// is not behind the cube's face (GREATER_OR_EQUAL: it may be inside, the term is evaluated), by the plain
// pipeline where it is (LESS: outside the cube, s(r) = 0, no term). The node splits only with the eye inside
// the cube and every face inside the view's depth range (dnrt::eyeInsideOuterCube), so every pixel's view
// ray leaves the cube through exactly one face and every pixel is shaded once, by one of the two pipelines;
// the early depth test skips the other before its fragment shader runs (llvmpipe skips a group of lanes
// that all fail it, where a branch would run both sides). No culling: seen from inside, every face is a
// back face.
// The corners are q = ±outer in the object's frame, mapped to world by the inverse of the push block's
// worldToQ (the map the term's s(r) is evaluated with); each corner is computed the same way wherever it
// appears, so the triangles share their edges exactly (no pixel twice, none missed).
#include "frame.glsl"
#include "dnrt/dnrt.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
// probes.frag's push block from its DNRT record on (offset 48: after ProbePush).
layout(push_constant) uniform Push {
  layout(offset = 48) vec4 dnrtWorldToQ[3];
  vec4 dnrtCentreWorld;
  vec4 dnrtExtents;  // y: outer (units of R)
} pc;

void main() {
  const vec3 q = dnrtCubeCorner(gl_VertexIndex) * pc.dnrtExtents.y;
  // q = M r + t with M's rows the worldToQ rows' xyz, t their w: r = M⁻¹ (q − t).
  const mat3 m = transpose(mat3(pc.dnrtWorldToQ[0].xyz, pc.dnrtWorldToQ[1].xyz, pc.dnrtWorldToQ[2].xyz));
  const vec3 t = vec3(pc.dnrtWorldToQ[0].w, pc.dnrtWorldToQ[1].w, pc.dnrtWorldToQ[2].w);
  gl_Position = camera.viewProj * vec4(inverse(m) * (q - t), 1.0);
}
