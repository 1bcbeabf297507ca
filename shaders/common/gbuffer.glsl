// G-buffer layout (engine/render/passes/gbuffer_pass.*):
//   0 albedo    RGBA8_UNORM  rgb linear albedo (Lambertian reflectance), a 1 where geometry was drawn
//   1 normal    RGBA16F      xyz world-space unit normal (facing the viewer), w the entity id + 1 as a
//                            float up to kEntityInNormalMax, kEntityInNormalMax + 1 for every larger id
//                            (so readers compare it only with ids + 1 ≤ kEntityInNormalMax: DNRT's self
//                            test reads it with the normal instead of a fourth G-buffer fetch)
//   2 emissive  RGBA16F      rgb emitted radiance (linear), w unused
//   3 entity    R32_UINT     entity id + 1 (0 = background)
//   depth       D32_SFLOAT   Vulkan depth 0..1
#ifndef BOUNCE_GBUFFER_GLSL
#define BOUNCE_GBUFFER_GLSL
const uint kBackgroundEntity = 0u;
// The largest entity id + 1 the normal's w holds (fp16 holds the integers to 2048 exactly; 2048 itself
// marks "larger"): engine/render/passes/gbuffer_pass.hpp kEntityInNormalMax.
const uint kEntityInNormalMax = 2047u;
#endif
