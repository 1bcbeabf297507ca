// Colour transforms at the end of the frame. Internal radiance is linear HDR (Rec.709 primaries).
#ifndef BOUNCE_COLOR_GLSL
#define BOUNCE_COLOR_GLSL

// sRGB opto-electronic transfer function (IEC 61966-2-1). Applied by hand because the storage /
// attachment formats we write (RGBA8 UNORM) are not sRGB formats on every device.
vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// Khronos PBR Neutral tone mapper (Khronos 3D Commerce, 2024): leaves colours below ~0.76 almost
// untouched (base colours stay recognisable, which matters when judging colour bleeding) and
// compresses highlights towards white without hue shifts.
vec3 pbrNeutralTonemap(vec3 color) {
  const float startCompression = 0.8 - 0.04;
  const float desaturation = 0.15;
  float x = min(color.r, min(color.g, color.b));
  float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  color -= offset;
  float peak = max(color.r, max(color.g, color.b));
  if (peak < startCompression) return color;
  const float d = 1.0 - startCompression;
  float newPeak = 1.0 - d * d / (peak + d - startCompression);
  color *= newPeak / peak;
  float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
  return mix(color, vec3(newPeak), g);
}

#endif
