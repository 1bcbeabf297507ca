// A 128-bit set (bit i % 32 of word i / 32: SL candidate lists, sl.glsl) walked lowest bit first in
// ONE loop. llvmpipe tests a loop's exit only after an iteration (README "What costs what on
// lavapipe"), so `for (w < 4) for (m = set[w]; m != 0; …)` runs n + 4 bodies for n set bits (a
// masked one per word, empty or not); `do { i = maskPop(rest); if (i < kMaskEmpty) … } while (rest
// != uvec4(0u))` runs max(n, 1), in the same order.
#ifndef BOUNCE_MASK_GLSL
#define BOUNCE_MASK_GLSL

const uint kMaskEmpty = 128u;

// The lowest set bit's index, cleared from `set`; kMaskEmpty when `set` is empty.
uint maskPop(inout uvec4 set) {
  uint i = kMaskEmpty;
  if (set.x != 0u) {
    i = uint(findLSB(set.x));
    set.x &= set.x - 1u;
  } else if (set.y != 0u) {
    i = 32u + uint(findLSB(set.y));
    set.y &= set.y - 1u;
  } else if (set.z != 0u) {
    i = 64u + uint(findLSB(set.z));
    set.z &= set.z - 1u;
  } else if (set.w != 0u) {
    i = 96u + uint(findLSB(set.w));
    set.w &= set.w - 1u;
  }
  return i;
}

#endif  // BOUNCE_MASK_GLSL
