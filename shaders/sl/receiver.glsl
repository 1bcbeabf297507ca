// The receiver of SL pass 2's fragment shaders (sl, sl.shadow, and both in one walk): this pixel, or at
// half or quarter resolution the G-buffer pixel kStep·j it stands for (engine/gi/resolution.hpp),
// its world position p and normal n. False on the background (depth 1), where the pass writes 0. The
// includer declares camera (frame.glsl), gDepth, gNormal and the specialization constant kStep
// (G-buffer pixels per sample per axis: 1, 2 or 4).
#ifndef BOUNCE_SL_RECEIVER_GLSL
#define BOUNCE_SL_RECEIVER_GLSL
#include "upsample.glsl"  // reducedSamplePixel: the one mapping of a reduced sample to its G-buffer pixel
bool slReceiver(out ivec2 pixel, out vec3 p, out vec3 n) {
  pixel = kStep > 1u ? reducedSamplePixel(ivec2(gl_FragCoord.xy), int(kStep), ivec2(camera.resolution.xy)) : ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) return false;
  n = texelFetch(gNormal, pixel, 0).xyz;
  p = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  return true;
}
#endif
