#version 450
#extension GL_GOOGLE_include_directive : require
// DNRT box mode: one object's outer cube, so the fragment shader runs only on covered pixels.
// 36 vertices from gl_VertexIndex (12 triangles, outward CCW); the pipeline culls FRONT faces and
// tests them against the scene's depth without writing (GREATER_OR_EQUAL: the surface is not behind
// the cube's exit point), so every covered pixel inside the cube runs once, camera inside it or not.
// kFullScreen (the paper's mode): one full-screen triangle per object instead.
// Either way the object's record is read here, once per vertex, and reaches dnrt.frag as flat
// varyings (dnrt.glsl explains why); its k and a are applied per grid vertex by combine.comp.
#include "frame.glsl"
#include "dnrt/dnrt.glsl"

layout(constant_id = 1) const bool kFullScreen = false;

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(std430, set = 1, binding = 3) readonly buffer Objects { DnrtObject objects[]; };
layout(push_constant) uniform Push { uint object; } pc;

layout(location = 0) flat out vec4 outWorldToQ[3];
layout(location = 3) flat out vec4 outCentreWorld;
layout(location = 4) flat out vec4 outExtents;
layout(location = 5) flat out uint outSelf;

void main() {
  DnrtObject ob = objects[pc.object];
  outWorldToQ = ob.worldToQ;
  outCentreWorld = ob.centreWorld;
  outExtents = ob.extents;
  outSelf = ob.ids.x;
  if (kFullScreen) {
    vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
    return;
  }
  gl_Position = camera.viewProj * (ob.boxToWorld * vec4(dnrtCubeCorner(gl_VertexIndex), 1.0));
}
