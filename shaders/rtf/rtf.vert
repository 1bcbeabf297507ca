#version 450
#extension GL_GOOGLE_include_directive : require
// RTF shading (engine/gi/rtf/node.hpp): what covers the pixels whose receivers can lie in one
// object's field, the sphere of radius R = (outer + Δr)·η around o — or reach·η with a 1/|q|² tail
// (scene::Rtf::tail) — beyond which the field is zero.
// llvmpipe runs the fragment shader in full for every covered pixel, its early `discard`s included
// (DESIGN.md "What costs what"), so coverage is the cost: instead of the sphere's bounding box (its
// projection up to 2.2× the sphere's silhouette disc), a camera-facing octagon through o that
// circumscribes the silhouette cone — half-angle α, sin α = R/d at eye distance d — and covers
// exactly the pixels whose rays meet the sphere plus the octagon's corners (1.055× the disc). It is
// drawn without depth test or culling from gl_VertexIndex (18 vertices: a fan of 6 triangles, so
// each covered pixel runs once); with the eye inside the sphere, or close to it (d < 1.05 R, where
// the octagon grows without bound), one full-screen triangle instead.
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
layout(location = 7) flat out vec4 outFace;    // n_r, 1/(6 n_r), 1/n_r, 1/(14 · spheres): X's two variants of 7 texels
layout(location = 8) flat out vec4 outRange[7];
layout(location = 15) flat out uint outSelf;
layout(location = 16) flat out float outReach;  // the tail's end (η; 0: the end at r_N + Δr), ids.z
layout(location = 17) flat out uvec4 outOnObject[2];  // the other rtf objects' entity + 1 (rtf.frag's variant)

const int kCorners = 8;  // the octagon: 6 fan triangles, 18 vertices (node.cpp's draw)
// rtf.frag's kStep (the same specialization constant): below full resolution the draw covers the reduced
// target, ⌈size/step⌉, whose sample j shades G-buffer pixel step·j.
layout(constant_id = 2) const uint kStep = 1u;

void main() {
  outToQ = ob.toQ;
  outToLocal = ob.toLocal;
  float spheres = ob.grid.x, n = ob.grid.y, inner = ob.grid.z, outer = ob.grid.w;
  outRadial = vec4(inner, (spheres - 1.0) / (outer - inner), spheres - 1.0, outer);
  outFace = vec4(n, 1.0 / (6.0 * n), 1.0 / n, 1.0 / (14.0 * spheres));
  outRange = range;
  outSelf = ob.ids.x;
  outReach = uintBitsToFloat(ob.ids.z);
  outOnObject = ob.onObject;
  vec3 o = ob.centreWorld.xyz, toO = o - camera.position.xyz;
  float R = ob.centreWorld.w, d = length(toO);
  if (d < 1.05 * R) {
    // One triangle over the whole viewport (clip space), the others degenerate.
    int v = gl_VertexIndex;
    gl_Position = v < 3 ? vec4(v == 1 ? 3.0 : -1.0, v == 2 ? 3.0 : -1.0, 0.5, 1.0) : vec4(0.0, 0.0, 0.5, 1.0);
    return;
  }
  vec3 view = toO / d;
  vec3 u = normalize(cross(view, abs(view.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
  vec3 w = cross(view, u);
  // The silhouette cone meets the plane through o normal to `view` in a circle of radius d·tan α;
  // the octagon around it has circumradius that / cos(π/8).
  float radius = R * d / sqrt(d * d - R * R) / cos(3.14159265 / float(kCorners));
  int tri = gl_VertexIndex / 3, k = gl_VertexIndex % 3;
  int corner = k == 0 ? 0 : tri + k;
  float a = 6.28318531 * float(corner) / float(kCorners);
  gl_Position = camera.viewProj * vec4(o + radius * (cos(a) * u + sin(a) * w), 1.0);
  if (kStep > 1u) {
    // On the reduced target the rasteriser tests sample j at its own centre, j + ½ reduced pixels, but
    // the sample shades G-buffer pixel step·j, whose centre is step·j + ½ full pixels: up to (step − 1)/2
    // pixels apart, and the octagon touches the silhouette at its 8 tangent points. So the polygon is
    // moved into the reduced viewport by the affine map that takes full-resolution pixel coordinate x to
    // (x − ½)/step + ½ (per axis, in clip space: × w): each sample is covered exactly where its
    // G-buffer pixel would be at full resolution. The full-screen triangle above needs no map.
    vec2 full = camera.resolution.xy, reduced = ceil(full / float(kStep));
    vec2 scale = full / (float(kStep) * reduced);
    vec2 shift = (float(kStep) - 1.0) / (float(kStep) * reduced) - 1.0;
    gl_Position.xy = (gl_Position.xy + gl_Position.w) * scale + gl_Position.w * shift;
  }
}
