// G-buffer layout (engine/render/passes/gbuffer_pass.*):
//   0 albedo    RGBA8_UNORM  rgb linear albedo (Lambertian reflectance), a 1 where geometry was drawn
//   1 normal    RGBA16F      xyz world-space unit normal (facing the viewer), w unused
//   2 emissive  RGBA16F      rgb emitted radiance (linear), w unused
//   3 entity    R32_UINT     entity id + 1 (0 = background)
//   depth       D32_SFLOAT   Vulkan depth 0..1
#ifndef BOUNCE_GBUFFER_GLSL
#define BOUNCE_GBUFFER_GLSL
const uint kBackgroundEntity = 0u;
#endif
