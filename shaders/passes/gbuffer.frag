#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer fill. glTF materials are treated as diffuse: albedo = baseColorFactor × baseColorTexture.
#include "frame.glsl"
#include "gbuffer.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
layout(set = 1, binding = 0) uniform sampler2D baseColorTex;  // sRGB format: sampled as linear
layout(set = 1, binding = 1) uniform sampler2D emissiveTex;
layout(push_constant) uniform Push { uint instance; } pc;

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec3 inWorld;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outEmissive;
layout(location = 3) out uint outEntity;

void main() {
  Instance inst = instances[pc.instance];
  vec3 albedo = inst.albedo.rgb;
  if (inst.albedo.a > 0.5) albedo *= texture(baseColorTex, inUv).rgb;
  vec3 emissive = inst.emissive.rgb;
  if (inst.emissive.a > 0.5) emissive *= texture(emissiveTex, inUv).rgb;
  // Two-sided shading: a surface seen from behind reflects with its normal flipped towards the eye.
  vec3 n = normalize(inNormal);
  if (dot(n, camera.position.xyz - inWorld) < 0.0) n = -n;
  outAlbedo = vec4(clamp(albedo, 0.0, 1.0), 1.0);
  // w: the entity id + 1, or kEntityInNormalMax + 1 for every larger one (gbuffer.glsl).
  outNormal = vec4(n, float(min(inst.ids.x + 1u, kEntityInNormalMax + 1u)));
  outEmissive = vec4(emissive, 0.0);
  outEntity = inst.ids.x + 1u;
}
