#!/usr/bin/env python3
"""How much of the reference's object effect on the indirect-only pixels is path-tracing noise.

`bounce accuracy` scores a technique's object effect on the indirect-only pixels (those the dynamic
objects neither cover nor shadow, game/accuracy.cpp indirectOnlyMask) as
    e = ||t - r|| / ||r||,   r = ref_with - ref_without,  t = tech_with - tech_without.
A reference of N samples per pixel carries noise n in r, so with r = r* + n (r* the converged
effect) and n independent of t:  e^2 = (||t - r*||^2 + ||n||^2) / (||r*||^2 + ||n||^2).
A perfect technique (t = r*) therefore scores sqrt(||n||^2 / ||r||^2), not 0: the floor.

||n||^2 is estimated the way `bounce accuracy` estimates its reference noise: the N/2-sample
reference is the first half of the N samples (sample s is drawn from index s), so
r_N - r_{N/2} = (second half - first half) / 2 has the variance of r_N's noise.

Inputs (linear PFMs, same size): the with/without references at N and N/2 spp and the direct-only
(bounces 0) pair that defines the mask, e.g. for cornell-1 (static level: the one `bounce accuracy`
wrote under <build>/cache/levels; every trace is served from the reference cache when present):
  bounce reference content/levels/cornell-1.json --spp 64 --out with64.pfm
  bounce reference <cache>/levels/cornell-1-<hash>-static.json --spp 64 --out without64.pfm
  (the same with --spp 32, and with --spp 1 --bounces 0)
  tools/effect_noise.py with64.pfm without64.pfm with32.pfm without32.pfm withd.pfm withoutd.pfm \
      --error dnrt=0.937 --spp-ratio 8 --error dnrt@512=0.763

--error NAME=E: a technique's indirect-only error against these references; printed: its error
against the converged effect, sqrt((e^2 (||r*||^2 + ||n||^2) - ||n||^2) / ||r*||^2).
--spp-ratio K with NAME@...=E: E was measured against a reference with K times the samples
(noise energy / K); the same inversion with that noise.
"""
import argparse
import sys

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    channels = 3 if kind == b"PF" else 1
    return data.reshape(height, width, channels).astype(np.float64)[::-1]  # PFM rows run bottom-up


def dilate3(mask):
    """3x3 dilation (indirectOnlyMask drops the pixels next to a covered or shadowed one)."""
    out = mask.copy()
    padded = np.pad(mask, 1)
    h, w = mask.shape
    for dy in range(3):
        for dx in range(3):
            out |= padded[dy:dy + h, dx:dx + w]
    return out


def distance_to(mask):
    """Euclidean distance (pixels) from every pixel to the nearest pixel of mask, brute force."""
    ys, xs = np.nonzero(mask)
    h, w = mask.shape
    gy, gx = np.mgrid[0:h, 0:w]
    gy, gx = gy.ravel(), gx.ravel()
    best = np.full(gy.size, np.inf)
    for k in range(0, gy.size, 2048):
        dy = gy[k:k + 2048, None] - ys[None, :]
        dx = gx[k:k + 2048, None] - xs[None, :]
        best[k:k + 2048] = np.sqrt((dy * dy + dx * dx).min(axis=1))
    return best.reshape(h, w)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    for name in ("with_full", "without_full", "with_half", "without_half", "with_direct", "without_direct"):
        p.add_argument(name)
    p.add_argument("--error", action="append", default=[], help="NAME=E or NAME@...=E (see --spp-ratio)")
    p.add_argument("--spp-ratio", type=float, default=1.0)
    a = p.parse_args()
    wf, of, wh, oh, wd, od = (read_pfm(x) for x in (a.with_full, a.without_full, a.with_half, a.without_half,
                                                     a.with_direct, a.without_direct))
    # indirectOnlyMask: the direct-only traces differ by more than 1e-4 relative, then 3x3 dilated.
    diff = np.abs(wd - od).max(axis=2)
    differs = diff > 1e-4 * (1.0 + np.maximum(wd.max(axis=2), od.max(axis=2)))
    indirect = ~dilate3(differs)
    effect, noise = wf - of, (wf - of) - (wh - oh)
    energy = lambda img, m: float((img[m] ** 2).sum())
    total, n2 = energy(effect, indirect), energy(noise, indirect)
    t2 = total - n2
    print(f"indirect-only pixels: {int(indirect.sum())} of {indirect.size} (covered or shadowed: {int(differs.sum())})")
    print(f"effect energy ||r||^2 = {total:.4g}; noise ||n||^2 = {n2:.4g} ({n2 / total:.1%}); converged ||r*||^2 = {t2:.4g}")
    if t2 <= 0:
        print("the effect is all noise at this sample count")
        return 0
    print(f"floor (a perfect technique's score against this reference): {np.sqrt(n2 / total):.3f}")
    k = a.spp_ratio
    print(f"floor against a reference with {k:g}x the samples: {np.sqrt((n2 / k) / (t2 + n2 / k)):.3f}")
    mean = effect[indirect].mean(axis=0)
    uniform = float((mean ** 2).sum()) * indirect.sum()
    print(f"a room-wide constant offset (the mean effect {np.array2string(mean, precision=4)}) is "
          f"{uniform / t2:.1%} of the converged effect energy")
    dist = distance_to(differs)
    for lo, hi in ((0, 8), (8, 24), (24, 64), (64, np.inf)):
        m = indirect & (dist >= lo) & (dist < hi)
        if not m.any():
            continue
        band, band_noise = energy(effect, m), energy(noise, m)
        print(f"  {lo:>3}-{hi:<4} px from a covered/shadowed pixel: {int(m.sum()):6d} px, converged effect energy "
              f"{(band - band_noise) / t2:6.1%}, noise {band_noise / band:5.1%} of the band's energy, mean effect "
              f"{effect[m].mean():+.4f}")
    for item in a.error:
        name, e = item.split("=")
        scale = k if "@" in name else 1.0
        nn = n2 / scale
        true2 = e_true = float(e) ** 2 * (t2 + nn) - nn
        e_true = np.sqrt(true2 / t2) if true2 > 0 else 0.0
        print(f"{name}: {float(e):.3f} against the reference -> {e_true:.3f} against the converged effect")
    return 0


if __name__ == "__main__":
    sys.exit(main())
