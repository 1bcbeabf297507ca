// One RTF object's shading record (engine/gi/rtf/update.hpp RtfObjectGpu, std140, a uniform block
// read by rtf.vert, which passes it on as flat varyings).
struct RtfObject {
  vec4 toQ[3];        // rows: q = toQ · (p, 1), the field's offset from o in units of η
  vec4 toLocal[3];    // rows: world → object-frame orthonormal map (a reflection for a mirrored object, engine/gi/placement.hpp)
  vec4 centreWorld;   // xyz: o; w: the field's radius (outer + Δr)·η, or reach·η with a tail (m), the sphere rtf.vert covers
  vec4 grid;          // spheres, face size, inner, outer (η)
  uvec4 ids;          // x: entity + 1; y: SH count; z: the tail's reach (η, float bits; 0: none)
  uvec4 onObject[2];  // entity + 1 of the 8 other rtf objects nearest (0xFFFFFFFF: none): receivers on them read X's on-object variant (rtf.frag)
  vec4 blocked[144];  // [j·9 + i].rgb = Â_l(i)/π · T_ij: folded into X by the ξ pass (xi.comp), not read here
};
