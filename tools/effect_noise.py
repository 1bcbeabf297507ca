#!/usr/bin/python3
"""How much of the reference's object effect on the indirect-only pixels is path-tracing noise.

`bounce accuracy` scores a technique's object effect on the indirect-only pixels (those the dynamic
objects neither cover nor shadow, game/accuracy.cpp indirectOnlyMask) as
    e = ||t - r|| / ||r||,   r = ref_with - ref_without,  t = tech_with - tech_without,
and since session 7 it estimates the reference's noise itself: accuracy.csv's indirect_noise_floor
and indirect_effect_rel_rmse_corrected (engine/ref/effect_noise.hpp derives them). This script reads
the same images from `bounce accuracy --effect-images --out DIR` (reference-<kind>-with|without.pfm,
the first-half references reference-<kind>-half-with|without.pfm, mask-indirect-only.pfm: one
definition of the mask, the C++ one) and prints the same floor, plus what the CSV does not hold:
the noise's share of the effect energy, a room-wide constant offset's share, the effect and noise by
distance from the covered/shadowed pixels, and corrected errors against a reference with more samples.

With r = r* + n (r* the converged effect) and n independent of t:
e^2 = (||t - r*||^2 + ||n||^2) / (||r*||^2 + ||n||^2). A perfect technique (t = r*) scores the floor
f = ||n|| / ||r||; ||n||^2 is estimated as ||r_N - r_{N/2}||^2 (the N/2-sample reference is the first
half of the N samples, so r_N - r_{N/2} = (second half - first half) / 2, which has the variance of
r_N's noise). Corrected error e* = ||t - r*|| / ||r*|| = sqrt((e^2 - f^2) / (1 - f^2)).

  bounce accuracy content/levels/cornell-1.json --rows dnrt --spp 64 --effect-images --out DIR
  tools/effect_noise.py DIR --error dnrt=0.937 --spp-ratio 8 --error dnrt@512=0.763

--kind K: the reference kind (default all; 1bounce for rows with ref=1bounce).
--error NAME=E: a technique's indirect-only error against these references; printed: its error
against the converged effect (= the CSV's indirect_effect_rel_rmse_corrected for a row of DIR).
--spp-ratio K with NAME@...=E: E was measured against a reference with K times the samples
(noise energy / K); the same inversion with that noise.
"""
import sys

import numpy as np

from tool_input import Arguments, BadInput, run


def read_pfm(path):
    """A PFM image (PF: RGB, Pf: grey) as float64 rows top-down; anything else is BadInput naming the file."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        if kind not in (b"PF", b"Pf"):
            raise BadInput(path, f"header {kind[:8]!r}", "a PFM image starting with PF or Pf")
        try:
            width, height = map(int, f.readline().split())
            scale = float(f.readline())
        except ValueError:
            raise BadInput(path, "a malformed size or scale line", "'W H' then a scale") from None
        channels = 3 if kind == b"PF" else 1
        if width <= 0 or height <= 0 or width * height > 1 << 28 or scale == 0:
            raise BadInput(path, f"size {width}x{height} scale {scale}", "a positive size under 2^28 pixels, scale != 0")
        raw = f.read(width * height * channels * 4 + 1)
    if len(raw) != width * height * channels * 4:
        raise BadInput(path, f"{len(raw)} bytes of pixels", f"{width * height * channels * 4} ({width}x{height}x{channels} floats)")
    data = np.frombuffer(raw, dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, channels).astype(np.float64)[::-1]  # PFM rows run bottom-up


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


def corrected(e, floor):
    """e* = sqrt(max(0, e^2 - f^2) / (1 - f^2)), as ref::noiseCorrectedError."""
    return float("nan") if floor >= 1 else np.sqrt(max(0.0, e * e - floor * floor) / (1 - floor * floor))


def main():
    p = Arguments(description=__doc__.split("\n")[0])
    p.add_argument("dir", help="a `bounce accuracy --effect-images --out DIR` folder")
    p.add_argument("--kind", default="all", help="reference kind (the rows' ref=...)")
    p.add_argument("--error", action="append", default=[], help="NAME=E or NAME@...=E (see --spp-ratio)")
    p.add_argument("--spp-ratio", type=float, default=1.0)
    a = p.parse_args()
    ref = lambda part: read_pfm(f"{a.dir}/reference-{a.kind}-{part}.pfm")
    wf, of, wh, oh = ref("with"), ref("without"), ref("half-with"), ref("half-without")
    indirect = read_pfm(f"{a.dir}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    effect, noise = wf - of, (wf - of) - (wh - oh)
    energy = lambda img, m: float((img[m] ** 2).sum())
    total, n2 = energy(effect, indirect), energy(noise, indirect)
    t2 = total - n2
    print(f"indirect-only pixels: {int(indirect.sum())} of {indirect.size}")
    print(f"effect energy ||r||^2 = {total:.4g}; noise ||n||^2 = {n2:.4g} ({n2 / total:.1%}); converged ||r*||^2 = {t2:.4g}")
    if t2 <= 0:
        print("the effect is all noise at this sample count")
        return 0
    floor = np.sqrt(n2 / total)
    print(f"floor (a perfect technique's score against this reference; accuracy.csv indirect_noise_floor): {floor:.4f}")
    k = a.spp_ratio
    print(f"floor against a reference with {k:g}x the samples: {np.sqrt((n2 / k) / (t2 + n2 / k)):.3f}")
    mean = effect[indirect].mean(axis=0)
    uniform = float((mean ** 2).sum()) * indirect.sum()
    print(f"a room-wide constant offset (the mean effect {np.array2string(mean, precision=4)}) is "
          f"{uniform / t2:.1%} of the converged effect energy")
    # Distance to the excluded pixels (covered or shadowed, dilated by one pixel as the mask is).
    dist = distance_to(~indirect)
    for lo, hi in ((0, 8), (8, 24), (24, 64), (64, np.inf)):
        m = indirect & (dist >= lo) & (dist < hi)
        if not m.any():
            continue
        band, band_noise = energy(effect, m), energy(noise, m)
        print(f"  {lo:>3}-{hi:<4} px from an excluded pixel: {int(m.sum()):6d} px, converged effect energy "
              f"{(band - band_noise) / t2:6.1%}, noise {band_noise / band:5.1%} of the band's energy, mean effect "
              f"{effect[m].mean():+.4f}")
    for item in a.error:
        name, e = item.split("=")
        if "@" in name:  # against a reference with k times the samples: its floor from the same energies
            f = np.sqrt((n2 / k) / (t2 + n2 / k))
        else:
            f = floor
        print(f"{name}: {float(e):.4f} against the reference -> {corrected(float(e), f):.4f} against the converged effect")
    return 0


if __name__ == "__main__":
    run(main, "tools/effect_noise.py DIR [--kind K] [--error NAME=E ...] [--spp-ratio K]", args=(1, None))
