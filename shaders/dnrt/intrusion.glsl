// Intrusion test (paper §5.2.3): per object, the distance from o to the nearest OTHER surface in
// six 90° views (a cube map stored as a 6-layer 2D array, R32F). A receiver r gets the object's
// term only if nothing lies between o and r. Faces: +X, −X, +Y, −Y, +Z, −Z looking along F with
// glm::lookAt's frame (right = normalize(F × up), up' = right × F), engine/gi/dnrt/node.cpp builds
// the same matrices, so rendering and lookup share one mapping (no cube-face orientation tables).
#ifndef BOUNCE_DNRT_INTRUSION_GLSL
#define BOUNCE_DNRT_INTRUSION_GLSL

const vec3 kFaceForward[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1),
                                     vec3(0, 0, -1));
const vec3 kFaceUp[6] = vec3[6](vec3(0, -1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1), vec3(0, -1, 0),
                                vec3(0, -1, 0));

// Layer and texture coordinate of direction d (non-zero) from o.
vec3 intrusionCoord(vec3 d) {
  vec3 a = abs(d);
  int face = a.x >= a.y && a.x >= a.z ? (d.x >= 0.0 ? 0 : 1) : (a.y >= a.z ? (d.y >= 0.0 ? 2 : 3) : (d.z >= 0.0 ? 4 : 5));
  vec3 f = kFaceForward[face];
  vec3 right = normalize(cross(f, kFaceUp[face]));
  vec3 up = cross(right, f);
  float depth = dot(d, f);
  // glm::perspective(90°): x_ndc = x/depth, y_ndc = y/depth; Vulkan row 0 is y_ndc = −1.
  vec2 ndc = vec2(dot(d, right), dot(d, up)) / depth;
  return vec3(ndc * 0.5 + 0.5, float(face));
}

#endif
